// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Decoding an LZF block, the compression of PCD's binary_compressed body, without holding what it
// expands to. Internal: not installed.
//
// A compressed block can expand about 88-fold (a 3-byte back reference repeats up to 264 bytes),
// and a forged header can declare fields nobody reads: 22.8 MB of zeros declared 2 GB of points.
// The decoder keeps only the last kLzfWindow bytes it wrote, the farthest a back reference can
// reach, and hands the output on in pieces; the caller keeps what it reads (issue #61, finding 1).

#include <cstddef>
#include <functional>
#include <string>

namespace lmk::detail {

/// The farthest back an LZF back reference reaches: 13 bits of offset, plus one.
inline constexpr std::size_t kLzfWindow = 8192;

/// Receives the decoded bytes in order: `n` bytes that start at `position` of the output.
using LzfSink =
    std::function<void(std::size_t position, const unsigned char* bytes, std::size_t n)>;

/// Decodes `in_bytes` bytes of LZF that must expand to exactly `expected` bytes. Returns an empty
/// string when they do, else what is wrong: a literal run or a back reference cut off by the end
/// of the input, a back reference before the start of the output, or another length.
std::string decode_lzf_stream(const unsigned char* in, std::size_t in_bytes, std::size_t expected,
                              const LzfSink& sink);

}  // namespace lmk::detail
