#include "mapfuse/core/progress.hpp"

#include <unistd.h>

#include <cstdio>

#include "mapfuse/core/log.hpp"

namespace mapfuse {
namespace {
constexpr double kTtyRedrawSeconds = 0.1;
constexpr double kPlainLineSeconds = 5.0;
}  // namespace

Progress::Progress(std::string label, std::size_t total)
    : label_(std::move(label)),
      total_(total),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {
  tty_ = ::isatty(STDERR_FILENO) != 0;
  enabled_ = logLevel() >= LogLevel::kInfo;
}

Progress::~Progress() {
  finish();
}

void Progress::advance(std::size_t n) {
  done_ += n;
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_draw_).count();
  if (since < (tty_ ? kTtyRedrawSeconds : kPlainLineSeconds)) return;
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return;
  last_draw_ = now;
  draw(false);
}

void Progress::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return;
  finished_ = true;
  if (enabled_) draw(true);
}

void Progress::draw(bool final_line) {
  const std::size_t done = done_.load();
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double rate = elapsed > 0 ? done / elapsed : 0.0;
  const double eta = (rate > 0 && total_ > done) ? (total_ - done) / rate : 0.0;
  char line[256];
  if (tty_ && total_ > 0) {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(kWidth * std::min<double>(1.0, double(done) / total_));
    std::string bar(filled, '#');
    bar.resize(kWidth, '.');
    std::snprintf(line, sizeof line, "\r%s [%s] %zu/%zu %.1f/s ETA %.0fs ", label_.c_str(),
                  bar.c_str(), done, total_, rate, eta);
    std::fputs(line, stderr);
    if (final_line) std::fputs("\n", stderr);
  } else {
    if (total_ > 0)
      std::snprintf(line, sizeof line, "mapfuse[progress] %s %zu/%zu (%.1f/s, %s %.0fs)\n",
                    label_.c_str(), done, total_, rate, final_line ? "took" : "ETA",
                    final_line ? elapsed : eta);
    else
      std::snprintf(line, sizeof line, "mapfuse[progress] %s %zu (%.1f/s)\n", label_.c_str(), done,
                    rate);
    std::fputs(line, stderr);
  }
  std::fflush(stderr);
}

}  // namespace mapfuse
