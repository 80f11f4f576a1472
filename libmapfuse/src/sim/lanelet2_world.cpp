#include "mapfuse/sim/lanelet2_world.hpp"

#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>

#include "line_chains.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/io/bounds.hpp"
#include "sign_posts.hpp"
#include "truth_counts.hpp"

namespace mapfuse::sim {

namespace {

constexpr double kCenterlineStep = 0.5;      // m
constexpr double kSuccessorTolerance = 0.1;  // m, shared bound end points
constexpr double kArrowStopDistance = 1.0;   // m, centreline vertex to stop line: a crossing
constexpr double kMinArrowLaneRoom = 2.5;    // m, the arrow must fit into the lane
constexpr double kJoinTolerance = 1e-3;      // m, line pieces sharing a node are one marking

/// The `height` tag of a way or node in metres; nullopt when absent or not a number in
/// (0, io::bounds::kMaxElementHeight].
std::optional<double> heightTag(const std::map<std::string, std::string>& tags) {
  const auto it = tags.find("height");
  if (it == tags.end()) return std::nullopt;
  char* end = nullptr;
  const double h = std::strtod(it->second.c_str(), &end);
  if (end == it->second.c_str() || !std::isfinite(h) || h <= 0.0 ||
      h > io::bounds::kMaxElementHeight)
    return std::nullopt;
  return h;
}

// Drivable lanelets are sampled every kCenterlineStep: at most 1000 km of them (2e6 samples;
// the Karlsruhe example map has about 30 km). One node 2700 km from the others made a single
// lanelet take 30 s.
constexpr double kMaxDrivableLength = 1e6;  // m
// A drivable lanelet's bounds at most this far apart on average (lanes are 2.5-5 m wide, the
// widest junction lanelets of real maps some 20 m). A fuzzed node 730 km from its neighbour made
// a lanelet 365 km wide whose centreline ran far from every bound.
constexpr double kMaxLaneWidth = 100.0;  // m

bool isDrivable(const std::string& subtype) {
  return subtype.empty() || subtype == "road" || subtype == "highway" || subtype == "exit" ||
         subtype == "bus_lane" || subtype == "play_street";
}

/// Resamples a line into exactly n points by arc-length fraction.
Polyline fractionSample(const Polyline& line, int n) {
  const auto cum = arcLengths(line);
  Polyline out;
  for (int k = 0; k < n; ++k) out.push_back(pointAt(line, cum, cum.back() * k / (n - 1)));
  return out;
}

struct IdAllocator {
  std::set<int64_t> used;
  int64_t next = 1;
  int64_t take(int64_t wanted) {
    if (used.insert(wanted).second) return wanted;
    return fresh();
  }
  int64_t fresh() {
    while (used.count(next)) ++next;
    used.insert(next);
    return next;
  }
};

/// A lanelet bound or a lane / stop line shorter than this is a way whose nodes lie at one place:
/// no direction, no marking.
constexpr double kMinWayLength = 0.01;  // m

/// A point, sign, light or arrow way longer than this is no such element (a node on the other
/// side of the Earth made a stop line of 12,700 km): dropped with a warning.
constexpr double kMaxSmallElement = 100.0;  // m

/// The map, its ways in ENU, the world being built and its element ids.
struct L2Builder {
  const io::Lanelet2Map& map;
  const Lanelet2Assumptions& A;
  World& world;
  geo::EnuConverter enu;
  std::vector<Polyline> ways;
  IdAllocator ids;
  bool map_has_poles = false;
  int lines = 0, stops = 0, signs = 0, lights = 0, boundaries = 0, crossing_lines = 0;
  int poles = 0, map_arrows = 0, drivable = 0, placed_poles = 0;
  SignPosts posts;  ///< signs and lights mounted together share one placed pole
  std::map<int64_t, std::pair<int64_t, int64_t>> line_ends;  // lane-line instance -> end nodes

  L2Builder(const io::Lanelet2Map& m, const geo::GeoOrigin& origin, const Lanelet2Assumptions& a,
            World& w)
      : map(m), A(a), world(w), enu(origin) {}

