#include "mapfuse/io/opendrive.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <pugixml.hpp>
#include <set>
#include <tuple>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/bounds.hpp"
#include "xml_root.hpp"

namespace mapfuse::io {

namespace {

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

std::optional<OdrLink> readLink(const pugi::xml_node& n) {
  if (!n) return std::nullopt;
  return OdrLink{n.attribute("elementType").value(), n.attribute("elementId").value(),
                 n.attribute("contactPoint").value()};
}

OdrGeometry readGeometry(const pugi::xml_node& g, const Reader& R) {
  OdrGeometry geo;
  using bounds::kMaxCoordinate, bounds::kMaxOdrRoadLength, bounds::kMaxCurvature;
  geo.s = R.along(g, "s");
  geo.x = R.bounded(g, "x", -kMaxCoordinate, kMaxCoordinate);
  geo.y = R.bounded(g, "y", -kMaxCoordinate, kMaxCoordinate);
  geo.hdg = R.bounded(g, "hdg", -bounds::kMaxAngle, bounds::kMaxAngle);
  geo.length = R.bounded(g, "length", 0.0, kMaxOdrRoadLength);
  const pugi::xml_node k = g.first_child();
  const std::string kind = k.name();
  if (kind == "line") {
    geo.kind = OdrGeometry::Kind::kLine;
  } else if (kind == "arc") {
    geo.kind = OdrGeometry::Kind::kArc;
    geo.curvature = R.bounded(k, "curvature", -kMaxCurvature, kMaxCurvature);
  } else if (kind == "spiral") {
    geo.kind = OdrGeometry::Kind::kSpiral;
    geo.curv_start = R.bounded(k, "curvStart", -kMaxCurvature, kMaxCurvature);
    geo.curv_end = R.bounded(k, "curvEnd", -kMaxCurvature, kMaxCurvature);
  } else if (kind == "poly3") {
    geo.kind = OdrGeometry::Kind::kPoly3;
    geo.a = R.number(k, "a");
    geo.b = R.number(k, "b");
    geo.c = R.number(k, "c");
    geo.d = R.number(k, "d");
  } else if (kind == "paramPoly3") {
    geo.kind = OdrGeometry::Kind::kParamPoly3;
    geo.au = R.number(k, "aU");
    geo.bu = R.number(k, "bU");
    geo.cu = R.number(k, "cU");
    geo.du = R.number(k, "dU");
    geo.av = R.number(k, "aV");
    geo.bv = R.number(k, "bV");
    geo.cv = R.number(k, "cV");
    geo.dv = R.number(k, "dV");
    const std::string range = k.attribute("pRange").value();
    if (range != "" && range != "normalized" && range != "arcLength")
      R.fail("paramPoly3@pRange", "'" + range + "' is not normalized or arcLength");
    geo.p_normalized = range != "arcLength";
  } else {
    R.fail("geometry", "unknown geometry '" + kind + "' (line, arc, spiral, poly3, paramPoly3)");
  }
  return geo;
}

OdrLane readLane(const pugi::xml_node& l, const Reader& road_reader, const std::string& where) {
  OdrLane lane;
  lane.id = road_reader.integer(l, "id");
  const Reader R(road_reader.file(), where + " lane " + std::to_string(lane.id),
                 road_reader.warnings());
  lane.type = l.attribute("type").value();
  if (l.child("border")) R.fail("border", "lane borders are not supported (give lane widths)");
  for (const pugi::xml_node w : l.children("width")) lane.widths.push_back(R.poly(w, "sOffset"));
  for (const pugi::xml_node m : l.children("roadMark")) {
    OdrRoadMark mark;
    mark.s_offset = R.along(m, "sOffset");
    mark.type = m.attribute("type").value();
    mark.color = m.attribute("color").value();
    mark.width = R.bounded(m, "width", 0.12, 0.0, 1e3);
    lane.marks.push_back(mark);
  }
  if (const pugi::xml_node link = l.child("link")) {
    if (const pugi::xml_node p = link.child("predecessor")) lane.predecessor = R.integer(p, "id");
    if (const pugi::xml_node s = link.child("successor")) lane.successor = R.integer(s, "id");
  }
  auto bySOffset = [](const auto& x, const auto& y) { return x.s < y.s; };
  std::stable_sort(lane.widths.begin(), lane.widths.end(), bySOffset);
  std::stable_sort(
      lane.marks.begin(), lane.marks.end(),
      [](const OdrRoadMark& x, const OdrRoadMark& y) { return x.s_offset < y.s_offset; });
  return lane;
}

OdrLaneSection readLaneSection(const pugi::xml_node& sec, const Reader& R,
                               const std::string& where) {
  OdrLaneSection section;
  section.s = R.along(sec, "s");
  const std::string sw = where + " laneSection s=" + Reader::text(sec, "s");
  const Reader RS(R.file(), sw, R.warnings());
  for (const char* side : {"left", "center", "right"})
    for (const pugi::xml_node l : sec.child(side).children("lane")) {
      section.lanes.push_back(readLane(l, RS, sw));
      if (section.lanes.size() > static_cast<std::size_t>(2 * bounds::kMaxOdrLanesPerSection + 1))
        RS.fail("lane",
                "more than " + std::to_string(2 * bounds::kMaxOdrLanesPerSection + 1) + " lanes");
      for (std::size_t k = 0; k + 1 < section.lanes.size(); ++k)
        if (section.lanes[k].id == section.lanes.back().id)
          RS.fail("lane@id", "lane id " + std::to_string(section.lanes.back().id) +
                                 " appears twice in the section");
    }
  return section;
}

OdrSignal readSignal(const pugi::xml_node& s, const Reader& R, const std::string& where) {
  OdrSignal sig;
  sig.id = s.attribute("id").value();
  sig.name = s.attribute("name").value();
  const Reader RS(R.file(), where + " signal " + sig.id, R.warnings());
  std::tie(sig.s, sig.t, sig.z_offset, sig.h_offset) = RS.placement(s, "hOffset");
  sig.height = RS.bounded(s, "height", 0.0, 0.0, bounds::kMaxElementHeight);
  sig.width = RS.bounded(s, "width", 0.0, 0.0, kMaxOffset);
  sig.type = s.attribute("type").value();
  sig.subtype = s.attribute("subtype").value();
  sig.country = s.attribute("country").value();
  sig.orientation = s.attribute("orientation").value();
  sig.dynamic = std::string(s.attribute("dynamic").value()) == "yes";
  return sig;
}

OdrObject readObject(const pugi::xml_node& o, const Reader& R, const std::string& where) {
  OdrObject obj;
  obj.id = o.attribute("id").value();
  obj.name = o.attribute("name").value();
  obj.type = o.attribute("type").value();
  const Reader RO(R.file(), where + " object " + obj.id, R.warnings());
  std::tie(obj.s, obj.t, obj.z_offset, obj.hdg) = RO.placement(o, "hdg");
  obj.length = RO.bounded(o, "length", 0.0, 0.0, kMaxOffset);
  obj.width = RO.bounded(o, "width", 0.0, 0.0, kMaxOffset);
  obj.height = RO.bounded(o, "height", 0.0, 0.0, bounds::kMaxElementHeight);
  obj.radius = RO.bounded(o, "radius", 0.0, 0.0, kMaxOffset);
  pugi::xml_node outline = o.child("outline");
  if (!outline) outline = o.child("outlines").child("outline");
  for (const pugi::xml_node c : outline.children()) {
    const std::string kind = c.name();
    if (kind == "cornerLocal")
      obj.outline.push_back({RO.bounded(c, "u", -kMaxOffset, kMaxOffset),
                             RO.bounded(c, "v", -kMaxOffset, kMaxOffset),
                             RO.bounded(c, "z", 0.0, -kMaxOffset, kMaxOffset), false});
    else if (kind == "cornerRoad")
      obj.outline.push_back({RO.along(c, "s", 0.0), RO.bounded(c, "t", -kMaxOffset, kMaxOffset),
                             RO.bounded(c, "dz", 0.0, -kMaxOffset, kMaxOffset), true});
  }
  return obj;
}

OdrRoad readRoad(const pugi::xml_node& r, const std::string& file, InputWarnings* warnings) {
  OdrRoad road;
  road.id = r.attribute("id").value();
  const std::string where = "road " + road.id;
  const Reader R(file, where, warnings);
  if (road.id.empty()) R.fail("road@id", "missing");
  road.name = r.attribute("name").value();
  road.junction = r.attribute("junction").as_string("-1");
  road.length = R.bounded(r, "length", 0.0, bounds::kMaxOdrRoadLength);
  if (const std::string rule = r.attribute("rule").value(); !rule.empty()) road.rule = rule;
  if (road.rule != "RHT" && road.rule != "LHT")
    R.fail("road@rule", "'" + road.rule + "' is not RHT or LHT");
  road.predecessor = readLink(r.child("link").child("predecessor"));
  road.successor = readLink(r.child("link").child("successor"));
  for (const pugi::xml_node g : r.child("planView").children("geometry"))
    road.plan_view.push_back(readGeometry(g, R));
  if (road.plan_view.empty()) R.fail("planView", "no geometry");
  for (const pugi::xml_node e : r.child("elevationProfile").children("elevation"))
    road.elevation.push_back(R.poly(e, "s"));
  for (const pugi::xml_node e : r.child("lateralProfile").children("superelevation"))
    road.superelevation.push_back(R.poly(e, "s"));
  const pugi::xml_node lanes = r.child("lanes");
  for (const pugi::xml_node o : lanes.children("laneOffset"))
    road.lane_offset.push_back(R.poly(o, "s"));
  for (const pugi::xml_node sec : lanes.children("laneSection"))
    road.sections.push_back(readLaneSection(sec, R, where));
  if (road.sections.empty()) R.fail("lanes", "no laneSection");
  for (const pugi::xml_node s : r.child("signals").children("signal"))
    road.signals.push_back(readSignal(s, R, where));
  for (const pugi::xml_node o : r.child("objects").children("object"))
    road.objects.push_back(readObject(o, R, where));
  auto byS = [](const auto& x, const auto& y) { return x.s < y.s; };
  std::stable_sort(road.plan_view.begin(), road.plan_view.end(), byS);
  std::stable_sort(road.elevation.begin(), road.elevation.end(), byS);
  std::stable_sort(road.superelevation.begin(), road.superelevation.end(), byS);
  std::stable_sort(road.lane_offset.begin(), road.lane_offset.end(), byS);
  std::stable_sort(road.sections.begin(), road.sections.end(), byS);
  return road;
}

}  // namespace

const OdrLane* OdrLaneSection::lane(int id) const {
  for (const auto& l : lanes)
    if (l.id == id) return &l;
  return nullptr;
}

const OdrRoad* OdrMap::road(const std::string& id) const {
  for (const auto& r : roads)
    if (r.id == id) return &r;
  return nullptr;
}

const OdrJunction* OdrMap::junction(const std::string& id) const {
  for (const auto& j : junctions)
    if (j.id == id) return &j;
  return nullptr;
}

namespace {

void readHeader(const pugi::xml_node& header, OdrMap& map) {
  // The PROJ string, without the blanks around it (esmini writes `<geoReference> </...>`).
  const std::string geo = header.child("geoReference").text().get();
  const auto first = geo.find_first_not_of(" \t\r\n");
  if (first != std::string::npos)
    map.geo_reference = geo.substr(first, geo.find_last_not_of(" \t\r\n") - first + 1);
  if (const pugi::xml_node off = header.child("offset")) {
    const Reader R(map.file, "header", &map.warnings);
    using bounds::kMaxCoordinate;
    map.offset_x = R.bounded(off, "x", 0.0, -kMaxCoordinate, kMaxCoordinate);
    map.offset_y = R.bounded(off, "y", 0.0, -kMaxCoordinate, kMaxCoordinate);
    map.offset_z = R.bounded(off, "z", 0.0, -kMaxCoordinate, kMaxCoordinate);
    map.offset_hdg = R.bounded(off, "hdg", 0.0, -bounds::kMaxAngle, bounds::kMaxAngle);
  }
}

/// Every road, with unique ids; the work of converting a map grows with its length (reference
/// lines, plan-view records included, and lanes are sampled every 0.5 m), so it is bounded.
void readRoads(const pugi::xml_node& root, OdrMap& map) {
  const std::string& file = map.file;
  double road_m = 0.0, geometry_m = 0.0, lane_m = 0.0;
  std::set<std::string> ids;
  for (const pugi::xml_node r : root.children("road")) {
    map.roads.push_back(readRoad(r, file, &map.warnings));
    const OdrRoad& road = map.roads.back();
    if (!ids.insert(road.id).second)
      throw ParseError(file, "road " + road.id, "road id '" + road.id + "' appears twice");
    road_m += road.length;
    for (const auto& g : road.plan_view) geometry_m += g.length;
    for (std::size_t k = 0; k < road.sections.size(); ++k) {
      const double end = k + 1 < road.sections.size() ? road.sections[k + 1].s : road.length;
      lane_m += std::max(0.0, end - road.sections[k].s) * road.sections[k].lanes.size();
    }
    for (const auto& [what, metres] : {std::pair{"road lengths", road_m},
                                       {"plan-view geometry lengths", geometry_m},
                                       {"lane lengths (section length x lanes)", lane_m}})
      if (metres > bounds::kMaxOdrMapLength)
        throw ParseError(file, "road " + road.id,
                         std::string("the map's ") + what + " add up to more than " +
                             bounds::numberText(bounds::kMaxOdrMapLength) + " m");
  }
  if (map.roads.empty()) throw ParseError(file, "road", "the map has no roads");
}

void readJunctions(const pugi::xml_node& root, OdrMap& map) {
  std::set<std::string> ids;
  for (const pugi::xml_node j : root.children("junction")) {
    OdrJunction junction;
    junction.id = j.attribute("id").value();
    junction.name = j.attribute("name").value();
    const Reader R(map.file, "junction " + junction.id, &map.warnings);
    if (!ids.insert(junction.id).second)
      R.fail("", "junction id '" + junction.id + "' appears twice");
    for (const pugi::xml_node c : j.children("connection")) {
      OdrConnection con;
      con.id = c.attribute("id").value();
      con.incoming_road = c.attribute("incomingRoad").value();
      // A direct junction (OpenDRIVE 1.7) links the incoming road to a `linkedRoad` instead.
      con.connecting_road = c.attribute("connectingRoad") ? c.attribute("connectingRoad").value()
                                                          : c.attribute("linkedRoad").value();
      con.contact_point = c.attribute("contactPoint").value();
      for (const pugi::xml_node ll : c.children("laneLink"))
        con.lane_links.push_back({R.integer(ll, "from"), R.integer(ll, "to")});
      junction.connections.push_back(con);
    }
    map.junctions.push_back(junction);
  }
}

}  // namespace

OdrMap parseOpenDrive(const std::string& xml, const std::string& file) {
  pugi::xml_document doc;
  const pugi::xml_node root = detail::xmlRoot(doc, xml, file, "OpenDRIVE");
  OdrMap map;
  map.file = file;
  readHeader(root.child("header"), map);
  readRoads(root, map);
  readJunctions(root, map);
  return map;
}

OdrMap readOpenDrive(const std::filesystem::path& path) {
  return parseOpenDrive(readBytes(path), path.string());
}

}  // namespace mapfuse::io
