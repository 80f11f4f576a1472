#include "mapfuse/io/osm_export.hpp"

#include <cstdio>
#include <pugixml.hpp>
#include <sstream>

#include "mapfuse/geo/origin.hpp"
#include "mapfuse/io/atomic_file.hpp"

namespace mapfuse::io {
namespace {

std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
  return buf;
}

void tag(pugi::xml_node n, const char* k, const std::string& v) {
  auto t = n.append_child("tag");
  t.append_attribute("k") = k;
  t.append_attribute("v") = v.c_str();
}

}  // namespace

std::string vectorMapToOsm(const VectorMap& map) {
  const geo::EnuConverter enu(map.origin);
  pugi::xml_document doc;
  auto decl = doc.append_child(pugi::node_declaration);
  decl.append_attribute("version") = "1.0";
  decl.append_attribute("encoding") = "UTF-8";
  auto osm = doc.append_child("osm");
  osm.append_attribute("version") = "0.6";
  osm.append_attribute("generator") = "mapfuse";
  long long next_id = 1;
  auto addNode = [&](const Eigen::Vector3d& p) {
    const geo::LatLonAlt g = enu.toWgs84(p);
    auto n = osm.append_child("node");
    const long long id = next_id++;
    n.append_attribute("id") = id;
    n.append_attribute("visible") = "true";
    n.append_attribute("version") = 1;
    n.append_attribute("lat") = fixed(g.lat, 9).c_str();
    n.append_attribute("lon") = fixed(g.lon, 9).c_str();
    tag(n, "ele", fixed(g.alt, 3));
    return std::make_pair(id, n);
  };
  struct Way {
    std::vector<long long> refs;
    const MapInstance* inst;
  };
  std::vector<Way> ways;
  for (const auto& inst : map.instances) {
    if (geometryKind(inst.cls) == GeometryKind::kPoint) {
      auto [id, n] = addNode(inst.points.front());
      (void)id;
      tag(n, "type", crowdClassName(inst.cls));
      tag(n, "height", fixed(inst.height, 2));
      tag(n, "mapfuse_id", std::to_string(inst.id));
      continue;
    }
    if (inst.cls == CrowdClass::kTrafficSign) {  // a tagged node at the sign's centre
      auto [id, n] = addNode(instanceCentre(inst));
      (void)id;
      tag(n, "type", "traffic_sign");
      tag(n, "mapfuse_id", std::to_string(inst.id));
      continue;
    }
    Way w{{}, &inst};
    for (const auto& p : inst.points) w.refs.push_back(addNode(p).first);
    if (geometryKind(inst.cls) == GeometryKind::kPlanar) w.refs.push_back(w.refs.front());
    ways.push_back(std::move(w));
  }
  for (const auto& w : ways) {
    auto way = osm.append_child("way");
    way.append_attribute("id") = next_id++;
    way.append_attribute("visible") = "true";
    way.append_attribute("version") = 1;
    for (long long r : w.refs) way.append_child("nd").append_attribute("ref") = r;
    const MapInstance& inst = *w.inst;
    switch (inst.cls) {
      case CrowdClass::kLaneLine:
        tag(way, "type", "line_thin");
        tag(way, "subtype", inst.attributes.style == LineStyle::kDashed ? "dashed" : "solid");
        if (inst.attributes.color != LineColor::kNone)
          tag(way, "color", lineColorName(inst.attributes.color));
        break;
      case CrowdClass::kStopLine: tag(way, "type", "stop_line"); break;
      case CrowdClass::kGroundArrow: tag(way, "type", "arrow"); break;
      case CrowdClass::kCrosswalk: tag(way, "type", "zebra_marking"); break;
      default: tag(way, "type", crowdClassName(inst.cls)); break;
    }
    tag(way, "mapfuse_id", std::to_string(inst.id));
  }
  std::ostringstream out;
  doc.save(out, "  ", pugi::format_default, pugi::encoding_utf8);
  return out.str();
}

void writeOsm(const std::filesystem::path& path, const VectorMap& map) {
  writeBytesAtomic(path, vectorMapToOsm(map));
}

}  // namespace mapfuse::io