  /// Every way in ENU; a node beyond the coordinate bound (what the truth's readers refuse) is
  /// refused here, so that simulate never writes a truth its own readers reject.
  Eigen::Vector3d toEnu(const geo::LatLonAlt& p, const std::string& what) const {
    const Eigen::Vector3d q = enu.toEnu(p);
    if (!(q.cwiseAbs().maxCoeff() <= io::bounds::kMaxCoordinate))
      throw InputError(map.file + ": " + what + " has a node at ENU (" +
                       io::bounds::numberText(q.x()) + ", " + io::bounds::numberText(q.y()) + ", " +
                       io::bounds::numberText(q.z()) + ") m from the origin, beyond " +
                       io::bounds::numberText(io::bounds::kMaxCoordinate) +
                       " m (docs/formats.md \"Value bounds\")");
    return q;
  }
  void convertWays() {
    ways.resize(map.linestrings.size());
    for (std::size_t i = 0; i < ways.size(); ++i)
      for (const auto& p : map.linestrings[i].points)
        ways[i].push_back(toEnu(p, "way " + std::to_string(map.linestrings[i].id)));
    int64_t max_id = 0;
    // The reader keeps |id| <= 2^63 - 2^32: abs and the fresh ids after max_id cannot overflow.
    for (const auto& w : map.linestrings) max_id = std::max(max_id, std::abs(w.id));
    for (const auto& l : map.lanelets) max_id = std::max(max_id, std::abs(l.id));
    ids.next = max_id + 1;  // ids of placed elements follow every map id
  }
  const Polyline& wayLine(int64_t id) const { return ways[map.way_index.at(id)]; }

  MapInstance& add(int64_t wanted, CrowdClass cls, Polyline pts, const std::string& note) {
    MapInstance m;
    m.id = ids.take(wanted);
    m.cls = cls;
    m.points = std::move(pts);
    m.note = note;
    m.source_ids = {wanted};
    world.truth.instances.push_back(std::move(m));
    return world.truth.instances.back();
  }

  void checkDrivableLength() const {
    double drivable_length = 0.0;
    for (const auto& ll : map.lanelets)
      if (ll.subtype != "crosswalk" && isDrivable(ll.subtype))
        drivable_length +=
            std::max(polylineLength(wayLine(ll.left)), polylineLength(wayLine(ll.right)));
    if (drivable_length > kMaxDrivableLength)
      throw InputError(map.file + ": drivable lanelets are " +
                       std::to_string(std::lround(drivable_length / 1000)) +
                       " km long in all, more than " +
                       std::to_string(std::lround(kMaxDrivableLength / 1000)) +
                       " km (the simulator samples them every " +
                       io::bounds::numberText(kCenterlineStep) + " m)");
  }

  /// A drivable lanelet's lane (and its reverse twin when two-way).
  void addLane(const io::Lanelet2Lanelet& ll, const Polyline& left, const Polyline& right) {
    const int n = std::max(
        2, static_cast<int>(
               std::ceil(std::max(polylineLength(left), polylineLength(right)) / kCenterlineStep)) +
               1);
    const Polyline L = fractionSample(left, n), R = fractionSample(right, n);
    Lane lane;
    lane.id = ll.id;
    double width = 0.0;
    for (int k = 0; k < n; ++k) {
      lane.centerline.push_back(0.5 * (L[k] + R[k]));
      width += (L[k] - R[k]).norm() / n;
    }
    lane.width = width;
    if (width > kMaxLaneWidth)
      throw InputError(map.file + ": lanelet " + std::to_string(ll.id) + ": its left way " +
                       std::to_string(ll.left) + " and right way " + std::to_string(ll.right) +
                       " are " + io::bounds::numberText(std::round(width)) +
                       " m apart on average, more than " + io::bounds::numberText(kMaxLaneWidth) +
                       " m (a bound with a misplaced node?)");
    // The left bound must lie left of the driving direction.
    const int m = n / 2;
    const Eigen::Vector3d dir =
        lane.centerline[std::min(n - 1, m + 1)] - lane.centerline[std::max(0, m - 1)];
    const Eigen::Vector3d lr = L[m] - R[m];
    if (dir.x() * lr.y() - dir.y() * lr.x() < 0.0) lane.centerline = reversed(lane.centerline);
    world.lanes.push_back(lane);
    if (!ll.one_way) {
      lane.centerline = reversed(lane.centerline);
      world.lanes.push_back(lane);
    }
  }

