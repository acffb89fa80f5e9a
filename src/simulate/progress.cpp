// Progress bar of `simulate`.
#include "progress.h"

#include <unistd.h>

#include <cstdio>

namespace nonsmooth_sim::simulate {
namespace {

constexpr double kShowAfterSeconds = 1.0;  // runs shorter than this show no bar
constexpr int kBarWidth = 40;

}  // namespace

ProgressBar::ProgressBar(long total_steps, double duration, bool enabled)
    : total_steps_(total_steps),
      duration_(duration),
      active_(enabled && isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()) {}

void ProgressBar::Draw(long step) {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (elapsed < kShowAfterSeconds) return;
  const double fraction = static_cast<double>(step) / static_cast<double>(total_steps_);
  const int filled = static_cast<int>(fraction * kBarWidth);
  char bar[kBarWidth + 1];
  for (int k = 0; k < kBarWidth; ++k) bar[k] = k < filled ? '#' : ' ';
  bar[kBarWidth] = '\0';
  const double remaining = fraction > 0.0 ? elapsed * (1.0 / fraction - 1.0) : 0.0;
  std::fprintf(stderr, "\r[%s] %5.1f%%  t = %.3f / %.3f s  (%.0f s left)", bar, 100.0 * fraction,
               fraction * duration_, duration_, remaining);
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressBar::Finish() {
  if (!drawn_) return;
  std::fprintf(stderr, "\r%*s\r", kBarWidth + 60, "");
  std::fflush(stderr);
}

}  // namespace nonsmooth_sim::simulate
