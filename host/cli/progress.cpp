#include "cli/progress.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <utility>

#include "intgrid/io/text_io.hpp"

namespace intgrid::cli {

std::string human_duration(double seconds) {
  const long long s = std::isfinite(seconds) && seconds > 0.0 ? std::llround(seconds) : 0;
  if (s < 60) return io::printed("%lld s", s);
  if (s < 3600) return io::printed("%lld min %02lld s", s / 60, s % 60);
  return io::printed("%lld h %02lld min", s / 3600, (s % 3600) / 60);
}

std::string progress_text(const std::string& label, std::size_t done, std::size_t total,
                          double elapsed_seconds) {
  const double share = total ? static_cast<double>(done) / static_cast<double>(total) : 1.0;
  std::string text = io::printed("%s: %zu/%zu (%.0f%%)", label.c_str(), done, total, 100.0 * share);
  if (done >= total) return text + " in " + human_duration(elapsed_seconds);
  if (done == 0) return text + ", ETA ?";
  return text + ", ETA " +
         human_duration(elapsed_seconds * static_cast<double>(total - done) /
                        static_cast<double>(done));
}

TerminalProgress::TerminalProgress(std::string label)
    : label_(std::move(label)),
      enabled_(isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()) {}

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
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  // "\x1b[K" clears what a longer previous line left to the right.
  std::fprintf(stderr, "\r%s\x1b[K", progress_text(label_, done, total, elapsed).c_str());
  std::fflush(stderr);
}

}  // namespace intgrid::cli
