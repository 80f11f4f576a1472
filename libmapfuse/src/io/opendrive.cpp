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
#include "opendrive_xml.hpp"
#include "xml_root.hpp"

namespace mapfuse::io {

namespace {

using detail::Reader;
using detail::readRoad;

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
