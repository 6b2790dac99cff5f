// How golden code reports a broken precondition (std::invalid_argument) or a lost state
// (std::runtime_error). Builds without exceptions (the bare-metal target) stop the program
// instead: nothing there could catch the error, and a wrong result must not go on.
#pragma once

#include <cstdlib>
#include <string>

namespace intgrid::core {

template <class Error>
[[noreturn]] void fail(const std::string& what) {
#if defined(__cpp_exceptions)
  throw Error(what);
#else
  (void)what;
  std::abort();
#endif
}

}  // namespace intgrid::core
