#include "progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace torte::lua {

std::string format_duration(double s) {
  char buf[64];
  if (!std::isfinite(s) || s < 0) return "?";
  if (s < 60) {
    std::snprintf(buf, sizeof buf, "%.1f s", s);
  } else if (s < 3600) {
    std::snprintf(buf, sizeof buf, "%d min %02d s", int(s) / 60, int(s) % 60);
  } else {
    std::snprintf(buf, sizeof buf, "%d h %02d min", int(s) / 3600, (int(s) / 60) % 60);
  }
  return buf;
}

ConsoleProgress::ConsoleProgress(std::string label, std::string rate_unit)
    : label_(std::move(label)), rate_unit_(std::move(rate_unit)), tty_(isatty(STDERR_FILENO)) {}

void ConsoleProgress::update(uint64_t done, uint64_t total, uint64_t rays, double elapsed) {
  std::unique_lock lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return;  // another thread is printing: skip, never block a worker
  const double fraction = total ? double(done) / double(total) : 1.0;
  const int percent = int(fraction * 100);
  // Terminal: redraw at most 10 times a second. Log/pipe: a line every 10 % or every 10 seconds, but nothing
  // for renders that finish within a second (the summary line follows anyway).
  const bool due = tty_ ? elapsed - last_print_ >= 0.1 || done == total
                        : elapsed >= 1 && (percent / 10 > last_percent_ / 10 || elapsed - last_print_ >= 10 ||
                                           done == total);
  if (!due || (done == total && last_percent_ == 100)) return;
  last_print_ = elapsed;
  last_percent_ = percent;
  const double mrays = elapsed > 0 ? double(rays) / elapsed * 1e-6 : 0;
  const double eta = fraction > 0 ? elapsed * (1 - fraction) / fraction : NAN;
  char line[256];
  if (tty_) {
    const int width = 30, filled = int(fraction * width);
    std::string bar(size_t(filled), '#');
    bar.append(size_t(width - filled), '-');
    std::snprintf(line, sizeof line, "\r%s [%s] %3d%%  %.2f %s  %s elapsed, ETA %s   ", label_.c_str(), bar.c_str(),
                  percent, mrays, rate_unit_.c_str(), format_duration(elapsed).c_str(),
                  format_duration(eta).c_str());
  } else {
    std::snprintf(line, sizeof line, "%s: %3d%%  %.2f %s  %s elapsed, ETA %s\n", label_.c_str(), percent, mrays,
                  rate_unit_.c_str(), format_duration(elapsed).c_str(), format_duration(eta).c_str());
  }
  std::fputs(line, stderr);
  std::fflush(stderr);
  printed_ = true;
}

void ConsoleProgress::finish() {
  std::lock_guard lock(mutex_);
  if (tty_ && printed_) std::fputs("\n", stderr);
}

}  // namespace torte::lua
