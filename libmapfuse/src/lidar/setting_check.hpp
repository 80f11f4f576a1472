#pragma once
/// @file The check the LiDAR odometry's internal settings (not tool parameters) apply to
/// themselves: "<Owner>::<field> = <value>. Violated constraint: <rule>" (ConfigError).
#include <string>

#include "mapfuse/core/error.hpp"

namespace mapfuse::lidar::detail {

/// A checker of one settings struct, named in its messages.
struct SettingCheck {
  const char* owner;  ///< e.g. "OdometrySettings"

  /// @throws ConfigError naming the owner, the field, the value and the rule unless `ok`.
  void operator()(bool ok, const char* field, double value, const char* rule) const {
    if (!ok)
      throw ConfigError(std::string(owner) + "::" + field + " = " + std::to_string(value) +
                        ". Violated constraint: " + rule);
  }
};

}  // namespace mapfuse::lidar::detail
