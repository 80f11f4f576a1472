#include "mapfuse/sim/world_changes.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <set>

#include "mapfuse/core/angles.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/sim/point_cells.hpp"

namespace mapfuse::sim {
namespace {

constexpr double kMinRestripeLength = 10.0;  // m, shorter lane lines are not restriped
constexpr double kStretchRamp = 10.0;        // m, a stretch shift fades in and out over this
constexpr double kMinStretchLine = 60.0;     // m, shorter lines are shifted over their length
constexpr double kStretchStep = 1.0;         // m, vertex spacing of a line shifted on a stretch
constexpr double kMoveMaxAngle = 20.0 * kPi / 180.0;  // rad, moves keep near the road direction
constexpr double kRoadsideGap = 2.0;      // m, an added sign / pole beside its lane's edge
constexpr double kLaneEndGap = 1.0;       // m, an added stop line before its lane's end
constexpr double kMinAddLane = 30.0;      // m, lanes that take an addition
constexpr int kPlacementTries = 500;      // per addition
constexpr double kAddedPoleHeight = 4.0;  // m
constexpr double kAddedSignBottom = 2.0;  // m above the road (as the procedural world's)
constexpr double kAddedSignSize = 0.6;    // m

/// The arrow template of the worlds (procedural_world.cpp, lanelet2_world.cpp): along x.
const std::vector<Eigen::Vector2d> kArrowShape{{-2.5, -0.15}, {1.0, -0.15}, {1.0, -0.6}, {2.5, 0.0},
                                               {1.0, 0.6},    {1.0, 0.15},  {-2.5, 0.15}};

/// Where changes may go: within `distance` of a route (route samples 1 m apart, by grid cell:
/// PointCells), or anywhere without routes.
class RouteScope {
 public:
  RouteScope(const std::vector<Polyline>& routes, double distance) : d_(distance) {
    if (distance <= 0) return;
    for (const auto& r : routes) {
      samples_.push_back(resample(r, kRouteStep));
      cells_.emplace_back(samples_.back(), d_);
    }
  }
  bool near(const Eigen::Vector3d& p) const {
    if (samples_.empty()) return true;
    for (std::size_t r = 0; r < samples_.size(); ++r)
      for (const uint32_t i : cells_[r].near(p, d_))
        if ((samples_[r][i] - p).head<2>().norm() <= d_) return true;
    return false;
  }
  /// Point and area elements by their centre; a lane line by at least half its length (a long
  /// line of a map world, partly beside the route, is still seen where the route passes).
  bool holds(const MapInstance& m) const {
    if (samples_.empty()) return true;
    if (m.cls == CrowdClass::kLaneLine) {
      const Polyline samples = resample(m.points, kRouteStep);
      std::size_t in = 0;
      for (const auto& p : samples) in += near(p) ? 1 : 0;
      return 2 * in >= samples.size();
    }
    return near(instanceCentre(m));
  }

 private:
  static constexpr double kRouteStep = 1.0;  // m
  double d_;
  std::vector<Polyline> samples_;  ///< per route
  std::vector<PointCells> cells_;  ///< per route, its samples by cell
};

class Changer {
 public:
  Changer(World& world, const ChangeSettings& s, const std::vector<Polyline>& routes)
      : world_(world), s_(s), rng_(s.seed), scope_(routes, s.route_distance) {}

  MapChanges run() {
    MapChanges out;
    out.origin = world_.truth.origin;
    out.source = "simulate change truth";
    // Kinds with the smallest pools draw first.
    draw(
        "change_retyped", s_.retyped, isRetypable, [&](MapInstance& m) { retype(m); },
        ChangeKind::kRetyped, out);
    draw(
        "change_restriped", s_.restriped, isRestripable, [&](MapInstance& m) { restripe(m); },
        ChangeKind::kRestriped, out);
    draw(
        "change_moved", s_.moved, isMovable, [&](MapInstance& m) { move(m); }, ChangeKind::kMoved,
        out);
    draw("change_removed", s_.removed, isRemovable, nullptr, ChangeKind::kRemoved, out);
    removeDrawn();
    for (int k = 0; k < s_.added; ++k) add(out);
    return out;
  }

 private:
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }

