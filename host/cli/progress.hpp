// Progress of a long run on a terminal: one line rewritten in place on stderr,
// silent when stderr is not a terminal (CI logs, pipes).
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace intgrid::cli {

class TerminalProgress {
 public:
  explicit TerminalProgress(std::string label);
  ~TerminalProgress();
  void operator()(std::size_t done, std::size_t total);

 private:
  std::string label_;
  bool enabled_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace intgrid::cli
