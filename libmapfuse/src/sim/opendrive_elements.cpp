// The true map elements of an OpenDRIVE world: lane lines from road marks, signs and traffic
// lights from signals, poles and crosswalks from objects, stop lines from stop-line signals.
#include <cmath>
#include <map>
#include <optional>
#include <string>

#include "line_chains.hpp"
#include "opendrive_internal.hpp"
#include "sign_posts.hpp"
#include "truth_counts.hpp"

namespace mapfuse::sim::detail {

namespace {

constexpr double kJoinTolerance = 0.02;     // m; marks of consecutive sections / roads meet here
const char* const kStopLineSignal = "294";  // StVO 294 "Haltlinie" (OpenDRIVE signal catalogue)

/// Line style of an OpenDRIVE road mark type; nullopt for marks that are no painted line.
std::optional<LineStyle> markStyle(const std::string& type, std::string* note) {
  if (type == "solid") return LineStyle::kSolid;
  if (type == "broken") return LineStyle::kDashed;
  if (type == "solid solid" || type == "solid broken" || type == "broken solid") {
    *note = "double mark '" + type + "' as one solid line";
    return LineStyle::kSolid;
  }
  if (type == "broken broken") {
    *note = "double mark 'broken broken' as one dashed line";
    return LineStyle::kDashed;
  }
  return std::nullopt;  // none, botts dots, grass, curb, edge, custom
}

LineColor markColor(const std::string& color, std::string* note) {
  if (color == "yellow") return LineColor::kYellow;
  if (!color.empty() && color != "standard" && color != "white")
    *note += (note->empty() ? "" : "; ") + std::string("colour '") + color + "' as white";
  return LineColor::kWhite;
}

bool isPole(const std::string& type) {
  return type == "pole" || type == "streetLamp";
}

/// An object painted on the road: OpenDRIVE 1.6 `roadMark` (also written `roadmark`), and the
/// `arrow` / `symbol` types of older exporters. Each becomes a ground arrow (the map's class for
/// symbols on the road), its note naming the subtype when it is not an arrow.
bool isRoadMarkObject(const io::OdrObject& o) {
  return o.type == "roadMark" || o.type == "roadmark" || o.type == "arrow" || o.type == "symbol";
}

/// Builds the elements of one map, road by road.
struct ElementBuilder {
  const OdrContext& ctx;
  World& world;
  int64_t next_id = 1;
  std::map<std::string, int> skipped_marks, skipped_objects;
  int signs = 0, lights = 0, poles = 0, crosswalks = 0, stop_lines = 0, arrows = 0;
  std::vector<std::pair<Eigen::Vector3d, double>> pole_requests;  // base, height

  ElementBuilder(const OdrContext& c, World& w) : ctx(c), world(w) {}

  MapInstance& add(CrowdClass cls, Polyline pts, const std::string& note) {
    return world.addTruth(next_id++, cls, std::move(pts), note);
  }

  /// Lane lines: the outer border of each lane (the centre lane: its line) per road mark record.
  void laneLines(const io::OdrRoad& road, const RoadGeometry& geo) {
    for (std::size_t k = 0; k < road.sections.size(); ++k) {
      const double s0 = geo.sectionStart(k), s1 = geo.sectionEnd(k);
      for (const io::OdrLane& lane : road.sections[k].lanes)
        for (std::size_t m = 0; m < lane.marks.size(); ++m) {
          const io::OdrRoadMark& mark = lane.marks[m];
          const double a = s0 + mark.s_offset;
          const double b =
              std::min(s1, m + 1 < lane.marks.size() ? s0 + lane.marks[m + 1].s_offset : s1);
          if (b - a < 1e-3) continue;
          std::string note;
          const std::optional<LineStyle> style = markStyle(mark.type, &note);
          if (!style) {
            ++skipped_marks[mark.type.empty() ? "(none)" : mark.type];
            continue;
          }
          Polyline pts;
          for (double s : ctx.samples(a, b))
            pts.push_back(ctx.toEnu(geo.point(s, geo.borderT(k, lane.id, s))));
          MapInstance& line = add(CrowdClass::kLaneLine, pts, "");
          line.attributes.style = *style;
          line.attributes.color = markColor(mark.color, &note);
          line.note = note;
        }
    }
  }

  /// Signals: traffic lights (dynamic), stop lines (294) and signs.
  void signal(const io::OdrSignal& sig, const RoadGeometry& geo) {
    const OpenDriveAssumptions& A = ctx.assumptions;
    const RefPose ref = geo.reference(sig.s);
    const Eigen::Vector3d base = geo.point(sig.s, sig.t);
    if (sig.type == kStopLineSignal) {
      const double half = 0.5 * (sig.width > 0 ? sig.width : 3.5);
      add(CrowdClass::kStopLine,
          {ctx.toEnu(geo.point(sig.s, sig.t - half)), ctx.toEnu(geo.point(sig.s, sig.t + half))},
          sig.width > 0 ? "" : "stop line width assumed by simulator");
      ++stop_lines;
      return;
    }
    if (sig.dynamic) {
      const double bottom = sig.z_offset > 0 ? sig.z_offset : A.light_bottom;
      add(CrowdClass::kTrafficLight, {ctx.toEnu(base + Eigen::Vector3d(0, 0, bottom))},
          sig.z_offset > 0 && sig.height > 0 ? "" : "mounting assumed by simulator")
          .height = sig.height > 0 ? sig.height : A.light_height;
      pole_requests.push_back({base, bottom});
      ++lights;
      return;
    }
    const double w = sig.width > 0 ? sig.width : A.sign_size;
    const double h = sig.height > 0 ? sig.height : A.sign_size;
    const double bottom = sig.z_offset > 0 ? sig.z_offset : A.sign_bottom;
    const double across = ref.hdg + sig.h_offset;  // plate faces along the road
    const Eigen::Vector3d side(-std::sin(across) * 0.5 * w, std::cos(across) * 0.5 * w, 0.0);
    const Eigen::Vector3d lo = base + Eigen::Vector3d(0, 0, bottom), up(0, 0, h);
    add(CrowdClass::kTrafficSign,
        {ctx.toEnu(lo - side), ctx.toEnu(lo + side), ctx.toEnu(lo + side + up),
         ctx.toEnu(lo - side + up)},
        sig.width > 0 && sig.height > 0 && sig.z_offset > 0
            ? ""
            : "size or mounting assumed by simulator");
    pole_requests.push_back({base, bottom + h});
    ++signs;
  }

