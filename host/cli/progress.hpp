// Progress of a long run on a terminal: one line rewritten in place on stderr, with the time
// left estimated from the pace so far, silent when stderr is not a terminal (CI logs, pipes).
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
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_;
};

// The progress line's text: "LABEL: DONE/TOTAL (P%), ETA 2 min 05 s" while running (the time
// left at the pace of the elapsed seconds so far; "ETA ?" before the first step), and "LABEL:
// TOTAL/TOTAL (100%) in 12 s" once done.
std::string progress_text(const std::string& label, std::size_t done, std::size_t total,
                          double elapsed_seconds);

// A duration for people: "45 s", "3 min 05 s", "2 h 07 min".
std::string human_duration(double seconds);

}  // namespace intgrid::cli
