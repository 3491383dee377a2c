// SPDX-License-Identifier: BSD-3-Clause
// Base64 for the report's data: URIs, against RFC 4648's examples.

#include "lmk/eval/detail/base64.h"

#include <gtest/gtest.h>

namespace lmk::detail {
namespace {

TEST(Base64, EncodesAsRfc4648) {
  EXPECT_EQ(base64(""), "");
  EXPECT_EQ(base64("M"), "TQ==");
  EXPECT_EQ(base64("Ma"), "TWE=");
  EXPECT_EQ(base64("Man"), "TWFu");
  EXPECT_EQ(base64("any carnal pleasure."), "YW55IGNhcm5hbCBwbGVhc3VyZS4=");
}

}  // namespace
}  // namespace lmk::detail
