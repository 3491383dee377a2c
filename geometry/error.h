#pragma once
// The one exception type of lmk. Library code throws it for bad input (a file, an argument, a
// setting); algorithm outcomes such as "nothing found" go in result structs instead.
// The message names the file or field, the problem and, where there is one, the fix.

#include <stdexcept>
#include <string>

namespace lmk {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace lmk
