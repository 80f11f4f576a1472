#pragma once
/// @file The check of a Settings struct's declarations (mapfuse/core/param.hpp): every rule of
/// its `visit` applied to the values it holds, the first violation a ConfigError (exit 2)
/// "<Owner>::<key> = <value>. Violated constraint: <rule>" (the message of Ceres'
/// `OPTION_GE`). It sits in core so that any area can check its own settings, also those that
/// are no tool's parameters (the LiDAR odometry's); the command-line and config-file side of
/// the same declarations is mapfuse/cli/params.hpp.
#include <cmath>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/param.hpp"

namespace mapfuse::param {

template <class T>
constexpr bool kIsNumber = std::is_arithmetic_v<T> && !std::is_same_v<T, bool>;

/// @brief "-1.0", "30", "true", "\"spread\"", "nan": a value as it reads in a JSON config file.
std::string showNumber(double value);
std::string showNumber(int64_t value);
std::string showNumber(uint64_t value);
std::string showText(const std::string& value);
std::string showList(const std::vector<double>& values);  ///< "[1.5, 0.75]"

/// @brief Any declared value as it reads in a config file (see showNumber).
template <class T>
std::string showValue(const T& value) {
  if constexpr (std::is_same_v<T, bool>) {
    return value ? "true" : "false";
  } else if constexpr (std::is_floating_point_v<T>) {
    return showNumber(static_cast<double>(value));
  } else if constexpr (std::is_integral_v<T> && std::is_signed_v<T>) {
    return showNumber(static_cast<int64_t>(value));
  } else if constexpr (std::is_integral_v<T>) {
    return showNumber(static_cast<uint64_t>(value));
  } else if constexpr (std::is_same_v<T, std::vector<double>>) {
    return showList(value);
  } else {
    return showText(value);
  }
}

/// Checks every rule of a `visit`; the first violation throws "<Owner>::<key> = <value>.
/// Violated constraint: <rule>".
struct ValidateVisitor {
  const char* owner;

  [[noreturn]] void fail(const char* key, const std::string& value, const std::string& rule) {
    throw ConfigError(std::string(owner) + "::" + key + " = " + value +
                      ". Violated constraint: " + rule);
  }
  template <class T>
  void operator()(const char* key, T& value, const char*, const char*, const Range& range) {
    static_assert(kIsNumber<T>, "a Range rules numbers");
    if (!range.contains(static_cast<double>(value)))
      fail(key, showValue(value), range.describe(key));
  }
  /// bool and free text have no rule; a number without one must still be finite.
  template <class T>
  void operator()(const char* key, T& value, const char*, const char*) {
    if constexpr (std::is_floating_point_v<T>)
      if (!std::isfinite(value)) fail(key, showValue(value), std::string(key) + " finite");
  }
  void operator()(const char* key, std::string& value, const char*, const char*,
                  const OneOf& names) {
    if (!names.contains(value)) fail(key, showValue(value), names.describe(key));
  }
  void operator()(const char* key, std::string& value, const char*, const char*,
                  const TextRule& rule) {
    if (!rule.ok(value)) fail(key, showValue(value), rule.text);
  }
  void operator()(const char* key, std::vector<double>& values, const char*, const char*,
                  const ListRule& rule) {
    if (!rule.contains(values)) fail(key, showList(values), rule.describe(key));
  }
  template <class E>
  void operator()(const char*, E&, const char*, const char*, const Names<E>&) {}
  template <class T>
  void relation(const char* key, const T& value, bool ok, const char* rule) {
    if (!ok) fail(key, showValue(value), std::string(key) + " " + rule);
  }
};

/// @brief Checks every rule `settings.visit` declares (numbers finite and in range, names
/// known, relations).
/// @throws ConfigError "<owner>::<key> = <value>. Violated constraint: <rule>"; `owner` is
/// Settings::kName unless given.
template <class Settings>
void validate(const Settings& settings, const char* owner = Settings::kName) {
  Settings copy = settings;
  ValidateVisitor v{owner};
  copy.visit(v);
}

}  // namespace mapfuse::param
