#include "mapfuse/core/param.hpp"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "mapfuse/core/param_check.hpp"

namespace mapfuse::param {

namespace {
std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", v);
  return text;
}
}  // namespace

bool Range::contains(double x) const {
  if (!std::isfinite(x)) return false;
  if (lo_open ? !(x > lo) : !(x >= lo)) return false;
  if (hi_open ? !(x < hi) : !(x <= hi)) return false;
  return true;
}

std::string Range::describe(const std::string& key) const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  if (key.empty()) return describe("x").substr(2);  // "in [0, 1]", "> 0"
  if (has_lo && has_hi)
    return key + " in " + (lo_open ? "(" : "[") + number(lo) + ", " + number(hi) +
           (hi_open ? ")" : "]");
  if (has_lo) return key + (lo_open ? " > " : " >= ") + number(lo);
  if (has_hi) return key + (hi_open ? " < " : " <= ") + number(hi);
  return key + " finite";
}

bool ListRule::contains(const std::vector<double>& values) const {
  if (values.size() < min_size || values.size() > max_size) return false;
  for (const double v : values)
    if (!each.contains(v)) return false;
  return true;
}

std::string ListRule::describe(const std::string& key) const {
  const std::string count = min_size == max_size
                                ? std::to_string(min_size)
                                : std::to_string(min_size) + " to " + std::to_string(max_size);
  return (key.empty() ? "" : key + ": ") + count + (max_size == 1 ? " value" : " values") +
         ", each " + each.describe("");
}

bool OneOf::contains(const std::string& s) const {
  for (const auto& n : names)
    if (n == s) return true;
  return false;
}

std::string OneOf::describe(const std::string& key) const {
  std::string text = key.empty() ? "one of " : key + " one of ";
  for (std::size_t i = 0; i < names.size(); ++i) text += (i ? ", " : "") + names[i];
  return text;
}

// The JSON library's own formatting, so that a message shows a value as the config file holds it
// (shortest round-trip digits, "1.0" for a whole double).
std::string showNumber(double value) {
  if (!std::isfinite(value)) return std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf");
  return nlohmann::json(value).dump();
}
std::string showNumber(int64_t value) {
  return nlohmann::json(value).dump();
}
std::string showNumber(uint64_t value) {
  return nlohmann::json(value).dump();
}
std::string showText(const std::string& value) {
  return nlohmann::json(value).dump();
}
std::string showList(const std::vector<double>& values) {
  std::string text = "[";
  for (std::size_t i = 0; i < values.size(); ++i) text += (i ? ", " : "") + showNumber(values[i]);
  return text + "]";
}

}  // namespace mapfuse::param