  /// Lanes and crosswalks from lanelets (the reader refuses a lanelet whose left bound is its
  /// right bound); a lanelet with a bound of no length (its nodes at one place) has no direction
  /// to drive or to orient its bounds by: dropped with a warning.
  void addLanelets() {
    checkDrivableLength();
    for (const auto& ll : map.lanelets) {
      Polyline left = wayLine(ll.left), right = wayLine(ll.right);
      const double shorter = std::min(polylineLength(left), polylineLength(right));
      if (!(shorter >= kMinWayLength)) {
        world.warnings.add(
            "lanelet with a bound shorter than " + io::bounds::numberText(kMinWayLength) +
                " m (dropped)",
            map.file + ": lanelet " + std::to_string(ll.id) + " (way " +
                std::to_string(polylineLength(left) < shorter + 1e-12 ? ll.left : ll.right) + ", " +
                io::bounds::numberText(shorter) + " m)");
        continue;
      }
      if ((left.front() - right.front()).norm() + (left.back() - right.back()).norm() >
          (left.front() - right.back()).norm() + (left.back() - right.front()).norm())
        right = reversed(right);
      if (ll.subtype == "crosswalk") {
        Polyline ring = left;
        for (auto it = right.rbegin(); it != right.rend(); ++it) ring.push_back(*it);
        add(ll.id, CrowdClass::kCrosswalk, ring, "");
        continue;
      }
      if (!isDrivable(ll.subtype)) continue;
      ++drivable;
      addLane(ll, left, right);
    }
    connectLanesByEndpoints(world, kSuccessorTolerance);
  }

  /// Poles mapped as points (`type=pole`, `height`); then no pole is placed under signs.
  void addPoles() {
    for (const auto& p : map.points) {
      if (p.type != "pole") continue;
      add(p.id, CrowdClass::kPole, {toEnu(p.position, "pole " + std::to_string(p.id))}, "").height =
          heightTag(p.tags).value_or(0.0);
      map_has_poles = true;
      ++poles;
    }
  }

  void addLaneLine(const io::Lanelet2LineString& w, const Polyline& pts) {
    auto& m = add(w.id, CrowdClass::kLaneLine, pts,
                  w.subtype == "solid_dashed" || w.subtype == "dashed_solid"
                      ? "double line " + w.subtype + " mapped to solid"
                      : "");
    m.attributes.style = w.subtype == "dashed" ? LineStyle::kDashed : LineStyle::kSolid;
    line_ends[m.id] = {w.node_ids.front(), w.node_ids.back()};
    const auto c = w.tags.find("color");
    m.attributes.color =
        c != w.tags.end() && c->second == "yellow" ? LineColor::kYellow : LineColor::kWhite;
    ++lines;
  }

  void addSign(const io::Lanelet2LineString& w, const Polyline& pts) {
    // With a `height` tag the way is the plate's bottom edge at its true altitude (as mapfuse
    // writes it); without, the plate is assumed (the example maps carry no heights).
    const std::optional<double> h = heightTag(w.tags);
    const double bottom = h ? 0.0 : A.sign_bottom, size = h ? *h : A.sign_size;
    const Eigen::Vector3d a = pts.front(), b = pts.back(), up(0, 0, 1);
    add(w.id, CrowdClass::kTrafficSign,
        {a + bottom * up, b + bottom * up, b + (bottom + size) * up, a + (bottom + size) * up},
        h ? "" : "mounting height assumed by simulator");
    const Eigen::Vector3d post = 0.5 * (a + b);
    if (!map_has_poles && posts.claim(post)) {
      add(ids.fresh(), CrowdClass::kPole, {post}, "placed by simulator under a sign").height =
          bottom + size;
      ++placed_poles;
    }
    ++signs;
  }

