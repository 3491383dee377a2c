// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/search_method.h"

#include "lmk/geometry/error.h"
#include "lmk/search/detail/reference_search.h"
#include "lmk/search/fast/fast_search.h"

namespace lmk::detail {

const SearchMethodSteps& search_method_steps(SearchMethod method) {
  switch (method) {
    case SearchMethod::fast:
      return fast_search_steps();
    case SearchMethod::reference:
      return reference_search_steps();
  }
  throw Error("find: unknown search method " + std::to_string(static_cast<int>(method)));
}

}  // namespace lmk::detail
