#include "cli/progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace intgrid::cli {

TerminalProgress::TerminalProgress(std::string label)
    : label_(std::move(label)), enabled_(isatty(STDERR_FILENO) != 0) {}

TerminalProgress::~TerminalProgress() {
  if (shown_) std::fputc('\n', stderr);
}

void TerminalProgress::operator()(std::size_t done, std::size_t total) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  // Redraw at most every 100 ms, and always at the end.
  if (shown_ && done < total && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  shown_ = true;
  std::fprintf(stderr, "\r%s: %zu/%zu (%.0f%%)", label_.c_str(), done, total,
               total ? 100.0 * static_cast<double>(done) / static_cast<double>(total) : 100.0);
  std::fflush(stderr);
}

}  // namespace intgrid::cli
