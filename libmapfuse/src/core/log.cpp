#include "mapfuse/core/log.hpp"

#include <atomic>
#include <iostream>
#include <mutex>

namespace mapfuse {
namespace {
std::atomic<int> g_level{static_cast<int>(LogLevel::kInfo)};
std::mutex g_mutex;
const char* levelName(LogLevel l) {
  switch (l) {
    case LogLevel::kWarn: return "warn";
    case LogLevel::kDebug: return "debug";
    default: return "info";
  }
}
}  // namespace

void setLogLevel(LogLevel level) {
  g_level = static_cast<int>(level);
}
LogLevel logLevel() {
  return static_cast<LogLevel>(g_level.load());
}

void logMessage(LogLevel level, const std::string& message) {
  if (static_cast<int>(level) > g_level.load()) return;
  std::lock_guard<std::mutex> lock(g_mutex);
  std::cerr << "mapfuse[" << levelName(level) << "] " << message << '\n';
}

}  // namespace mapfuse
