// One OpenDRIVE <road> read into its records (opendrive_xml.hpp).
#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>

#include "opendrive_xml.hpp"

namespace mapfuse::io::detail {
namespace {

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

}  // namespace

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

}  // namespace mapfuse::io::detail
