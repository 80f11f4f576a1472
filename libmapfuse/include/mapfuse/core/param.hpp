#pragma once
/// @file The vocabulary of parameter declarations. Every parameter is declared once, in the
/// `visit` member of the Settings struct that owns its field, with its key, unit, help and rule:
///
///   double voxel_size = 0.25;  ///< m
///   template <class V> void visit(V& v) {
///     v("voxel_size", voxel_size, "m", "voxel edge", param::gt(0) & param::le(100));
///     v("method", method, "", "icp | sgicp", kMethodNames);        // enum: param::Names
///     v("partner_choice", choice, "", "overlap | spread", param::oneOf({"overlap", "spread"}));
///     v("use_labels", use_labels, "", "match within a class only");  // bool or free text
///     v("pyramid", pyramid, "m", "per level", param::listOf(1, 5, param::gt(0)));  // numbers
///     v.relation("coarse_bin", coarse_bin, coarse_bin < coarse_radius, "< coarse_radius");
///   }
///
/// Numbers always carry a Range (finite values only; integers are range-checked before they are
/// narrowed). The visitors in mapfuse/core/param_check.hpp (validation, for any area's
/// settings), mapfuse/cli/params.hpp and mapfuse/cli/app.hpp turn that one list into the
/// command-line options, the config-file reader, validation and the resolved config, so
/// a parameter's name, default and rule cannot drift apart. Ceres names its rules the same way
/// (`OPTION_GE(max_num_iterations, 0)`).
#include <cstddef>
#include <initializer_list>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace mapfuse::param {

/// A numeric rule: the value lies between `lo` and `hi`, each end open or closed.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;

  /// @brief True when `x` is finite and inside the range.
  bool contains(double x) const;
  /// @brief "voxel_size in (0, 100]", "min_overlap in [0, 1]", "max_iterations >= 1"; without a
  /// key: "in (0, 100]".
  std::string describe(const std::string& key) const;
};

/// @brief x > v
constexpr Range gt(double v) {
  return {v, std::numeric_limits<double>::infinity(), true, false};
}
/// @brief x >= v
constexpr Range ge(double v) {
  return {v, std::numeric_limits<double>::infinity(), false, false};
}
/// @brief x < v
constexpr Range lt(double v) {
  return {-std::numeric_limits<double>::infinity(), v, false, true};
}
/// @brief x <= v
constexpr Range le(double v) {
  return {-std::numeric_limits<double>::infinity(), v, false, false};
}
/// @brief lo <= x <= hi
constexpr Range in(double lo, double hi) {
  return {lo, hi, false, false};
}
/// @brief Both rules: the tighter end of each side.
constexpr Range operator&(const Range& a, const Range& b) {
  Range r = a;
  if (b.lo > r.lo || (b.lo == r.lo && b.lo_open)) {
    r.lo = b.lo;
    r.lo_open = b.lo_open;
  }
  if (b.hi < r.hi || (b.hi == r.hi && b.hi_open)) {
    r.hi = b.hi;
    r.hi_open = b.hi_open;
  }
  return r;
}

/// A list of numbers (std::vector<double>): how many values, and the range of each. The command
/// line takes them comma-separated (`--pyramid-distances 1.5,0.75`), a config file as an array.
struct ListRule {
  std::size_t min_size = 1;
  std::size_t max_size = 1;
  Range each;

  /// @brief True when the size is allowed and every value lies in `each`.
  bool contains(const std::vector<double>& values) const;
  /// @brief "class_weights: 7 values, each in [0, 1000]"; "pyramid_distances: 1 to 5 values, each
  /// in (0, 100]"; without a key the same text without "key: ".
  std::string describe(const std::string& key) const;
};
/// @brief min_size..max_size values, each inside `each`.
constexpr ListRule listOf(std::size_t min_size, std::size_t max_size, const Range& each) {
  return {min_size, max_size, each};
}

/// A text parameter that takes one of a few names.
struct OneOf {
  std::vector<std::string> names;
  bool contains(const std::string& s) const;
  std::string describe(
      const std::string& key) const;  ///< "method one of icp, sgicp"; no key: "one of ..."
};
inline OneOf oneOf(std::initializer_list<const char*> names) {
  return OneOf{std::vector<std::string>(names.begin(), names.end())};
}

/// Names of an enum parameter's values (what configs and the command line use).
template <class E>
struct Names {
  std::vector<std::pair<const char*, E>> entries;

  const char* nameOf(E value) const {
    for (const auto& [n, e] : entries)
      if (e == value) return n;
    return "?";
  }
  bool find(const std::string& name, E* value) const {
    for (const auto& [n, e] : entries)
      if (name == n) {
        *value = e;
        return true;
      }
    return false;
  }
  OneOf oneOf() const {
    OneOf o;
    for (const auto& entry : entries) o.names.emplace_back(entry.first);
    return o;
  }
};

/// A rule on a text parameter that a function decides (e.g. "lat,lon,alt").
struct TextRule {
  bool (*ok)(const std::string&);
  const char* text;  ///< what a valid value looks like
};

}  // namespace mapfuse::param