  /// Moves p to `xy`, keeping its height above the ground where the world knows its surface
  /// (World::surface_height); elsewhere its z stays.
  void moveOnGround(Eigen::Vector3d& p, const Eigen::Vector2d& xy) const {
    if (world_.surface_height)
      p.z() +=
          world_.surface_height(Eigen::Vector3d(xy.x(), xy.y(), p.z())) - world_.surface_height(p);
    p.head<2>() = xy;
  }
  void moveOnGround(Polyline& line, const Polyline& to) const {
    for (std::size_t i = 0; i < line.size(); ++i) moveOnGround(line[i], to[i].head<2>());
  }
  bool coin() { return uniform(0.0, 1.0) < 0.5; }

  static bool isRemovable(const MapInstance& m) { return m.cls != CrowdClass::kLaneLine; }
  static bool isMovable(const MapInstance& m) {
    return m.cls == CrowdClass::kPole || m.cls == CrowdClass::kTrafficSign;
  }
  static bool isRestripable(const MapInstance& m) {
    return m.cls == CrowdClass::kLaneLine && polylineLength(m.points) >= kMinRestripeLength;
  }
  static bool isRetypable(const MapInstance& m) {
    return m.cls == CrowdClass::kGroundArrow ||
           (m.cls == CrowdClass::kLaneLine && m.attributes.style != LineStyle::kNone);
  }

  /// Picks `count` unchanged elements that `eligible` accepts, changes each with `apply`
  /// (nullptr: marks it removed) and records the change.
  void draw(const char* key, int count, bool (*eligible)(const MapInstance&),
            const std::function<void(MapInstance&)>& apply, ChangeKind kind, MapChanges& out) {
    std::vector<std::size_t> pool;
    for (std::size_t i = 0; i < world_.truth.instances.size(); ++i)
      if (!changed_.count(i) && eligible(world_.truth.instances[i]) &&
          scope_.holds(world_.truth.instances[i]))
        pool.push_back(i);
    if (int(pool.size()) < count)
      throw ConfigError(std::string(key) + " = " + std::to_string(count) + ": the world " +
                        world_.name + " has only " + std::to_string(pool.size()) +
                        " elements left that can take this change" +
                        (s_.route_distance > 0 ? " within change_route_distance of a route" : ""));
    for (int k = 0; k < count; ++k) {  // partial Fisher-Yates: the first `count` of a shuffle
      const std::size_t j =
          std::uniform_int_distribution<std::size_t>(std::size_t(k), pool.size() - 1)(rng_);
      std::swap(pool[std::size_t(k)], pool[j]);
    }
    pool.resize(std::size_t(count));
    std::sort(pool.begin(), pool.end());  // changes listed in map order within a kind
    for (const std::size_t i : pool) {
      changed_.insert(i);
      MapInstance& m = world_.truth.instances[i];
      changed_centres_.emplace_back(m.cls, instanceCentre(m));
      MapChange c;
      c.kind = kind;
      c.cls = m.cls;
      c.before = m;
      if (apply) {
        apply(m);
        c.after = m;
      } else {
        removed_.insert(i);
      }
      out.changes.push_back(std::move(c));
    }
  }

  void removeDrawn() {
    std::vector<MapInstance> kept;
    for (std::size_t i = 0; i < world_.truth.instances.size(); ++i)
      if (!removed_.count(i)) kept.push_back(std::move(world_.truth.instances[i]));
    world_.truth.instances = std::move(kept);
  }

  /// Dashed <-> solid; an arrow turned round its centre (point reflection in the ground plane).
  void retype(MapInstance& m) {
    if (m.cls == CrowdClass::kLaneLine) {
      m.attributes.style =
          m.attributes.style == LineStyle::kDashed ? LineStyle::kSolid : LineStyle::kDashed;
      m.note = "retyped by simulator change";
      return;
    }
    const Eigen::Vector3d c = footprintCentre(m.points);
    for (auto& p : m.points) moveOnGround(p, 2.0 * c.head<2>() - p.head<2>());
    m.note = "turned round by simulator change";
  }

