#pragma once
/// @file The XML side of the OpenDRIVE reader (private to libmapfuse/src/io; io/opendrive.hpp):
/// attribute reading with the file and element named in every error, the reading policy's
/// clamps and warnings (docs/formats.md "Map content checks"), and one road's records.
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <pugixml.hpp>
#include <string>
#include <utility>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/bounds.hpp"
#include "mapfuse/io/opendrive.hpp"

namespace mapfuse::io::detail {

/// m: lateral offsets (t), heights above the road and sizes of signals and objects; a road is
/// never wider, a sign never bigger.
constexpr double kMaxOffset = 1e3;

/// Reads the attributes of one element; errors name the file and the element's path.
class Reader {
 public:
  Reader(const std::string& file, std::string where, InputWarnings* warnings)
      : file_(file), where_(std::move(where)), warnings_(warnings) {}

  double number(const pugi::xml_node& n, const char* attr) const {
    const pugi::xml_attribute a = n.attribute(attr);
    if (!a) fail(std::string(n.name()) + "@" + attr, "missing");
    return parse(n, attr, a.value());
  }
  double number(const pugi::xml_node& n, const char* attr, double fallback) const {
    const pugi::xml_attribute a = n.attribute(attr);
    return a ? parse(n, attr, a.value()) : fallback;
  }
  /// A required number within [lo, hi].
  double bounded(const pugi::xml_node& n, const char* attr, double lo, double hi) const {
    return check(n, attr, number(n, attr), lo, hi);
  }
  /// An optional number within [lo, hi].
  double bounded(const pugi::xml_node& n, const char* attr, double fallback, double lo,
                 double hi) const {
    return check(n, attr, number(n, attr, fallback), lo, hi);
  }
  int integer(const pugi::xml_node& n, const char* attr) const {
    const double v = number(n, attr);
    if (v != std::floor(v) || std::abs(v) > 1e9)
      fail(std::string(n.name()) + "@" + attr, "'" + text(n, attr) + "' is not an integer");
    return static_cast<int>(v);
  }
  static std::string text(const pugi::xml_node& n, const char* attr) {
    return n.attribute(attr).value();
  }
  /// A position along a road (`s`, `sOffset`; `fallback` when optional, NaN when required):
  /// at most kMaxOdrRoadLength; a negative one (survey maps write road marks from sOffset -4.6)
  /// is clamped to 0 with a warning (docs/formats.md "Map content checks").
  double along(const pugi::xml_node& n, const char* attr, double fallback = NAN) const {
    const double v = std::isnan(fallback) ? number(n, attr) : number(n, attr, fallback);
    if (v < 0.0 && v >= -bounds::kMaxOdrRoadLength) {
      warnings_->add(std::string(n.name()) + "@" + attr + " negative (clamped to 0)",
                     file_ + ": " + where_ + " " + n.name() + "@" + attr + "=" + text(n, attr));
      return 0.0;
    }
    return check(n, attr, v, 0.0, bounds::kMaxOdrRoadLength);
  }
  /// A cubic record: its start within a road, coefficients finite (the evaluated points are
  /// checked against the coordinate bound by sim/opendrive_world.cpp).
  OdrPoly3 poly(const pugi::xml_node& n, const char* s_attr) const {
    return {along(n, s_attr), number(n, "a"), number(n, "b"), number(n, "c"), number(n, "d")};
  }
  InputWarnings* warnings() const { return warnings_; }
  const std::string& file() const { return file_; }
  /// Where a signal or object stands on its road: s, t, zOffset and the heading attribute
  /// `heading` (a signal's hOffset, an object's hdg), read in that order.
  std::tuple<double, double, double, double> placement(const pugi::xml_node& n,
                                                       const char* heading) const {
    const double s = along(n, "s");
    const double t = bounded(n, "t", -kMaxOffset, kMaxOffset);
    const double z = bounded(n, "zOffset", 0.0, -kMaxOffset, kMaxOffset);
    return {s, t, z, bounded(n, heading, 0.0, -bounds::kMaxAngle, bounds::kMaxAngle)};
  }
  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw ParseError(file_, where_ + (field.empty() ? "" : " " + field), problem);
  }
  double check(const pugi::xml_node& n, const char* attr, double v, double lo, double hi) const {
    if (!bounds::within(v, lo, hi))
      fail(std::string(n.name()) + "@" + attr,
           "'" + text(n, attr) + "' is outside " + bounds::rangeText(lo, hi));
    return v;
  }

 private:
  double parse(const pugi::xml_node& n, const char* attr, const char* s) const {
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE || !std::isfinite(v))
      fail(std::string(n.name()) + "@" + attr, std::string("'") + s + "' is not a number");
    return v;
  }
  const std::string& file_;
  std::string where_;
  InputWarnings* warnings_;
};

/// @brief One <road>: its plan view, elevation, lanes, signals and objects, read by the policy.
OdrRoad readRoad(const pugi::xml_node& r, const std::string& file, InputWarnings* warnings);

}  // namespace mapfuse::io::detail
