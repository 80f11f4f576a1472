#pragma once
/// @file OpenDRIVE reader (docs/simulate.md "OpenDRIVE maps"), with pugixml: the header's
/// georeference, roads (links, plan view, elevation, superelevation, lane offsets, lane sections
/// with lane widths, road marks and links, signals, objects) and junctions (connections with lane
/// links). Records are kept as the file states them; the geometry is evaluated by
/// sim/opendrive_geometry.hpp. Reading policy (docs/formats.md "Map content checks"): structural
/// faults (XML syntax, a missing or non-numeric required attribute, an unknown geometry kind, lane
/// `border` records, duplicate road / junction / lane ids) are ParseErrors naming the file and the
/// element (road id, lane id); values outside the standard's range that can still be used (a
/// negative `s` / `sOffset`) are clamped and counted in OdrMap::warnings, one entry per kind.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "mapfuse/core/input_warnings.hpp"

namespace mapfuse::io {

/// a + b ds + c ds^2 + d ds^3 from `s` (ds = s - this s), as OpenDRIVE writes every polynomial.
struct OdrPoly3 {
  double s = 0.0;  ///< start (m along the road, or sOffset within a lane section)
  double a = 0.0, b = 0.0, c = 0.0, d = 0.0;
  double at(double s_query) const {
    const double x = s_query - s;
    return a + x * (b + x * (c + x * d));
  }
  double slope(double s_query) const {
    const double x = s_query - s;
    return b + x * (2 * c + x * 3 * d);
  }
};

/// One plan-view record.
struct OdrGeometry {
  enum class Kind { kLine, kArc, kSpiral, kPoly3, kParamPoly3 };
  Kind kind = Kind::kLine;
  double s = 0.0, x = 0.0, y = 0.0, hdg = 0.0, length = 0.0;              ///< m, rad
  double curvature = 0.0;                                                 ///< arc, 1/m
  double curv_start = 0.0, curv_end = 0.0;                                ///< spiral, 1/m
  double a = 0, b = 0, c = 0, d = 0;                                      ///< poly3: v(u)
  double au = 0, bu = 0, cu = 0, du = 0, av = 0, bv = 0, cv = 0, dv = 0;  ///< paramPoly3
  bool p_normalized = true;  ///< paramPoly3 pRange: normalized (p in [0, 1]) or arcLength
};

struct OdrRoadMark {
  double s_offset = 0.0;  ///< m from the lane section start
  std::string type;       ///< "solid", "broken", "solid solid", "none", ...
  std::string color;      ///< "standard", "white", "yellow", ...
  double width = 0.12;    ///< m
};

struct OdrLane {
  int id = 0;  ///< > 0 left of the reference line, < 0 right, 0 the centre lane
  std::string type;
  std::vector<OdrPoly3> widths;  ///< s = sOffset
  std::vector<OdrRoadMark> marks;
  std::optional<int> predecessor, successor;  ///< lane ids in the neighbouring section / road
};

struct OdrLaneSection {
  double s = 0.0;
  std::vector<OdrLane> lanes;  ///< left (descending id), centre, right (descending id)
  const OdrLane* lane(int id) const;
};

/// A road's link at one end.
struct OdrLink {
  std::string element_type;  ///< "road" | "junction"
  std::string element_id;
  std::string contact_point;  ///< "start" | "end" (roads)
};

struct OdrSignal {
  std::string id, name, type, subtype, country, orientation;  ///< orientation "+", "-", "none"
  double s = 0.0, t = 0.0, z_offset = 0.0, h_offset = 0.0;
  double height = 0.0, width = 0.0;  ///< m (0 when absent)
  bool dynamic = false;              ///< a traffic light
};

struct OdrCorner {
  double u = 0.0, v = 0.0, z = 0.0;  ///< cornerLocal (object frame), or s, t, dz (cornerRoad)
  bool road = false;                 ///< cornerRoad
};

struct OdrObject {
  std::string id, name, type;
  double s = 0.0, t = 0.0, z_offset = 0.0, hdg = 0.0;
  double length = 0.0, width = 0.0, height = 0.0, radius = 0.0;
  std::vector<OdrCorner> outline;  ///< first outline, if any
};

struct OdrRoad {
  std::string id, name, junction;  ///< junction "-1" outside junctions
  std::string rule = "RHT";        ///< traffic rule: RHT | LHT
  double length = 0.0;
  std::optional<OdrLink> predecessor, successor;
  std::vector<OdrGeometry> plan_view;
  std::vector<OdrPoly3> elevation, superelevation, lane_offset;
  std::vector<OdrLaneSection> sections;
  std::vector<OdrSignal> signals;
  std::vector<OdrObject> objects;
};

struct OdrLaneLink {
  int from = 0, to = 0;
};

struct OdrConnection {
  std::string id, incoming_road, connecting_road, contact_point;
  std::vector<OdrLaneLink> lane_links;
};

struct OdrJunction {
  std::string id, name;
  std::vector<OdrConnection> connections;
};

struct OdrMap {
  std::string file;
  std::string geo_reference;  ///< PROJ string of the header ("" when absent)
  double offset_x = 0.0, offset_y = 0.0, offset_z = 0.0, offset_hdg = 0.0;  ///< header <offset>
  std::vector<OdrRoad> roads;
  std::vector<OdrJunction> junctions;
  InputWarnings warnings;  ///< values clamped or records dropped, by kind (count, first example)

  const OdrRoad* road(const std::string& id) const;
  const OdrJunction* junction(const std::string& id) const;
};

/// @brief Parses an OpenDRIVE file. @throws IoError when unreadable; ParseError when malformed.
OdrMap readOpenDrive(const std::filesystem::path& path);

/// @brief Parses OpenDRIVE XML held in memory; `file` names the source in errors.
OdrMap parseOpenDrive(const std::string& xml, const std::string& file);

}  // namespace mapfuse::io
