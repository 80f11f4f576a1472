#pragma once
/// @file Progress of long work on stderr: a bar with rate and ETA on a TTY, a plain line
/// every few seconds otherwise, nothing when the log level is quiet. Thread-safe.
#include <atomic>
#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

namespace mapfuse {

class Progress {
 public:
  /// @param label what is counted ("frames", "pairs"); @param total expected count (0 = unknown).
  Progress(std::string label, std::size_t total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// @brief Adds n finished items and redraws when due.
  void advance(std::size_t n = 1);
  /// @brief Prints the final line (also called by the destructor).
  void finish();

 private:
  void draw(bool final_line);
  std::string label_;
  std::size_t total_;
  std::atomic<std::size_t> done_{0};
  std::chrono::steady_clock::time_point start_, last_draw_;
  std::mutex mutex_;
  bool tty_ = false;
  bool enabled_ = true;
  bool finished_ = false;
};

}  // namespace mapfuse
