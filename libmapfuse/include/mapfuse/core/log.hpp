#pragma once
/// @file Log levels on stderr. stdout is reserved for results (shell pipelines).
#include <sstream>
#include <string>

namespace mapfuse {

enum class LogLevel : int { kQuiet = 0, kWarn = 1, kInfo = 2, kDebug = 3 };

/// @brief Sets the process-wide level (apps: --quiet -> kQuiet, default kInfo, -v -> kDebug).
void setLogLevel(LogLevel level);
LogLevel logLevel();

/// @brief Writes "mapfuse[<level>] message" to stderr when level <= the current level.
void logMessage(LogLevel level, const std::string& message);

}  // namespace mapfuse

#define MAPFUSE_LOG(level, expr)                                              \
  do {                                                                        \
    if (static_cast<int>(level) <= static_cast<int>(::mapfuse::logLevel())) { \
      std::ostringstream mapfuse_log_ss_;                                     \
      mapfuse_log_ss_ << expr;                                                \
      ::mapfuse::logMessage(level, mapfuse_log_ss_.str());                    \
    }                                                                         \
  } while (0)
#define MAPFUSE_INFO(expr) MAPFUSE_LOG(::mapfuse::LogLevel::kInfo, expr)
#define MAPFUSE_WARN(expr) MAPFUSE_LOG(::mapfuse::LogLevel::kWarn, expr)
#define MAPFUSE_DEBUG(expr) MAPFUSE_LOG(::mapfuse::LogLevel::kDebug, expr)