  /// The ground outline of an object: its outline (cornerLocal / cornerRoad), else its
  /// length x width rectangle; fewer than 3 points when it has neither.
  Polyline outline(const io::OdrObject& o, const RoadGeometry& geo) const {
    const RefPose ref = geo.reference(o.s);
    const Eigen::Vector3d base = geo.point(o.s, o.t) + Eigen::Vector3d(0, 0, o.z_offset);
    Polyline ring;
    const double h = ref.hdg + o.hdg, c = std::cos(h), s = std::sin(h);
    auto local = [&](double u, double v, double z) {
      return ctx.toEnu(base + Eigen::Vector3d(c * u - s * v, s * u + c * v, z));
    };
    for (const io::OdrCorner& q : o.outline)
      ring.push_back(q.road ? ctx.toEnu(geo.point(q.u, q.v) + Eigen::Vector3d(0, 0, q.z))
                            : local(q.u, q.v, q.z));
    if (ring.size() < 3 && o.length > 0 && o.width > 0) {
      ring.clear();
      for (const auto& [u, v] : {std::pair{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}})
        ring.push_back(local(u * o.length, v * o.width, 0.0));
    }
    return ring;
  }

  /// Objects: poles, crosswalks and road-mark objects (ground arrows).
  void object(const io::OdrObject& o, const RoadGeometry& geo) {
    if (isPole(o.type)) {
      const Eigen::Vector3d base = geo.point(o.s, o.t) + Eigen::Vector3d(0, 0, o.z_offset);
      add(CrowdClass::kPole, {ctx.toEnu(base)}, "").height = o.height;
      ++poles;
      return;
    }
    const bool road_mark = isRoadMarkObject(o);
    if (o.type != "crosswalk" && !road_mark) {
      ++skipped_objects[o.type.empty() ? "(none)" : o.type];
      return;
    }
    Polyline ring = outline(o, geo);
    if (ring.size() < 3) {
      ++skipped_objects[o.type + " without outline or size"];
      return;
    }
    if (!road_mark) {
      add(CrowdClass::kCrosswalk, ring, "");
      ++crosswalks;
      return;
    }
    const std::string what = o.name.empty() ? o.type : o.name;
    const bool arrow = what.find("rrow") != std::string::npos || o.type == "arrow";
    add(CrowdClass::kGroundArrow, ring, arrow ? "" : "road-mark object '" + what + "' as an arrow");
    ++arrows;
  }
};

}  // namespace

void addOpenDriveElements(const OdrContext& ctx, World& world) {
  const io::OdrMap& map = ctx.map;
  ElementBuilder B(ctx, world);
  bool map_has_poles = false;
  for (const auto& road : map.roads)
    for (const auto& o : road.objects) map_has_poles |= isPole(o.type);
  for (std::size_t r = 0; r < map.roads.size(); ++r) {
    const io::OdrRoad& road = map.roads[r];
    const RoadGeometry& geo = *ctx.roads[r];
    B.laneLines(road, geo);
    for (const io::OdrSignal& sig : road.signals) B.signal(sig, geo);
    for (const io::OdrObject& o : road.objects) B.object(o, geo);
  }
  // Poles under signs and lights when the map has none of its own.
  int placed_poles = 0;
  SignPosts posts;  // signs and lights mounted together share one pole
  if (!map_has_poles)
    for (const auto& [base, height] : B.pole_requests) {
      const Eigen::Vector3d enu = ctx.toEnu(base);
      if (!posts.claim(enu)) continue;
      B.add(CrowdClass::kPole, {enu}, "placed by simulator under a sign or light").height = height;
      ++placed_poles;
    }
  const int joins = joinLineChains(world.truth.instances, kJoinTolerance);
  int lines = 0;
  for (const auto& m : world.truth.instances) lines += m.cls == CrowdClass::kLaneLine;
  TruthCounts{lines, B.stop_lines, B.signs, B.lights, B.poles, placed_poles, joins}.writeTo(
      world.stats);
  world.stats["crosswalks"] = B.crosswalks;
  world.stats["arrows"] = B.arrows;
  world.stats["road_marks_not_lines"] = totalOf(B.skipped_marks);
  world.stats["objects_skipped"] = totalOf(B.skipped_objects);
}

}  // namespace mapfuse::sim::detail