  void addLight(const io::Lanelet2LineString& w, const Polyline& pts) {
    const std::optional<double> h = heightTag(w.tags);
    const double bottom = h ? 0.0 : A.light_bottom;
    const Eigen::Vector3d c = 0.5 * (pts.front() + pts.back());
    add(w.id, CrowdClass::kTrafficLight, {c + Eigen::Vector3d(0, 0, bottom)},
        h ? "" : "mounting height assumed by simulator")
        .height = h ? *h : A.light_height;
    if (!map_has_poles && posts.claim(c)) {
      add(ids.fresh(), CrowdClass::kPole, {c}, "placed by simulator under a traffic light").height =
          A.light_bottom;
      ++placed_poles;
    }
    ++lights;
  }

  /// Line strings: lane lines, stop lines, signs, lights and arrows.
  void addLineStrings() {
    for (std::size_t i = 0; i < map.linestrings.size(); ++i) {
      const auto& w = map.linestrings[i];
      const Polyline& pts = ways[i];
      const bool small = w.type == "stop_line" || w.type == "traffic_sign" ||
                         w.type == "traffic_light" || w.type == "arrow";
      if (small && polylineLength(pts) > kMaxSmallElement) {
        world.warnings.add("stop line, sign, light or arrow way longer than " +
                               io::bounds::numberText(kMaxSmallElement) + " m (dropped)",
                           map.file + ": way " + std::to_string(w.id) + " (" + w.type + ", " +
                               io::bounds::numberText(std::round(polylineLength(pts))) + " m)");
        continue;
      }
      const bool line = w.type == "line_thin" || w.type == "line_thick" || w.type == "stop_line";
      if (line && pts.size() >= 2 && !(polylineLength(pts) >= kMinWayLength)) {
        world.warnings.add("lane or stop line way shorter than " +
                               io::bounds::numberText(kMinWayLength) + " m (dropped)",
                           map.file + ": way " + std::to_string(w.id) + " (" + w.type + ")");
        continue;
      }
      if ((w.type == "line_thin" || w.type == "line_thick") && pts.size() >= 2) {
        addLaneLine(w, pts);
      } else if (w.type == "stop_line" && pts.size() >= 2) {
        add(w.id, CrowdClass::kStopLine, {pts.front(), pts.back()}, "");
        ++stops;
      } else if (w.type == "traffic_sign") {
        addSign(w, pts);
      } else if (w.type == "traffic_light") {
        addLight(w, pts);
      } else if (w.type == "arrow" && pts.size() >= 4) {  // an outline (closed way)
        Polyline ring = pts;
        if ((ring.front() - ring.back()).norm() < kJoinTolerance) ring.pop_back();
        add(w.id, CrowdClass::kGroundArrow, ring, "");
        ++map_arrows;
      } else if (w.type == "curbstone" || w.type == "road_border") {
        ++boundaries;
      } else if (w.type == "zebra_marking" || w.type == "pedestrian_marking") {
        ++crossing_lines;
      }
    }
  }

  /// One marking cut into several ways (at lanelet ends, sharing the end node) is one line.
  int joinLines() {
    return joinLineChains(world.truth.instances, kJoinTolerance,
                          [&](const MapInstance& a, int side_a, const MapInstance& b, int side_b) {
                            const auto ea = line_ends.find(a.id), eb = line_ends.find(b.id);
                            if (ea == line_ends.end() || eb == line_ends.end()) return false;
                            return (side_a == 0 ? ea->second.first : ea->second.second) ==
                                   (side_b == 0 ? eb->second.first : eb->second.second);
                          });
  }

