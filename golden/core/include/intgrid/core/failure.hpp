// How golden code reports a broken precondition (std::invalid_argument) or a lost state
// (std::runtime_error). Builds without exceptions (the bare-metal target) stop the program
// instead: nothing there could catch the error, and a wrong result must not go on.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
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

// Throws std::invalid_argument "FIELD WHAT": how a configuration check names the field at fault
// by its path ("loops.window must be > 0").
[[noreturn]] inline void fail_field(const std::string& field, const std::string& what) {
  fail<std::invalid_argument>(field + " " + what);
}

// fail_field(field, what) unless ok.
inline void require_field(bool ok, const std::string& field, const std::string& what) {
  if (!ok) fail_field(field, what);
}

// A number as failure messages print it: six significant digits ("0.05", "1e+09").
inline std::string number_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace intgrid::core