  /// Centre of the arrow's extent along its longest vertex-pair axis and across it.
  static Eigen::Vector3d footprintCentre(const Polyline& ring) {
    Eigen::Vector2d axis(1, 0);
    double longest = 0.0;
    for (const auto& a : ring)
      for (const auto& b : ring)
        if ((a - b).head<2>().norm() > longest)
          longest = (a - b).head<2>().norm(), axis = (b - a).head<2>().normalized();
    const Eigen::Vector2d normal(-axis.y(), axis.x());
    double lo_a = 1e300, hi_a = -1e300, lo_n = 1e300, hi_n = -1e300;
    for (const auto& p : ring) {
      lo_a = std::min(lo_a, p.head<2>().dot(axis)), hi_a = std::max(hi_a, p.head<2>().dot(axis));
      lo_n = std::min(lo_n, p.head<2>().dot(normal)),
      hi_n = std::max(hi_n, p.head<2>().dot(normal));
    }
    const Eigen::Vector2d c = 0.5 * (lo_a + hi_a) * axis + 0.5 * (lo_n + hi_n) * normal;
    return {c.x(), c.y(), 0.0};
  }

  /// Shifted sideways by a in [shift_min, shift_max] (either side): over the whole line, or
  /// (lines of kMinStretchLine m or more, one in two) over a stretch with cosine ramps.
  void restripe(MapInstance& m) {
    const double a = uniform(s_.shift_min, s_.shift_max) * (coin() ? 1.0 : -1.0);
    const double length = polylineLength(m.points);
    if (length < kMinStretchLine || coin()) {
      moveOnGround(m.points, offsetLine(m.points, a));
      m.note = "restriped by simulator change";
      return;
    }
    const double stretch = uniform(3.0 * kStretchRamp, std::min(length, 10.0 * kStretchRamp));
    const double s0 = uniform(0.0, length - stretch);
    Polyline line = resample(m.points, kStretchStep);
    const std::vector<double> cum = arcLengths(line);
    Polyline out(line.size());
    for (std::size_t i = 0; i < line.size(); ++i) {
      const double into = std::min(cum[i] - s0, s0 + stretch - cum[i]);  // < 0 outside
      const double w = into <= 0.0            ? 0.0
                       : into >= kStretchRamp ? 1.0
                                              : 0.5 - 0.5 * std::cos(kPi * into / kStretchRamp);
      out[i] = line[i] + a * w * leftNormalAt(line, i);
    }
    moveOnGround(line, out);
    m.points = std::move(line);
    m.note = "restriped on a stretch by simulator change";
  }

  /// Along the nearest lane's direction (within kMoveMaxAngle), either way, by a distance in
  /// [move_min, move_max].
  void move(MapInstance& m) {
    const Eigen::Vector3d base = instanceCentre(m);
    Eigen::Vector2d t = nearestLaneDirection(base);
    const double angle = uniform(-kMoveMaxAngle, kMoveMaxAngle) + (coin() ? 0.0 : kPi);
    const Eigen::Vector2d d(std::cos(angle) * t.x() - std::sin(angle) * t.y(),
                            std::sin(angle) * t.x() + std::cos(angle) * t.y());
    const double distance = uniform(s_.move_min, s_.move_max);
    for (auto& p : m.points) moveOnGround(p, p.head<2>() + distance * d);
    m.note = "moved by simulator change";
  }

  Eigen::Vector2d nearestLaneDirection(const Eigen::Vector3d& p) const {
    double best = 1e300;
    Eigen::Vector2d dir(1, 0);
    for (const auto& lane : world_.lanes)
      for (std::size_t i = 0; i + 1 < lane.centerline.size(); ++i) {
        const double d = (lane.centerline[i] - p).head<2>().norm();
        const Eigen::Vector2d seg = (lane.centerline[i + 1] - lane.centerline[i]).head<2>();
        if (d < best && seg.norm() > 1e-6) best = d, dir = seg.normalized();
      }
    return dir;
  }

  /// A new element: a sign or pole beside a lane, an arrow in one, a stop line across its end
  /// (or across it); kPlacementTries draws of a lane and a place, the first clear one taken.
  void add(MapChanges& out) {
    static const CrowdClass kClasses[] = {CrowdClass::kTrafficSign, CrowdClass::kPole,
                                          CrowdClass::kGroundArrow, CrowdClass::kStopLine};
    const CrowdClass cls = kClasses[std::uniform_int_distribution<int>(0, 3)(rng_)];
    for (int attempt = 0; attempt < kPlacementTries; ++attempt) {
      const Lane& lane =
          world_
              .lanes[std::uniform_int_distribution<std::size_t>(0, world_.lanes.size() - 1)(rng_)];
      const double length = polylineLength(lane.centerline);
      if (length < kMinAddLane) continue;
      MapInstance m;
      m.cls = cls;
      m.id = nextId();
      m.source_ids = {m.id};
      m.note = "added by simulator change";
      // A stop line goes across a lane end; where every end has one already (the procedural
      // world's), the second half of the tries place it across the lane (a new stop).
      const bool at_end = cls == CrowdClass::kStopLine && attempt < kPlacementTries / 2;
      placeNew(m, lane, at_end ? length - kLaneEndGap : uniform(10.0, length - 10.0));
      if (!isClear(m) || !scope_.holds(m)) continue;
      world_.truth.instances.push_back(m);
      MapChange c;
      c.kind = ChangeKind::kAdded;
      c.cls = cls;
      c.after = std::move(m);
      out.changes.push_back(std::move(c));
      return;
    }
    throw ConfigError("change_added = " + std::to_string(s_.added) + ": no clear place for a " +
                      crowdClassName(cls) + " left in the world " + world_.name + " after " +
                      std::to_string(kPlacementTries) + " tries");
  }