  int placeArrows();
};

/// Arrows before stop lines, one per lane ending at a stop line, unless the map has arrows.
/// Lanes whose bounding box is farther than kArrowStopDistance from the stop line cannot cross
/// it: skipped unread. @return the arrows placed.
int L2Builder::placeArrows() {
  int arrows = 0;
  struct Box {
    Eigen::Vector2d lo, hi;
  };
  auto boxOf = [](const Polyline& line) {
    Box b{line.front().head<2>(), line.front().head<2>()};
    for (const auto& p : line) b.lo = b.lo.cwiseMin(p.head<2>()), b.hi = b.hi.cwiseMax(p.head<2>());
    return b;
  };
  std::vector<Box> lane_boxes;
  for (const auto& lane : world.lanes) lane_boxes.push_back(boxOf(lane.centerline));
  const std::size_t n_instances = map_arrows > 0 ? 0 : world.truth.instances.size();
  for (std::size_t i = 0; i < n_instances; ++i) {
    if (world.truth.instances[i].cls != CrowdClass::kStopLine) continue;
    const Polyline stop = world.truth.instances[i].points;
    const Box sb = boxOf(stop);
    for (std::size_t li = 0; li < world.lanes.size(); ++li) {
      const Lane& lane = world.lanes[li];
      const Box& lb = lane_boxes[li];
      if ((lb.lo - sb.hi).maxCoeff() > kArrowStopDistance ||
          (sb.lo - lb.hi).maxCoeff() > kArrowStopDistance)
        continue;
      // Where the lane centreline crosses the stop line (closest vertex within tolerance).
      const auto cum = arcLengths(lane.centerline);
      double s_stop = -1.0, best = kArrowStopDistance;
      for (std::size_t v = 0; v < lane.centerline.size(); ++v) {
        const double dist = distanceToPolyline(stop, lane.centerline[v]);
        if (dist < best) best = dist, s_stop = cum[v];
      }
      const double s_arrow = s_stop - A.arrow_before_stop;
      if (s_stop < 0.0 || s_arrow < kMinArrowLaneRoom) continue;
      const Eigen::Vector3d c = pointAt(lane.centerline, cum, s_arrow);
      const Eigen::Vector3d t = (pointAt(lane.centerline, cum, s_arrow + 0.5) -
                                 pointAt(lane.centerline, cum, s_arrow - 0.5))
                                    .normalized();
      const Eigen::Vector3d n(-t.y(), t.x(), 0.0);
      Polyline ring;
      for (const auto& q : std::vector<Eigen::Vector2d>{{-2.5, -0.15},
                                                        {1.0, -0.15},
                                                        {1.0, -0.6},
                                                        {2.5, 0.0},
                                                        {1.0, 0.6},
                                                        {1.0, 0.15},
                                                        {-2.5, 0.15}})
        ring.push_back(c + q.x() * t + q.y() * n);
      add(ids.fresh(), CrowdClass::kGroundArrow, ring, "placed by simulator before a stop line");
      ++arrows;
    }
  }
  return arrows;
}

}  // namespace

World worldFromLanelet2(const io::Lanelet2Map& map, const geo::GeoOrigin& origin,
                        const Lanelet2Assumptions& A) {
  if (map.untyped_ways > 0)
    MAPFUSE_WARN(map.file << ": " << map.untyped_ways
                          << " ways have no `type` tag; read as `virtual` (no marking)");
  World world;
  world.name = map.file;
  world.truth.origin = origin;
  world.truth.source = "simulate ground truth (Lanelet2 " + map.file + ")";
  L2Builder B(map, origin, A, world);
  B.convertWays();
  B.addLanelets();
  B.addPoles();
  B.addLineStrings();
  const int joins = B.joinLines();
  const int arrows = B.placeArrows();
  world.stats["lanelets"] = static_cast<double>(map.lanelets.size());
  world.stats["drivable_lanelets"] = B.drivable;
  world.stats["boundaries_ignored"] = B.boundaries;
  world.stats["crossing_lines_ignored"] = B.crossing_lines;
  world.stats["arrows_placed"] = arrows;
  world.stats["arrows_mapped"] = B.map_arrows;
  world.stats["untyped_ways_as_virtual"] = map.untyped_ways;
  world.stats["skipped_ways"] = detail::totalOf(map.skipped_way_types);
  detail::TruthCounts{B.lines, B.stops, B.signs, B.lights, B.poles, B.placed_poles, joins}.writeTo(
      world.stats);
  world.stats["skipped_relations"] = detail::totalOf(map.skipped_relation_types);
  return world;
}

}  // namespace mapfuse::sim