  int64_t nextId() const {
    int64_t id = 0;
    for (const auto& m : world_.truth.instances) id = std::max(id, m.id);
    return id + 1;
  }

  /// The geometry of a new element of m.cls at arc length s of the lane.
  void placeNew(MapInstance& m, const Lane& lane, double s) const {
    const std::vector<double> cum = arcLengths(lane.centerline);
    const Eigen::Vector3d c = pointAt(lane.centerline, cum, s);
    Eigen::Vector3d t =
        pointAt(lane.centerline, cum, s + 0.5) - pointAt(lane.centerline, cum, s - 0.5);
    t.z() = 0.0;
    t.normalize();
    const Eigen::Vector3d n(-t.y(), t.x(), 0.0);  // left
    const Eigen::Vector3d up(0, 0, 1);
    Eigen::Vector3d side = c;  // right of the lane, on the ground
    moveOnGround(side, (c - (0.5 * lane.width + kRoadsideGap) * n).head<2>());
    const double h = 0.5 * kAddedSignSize;
    switch (m.cls) {
      case CrowdClass::kPole:
        m.points = {side};
        m.height = kAddedPoleHeight;
        break;
      case CrowdClass::kTrafficSign:  // a plate facing the lane's traffic
        m.points = {side + h * n + kAddedSignBottom * up, side - h * n + kAddedSignBottom * up,
                    side - h * n + (kAddedSignBottom + kAddedSignSize) * up,
                    side + h * n + (kAddedSignBottom + kAddedSignSize) * up};
        break;
      case CrowdClass::kGroundArrow:
        for (const auto& q : kArrowShape) {
          m.points.push_back(c);
          moveOnGround(m.points.back(), (c + q.x() * t + q.y() * n).head<2>());
        }
        break;
      default:  // stop line across the lane
        m.points = {c, c};
        moveOnGround(m.points[0], (c + 0.5 * lane.width * n).head<2>());
        moveOnGround(m.points[1], (c - 0.5 * lane.width * n).head<2>());
        break;
    }
  }

  /// No element of the class (nor where a changed one stood) within kAddedClearance; a sign or
  /// pole off every lane.
  bool isClear(const MapInstance& m) const {
    const Eigen::Vector3d c = instanceCentre(m);
    for (const auto& other : world_.truth.instances)
      if (other.cls == m.cls && (instanceCentre(other) - c).head<2>().norm() < kAddedClearance)
        return false;
    for (const auto& [cls, centre] : changed_centres_)
      if (cls == m.cls && (centre - c).head<2>().norm() < kAddedClearance) return false;
    if (m.cls != CrowdClass::kPole && m.cls != CrowdClass::kTrafficSign) return true;
    for (const auto& lane : world_.lanes)
      if (distanceToPolyline(lane.centerline, m.points.front()) < 0.5 * lane.width + 0.5)
        return false;
    return true;
  }

  World& world_;
  const ChangeSettings& s_;
  std::mt19937_64 rng_;
  RouteScope scope_;
  std::set<std::size_t> changed_, removed_;
  /// Where changed elements stood before: additions keep clear of them too.
  std::vector<std::pair<CrowdClass, Eigen::Vector3d>> changed_centres_;
};

}  // namespace

MapChanges applyWorldChanges(World& world, const ChangeSettings& settings,
                             const std::vector<Polyline>& routes) {
  if (settings.total() == 0) return {world.truth.origin, "simulate change truth", {}};
  return Changer(world, settings, routes).run();
}

}  // namespace mapfuse::sim
