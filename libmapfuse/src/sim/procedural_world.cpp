#include "mapfuse/sim/procedural_world.hpp"

#include <cmath>
#include <random>

#include "mapfuse/core/angles.hpp"
#include "mapfuse/core/error.hpp"

namespace mapfuse::sim {

namespace {

constexpr double kPolylineStep = 1.0;      // m, spacing of generated polylines
constexpr double kSignBottom = 2.0;        // m, sign lower edge above the road
constexpr double kSignSize = 0.6;          // m, square sign edge
constexpr double kLightBottom = 2.8;       // m, traffic-light housing lower edge
constexpr double kLightHeight = 0.9;       // m, housing height (red/yellow/green)
constexpr double kLampHeight = 8.0;        // m, street lamp pole height
constexpr double kArrowBeforeStop = 12.0;  // m, arrow centre before the stop line

struct WorldBuilder {
  World world;
  int64_t next_lane = 1;
  int64_t next_instance = 1;
  std::mt19937_64 rng;

  explicit WorldBuilder(uint64_t seed) : rng(seed) {}
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }

  void addLane(Polyline centerline, double width) {
    Lane lane;
    lane.id = next_lane++;
    lane.centerline = std::move(centerline);
    lane.width = width;
    world.lanes.push_back(std::move(lane));
  }
  MapInstance& addInstance(CrowdClass cls, Polyline points, const std::string& note = "") {
    MapInstance& m = world.addTruth(next_instance++, cls, std::move(points), note);
    if (cls == CrowdClass::kLaneLine) m.attributes.color = LineColor::kWhite;
    return m;
  }
  void addLine(const Polyline& line, LineStyle style) {
    addInstance(CrowdClass::kLaneLine, line).attributes.style = style;
  }
  /// Rectangle/polygon in the road frame at arc position (p, tangent t, left n).
  Polyline local(const Eigen::Vector3d& p, const Eigen::Vector3d& t, const Eigen::Vector3d& n,
                 const std::vector<Eigen::Vector2d>& xy, double z = 0.0) {
    Polyline ring;
    for (const auto& q : xy) ring.push_back(p + q.x() * t + q.y() * n + Eigen::Vector3d(0, 0, z));
    return ring;
  }
};

struct Frame {
  Eigen::Vector3d p, t, n;  // point, unit tangent, unit left normal
};

Frame frameAt(const Polyline& line, double s) {
  const auto cum = arcLengths(line);
  Frame f;
  f.p = pointAt(line, cum, s);
  const Eigen::Vector3d a = pointAt(line, cum, s - 0.5), b = pointAt(line, cum, s + 0.5);
  f.t = (b - a).normalized();
  f.n = Eigen::Vector3d(-f.t.y(), f.t.x(), 0.0);
  return f;
}

Polyline bezier(const Eigen::Vector3d& p0, const Eigen::Vector3d& t0, const Eigen::Vector3d& p3,
                const Eigen::Vector3d& t3) {
  const double d = (p3 - p0).norm();
  const Eigen::Vector3d p1 = p0 + t0 * d / 3.0, p2 = p3 - t3 * d / 3.0;
  const int n = std::max(2, static_cast<int>(std::ceil(d / kPolylineStep)));
  Polyline out;
  for (int k = 0; k <= n; ++k) {
    const double s = static_cast<double>(k) / n, u = 1.0 - s;
    out.push_back(u * u * u * p0 + 3 * u * u * s * p1 + 3 * u * s * s * p2 + s * s * s * p3);
  }
  return out;
}

/// End of a road at an intersection: the lanes arriving and leaving there.
struct Arm {
  std::vector<std::size_t> in_lanes, out_lanes;  // lane indices, inner lane first
};

double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

/// Lifts every lane and true element onto the terrain z = A (sin(kx + a) + sin(ky + b)): each
/// point keeps its height above the road surface beneath it.
void liftOntoTerrain(World& world, const ProceduralParams& P, double phase_a, double phase_b) {
  if (P.hill_grade <= 0.0) return;
  const double k = 2.0 * kPi / P.hill_wavelength, A = P.hill_grade / k;
  world.surface_height = [k, A, phase_a, phase_b](const Eigen::Vector3d& q) {
    return A * (std::sin(k * q.x() + phase_a) + std::sin(k * q.y() + phase_b));
  };
  auto lift = [&](Eigen::Vector3d& p) { p.z() += world.surface_height(p); };
  for (Lane& lane : world.lanes)
    for (auto& p : lane.centerline) lift(p);
  for (MapInstance& m : world.truth.instances)
    for (auto& p : m.points) lift(p);
  world.stats["hill_amplitude_m"] = 2.0 * A;
}

/// Intersection centres on the grid, each shifted by a random jitter.
std::vector<Eigen::Vector3d> intersectionCentres(WorldBuilder& B, const ProceduralParams& P) {
  const int G = P.grid_size;
  std::vector<Eigen::Vector3d> centre(G * G);
  for (int i = 0; i < G; ++i)
    for (int j = 0; j < G; ++j) {
      // y's jitter drawn first: the order the release (gcc) build used (sim/draw_order.hpp).
      const double jitter_y = B.uniform(-P.jitter, P.jitter);
      const double jitter_x = B.uniform(-P.jitter, P.jitter);
      centre[i * G + j] = Eigen::Vector3d((i - (G - 1) / 2.0) * P.block_length + jitter_x,
                                          (j - (G - 1) / 2.0) * P.block_length + jitter_y, 0.0);
    }
  return centre;
}

/// One road between intersections a and b: its reference line, bulging sideways by `amp`.
struct Road {
  int a = 0, b = 0;
  Polyline ref;
  int lanes = 1;
  double length = 0.0;
};

/// The bypass lane: forks off the outer forward lane `fwd` and merges back (a fork + a merge),
/// with its own solid edges.
void addBypass(WorldBuilder& B, const Polyline& fwd, double L, double w, Arm& arm_a, Arm& arm_b) {
  const double s1 = 0.25 * L, s2 = 0.75 * L, ramp = 0.2 * L, D = 3.0 * w;
  Polyline branch, right_edge, left_edge;
  // Samples span [s1, s2] exactly, so the branch ends where the merge lane starts.
  const int nb = static_cast<int>(std::ceil((s2 - s1) / kPolylineStep));
  for (int k = 0; k <= nb; ++k) {
    const double s = s1 + (s2 - s1) * k / nb;
    const Frame f = frameAt(fwd, s);
    const double d = D * (smoothstep((s - s1) / ramp) * smoothstep((s2 - s) / ramp));
    branch.push_back(f.p - d * f.n);
    right_edge.push_back(f.p - (d + w / 2) * f.n);
    if (d >= w) left_edge.push_back(f.p - (d - w / 2) * f.n);
  }
  B.addLane(subLine(fwd, 0, s1, kPolylineStep), w);
  arm_a.out_lanes.push_back(B.world.lanes.size() - 1);
  B.addLane(subLine(fwd, s1, s2, kPolylineStep), w);
  B.addLane(branch, w);
  B.addLane(subLine(fwd, s2, L, kPolylineStep), w);
  arm_b.in_lanes.push_back(B.world.lanes.size() - 1);
  B.addLine(right_edge, LineStyle::kSolid);
  if (left_edge.size() >= 2) B.addLine(left_edge, LineStyle::kSolid);
}

/// Lanes: forward (a->b) on the right, backward on the left; inner lane first. The first road
/// long enough gets the bypass on its outer forward lane.
void addLanes(WorldBuilder& B, const Road& r, double w, Arm& arm_a, Arm& arm_b, bool& fork_done) {
  for (int k = 0; k < r.lanes; ++k) {
    const Polyline fwd = offsetLine(r.ref, -(k + 0.5) * w);
    if (!fork_done && k == r.lanes - 1 && r.length > 150.0) {
      fork_done = true;
      addBypass(B, fwd, r.length, w, arm_a, arm_b);
    } else {
      B.addLane(fwd, w);
      arm_a.out_lanes.push_back(B.world.lanes.size() - 1);
      arm_b.in_lanes.push_back(B.world.lanes.size() - 1);
    }
    B.addLane(reversed(offsetLine(r.ref, (k + 0.5) * w)), w);
    arm_b.out_lanes.push_back(B.world.lanes.size() - 1);
    arm_a.in_lanes.push_back(B.world.lanes.size() - 1);
  }
}

/// Lane lines (solid centre and edges, dashed between lanes) and street lamps, alternating sides.
void addLinesAndLamps(WorldBuilder& B, const ProceduralParams& P, const Road& r) {
  const double w = P.lane_width;
  B.addLine(r.ref, LineStyle::kSolid);
  for (int k = 1; k < r.lanes; ++k) {
    B.addLine(offsetLine(r.ref, -k * w), LineStyle::kDashed);
    B.addLine(reversed(offsetLine(r.ref, k * w)), LineStyle::kDashed);
  }
  B.addLine(offsetLine(r.ref, -r.lanes * w), LineStyle::kSolid);
  B.addLine(reversed(offsetLine(r.ref, r.lanes * w)), LineStyle::kSolid);
  int side = 1;
  for (double s = P.pole_spacing / 2; s < r.length - 20.0; s += P.pole_spacing, side = -side) {
    const Frame f = frameAt(r.ref, s);
    B.addInstance(CrowdClass::kPole, {f.p + side * (r.lanes * w + 2.0) * f.n}).height = kLampHeight;
  }
}

/// One road end arriving at `node` along `dirline`: stop line, arrows, sign + pole, light +
/// pole where the intersection has lights, crosswalk (always with lights, else drawn).
void addRoadEnd(WorldBuilder& B, const ProceduralParams& P, const Road& r, const Polyline& dirline,
                bool lights) {
  const double w = P.lane_width, L = r.length;
  const Frame f = frameAt(dirline, L);
  const Eigen::Vector3d inner = f.p, outer = f.p - r.lanes * w * f.n;
  B.addInstance(CrowdClass::kStopLine, {inner, outer});
  if (L > 3 * kArrowBeforeStop)
    for (int k = 0; k < r.lanes; ++k) {
      const Frame g = frameAt(dirline, L - kArrowBeforeStop);
      const Eigen::Vector3d c = g.p - (k + 0.5) * w * g.n;
      B.addInstance(CrowdClass::kGroundArrow, B.local(c, g.t, g.n,
                                                      {{-2.5, -0.15},
                                                       {1.0, -0.15},
                                                       {1.0, -0.6},
                                                       {2.5, 0.0},
                                                       {1.0, 0.6},
                                                       {1.0, 0.15},
                                                       {-2.5, 0.15}}));
    }
  const Frame g = frameAt(dirline, L - 5.0);
  const Eigen::Vector3d sc = g.p - (r.lanes * w + 1.5) * g.n;
  const double h = kSignSize / 2;
  B.addInstance(CrowdClass::kTrafficSign,
                B.local(sc, g.t, g.n, {{0, h}, {0, -h}, {0, -h}, {0, h}}, 0.0));
  auto& sign = B.world.truth.instances.back();
  sign.points[0].z() = sign.points[1].z() = kSignBottom;
  sign.points[2].z() = sign.points[3].z() = kSignBottom + kSignSize;
  B.addInstance(CrowdClass::kPole, {sc}, "pole under a sign").height = kSignBottom + kSignSize;
  const Eigen::Vector3d cw0 = f.p + 1.0 * f.t;
  if (lights) {
    const Eigen::Vector3d lc = f.p + 0.5 * f.t - (r.lanes * w + 1.0) * f.n;
    B.addInstance(CrowdClass::kTrafficLight, {lc + Eigen::Vector3d(0, 0, kLightBottom)}).height =
        kLightHeight;
    B.addInstance(CrowdClass::kPole, {lc}, "pole under a traffic light").height = kLightBottom;
  }
  if (lights || B.uniform(0, 1) < P.crosswalk_probability) {
    const double left = r.lanes * w, depth = 4.0;
    B.addInstance(CrowdClass::kCrosswalk,
                  B.local(cw0, f.t, f.n, {{0, -left}, {depth, -left}, {depth, left}, {0, left}}));
  }
}

/// The road between intersections a and b (draws: its bulge, its lanes per direction, then the
/// crosswalks of its two ends) with everything on it.
void addRoad(WorldBuilder& B, const ProceduralParams& P, const std::vector<Eigen::Vector3d>& centre,
             int a, int b, const std::vector<bool>& has_lights, std::vector<std::vector<Arm>>& arms,
             bool& fork_done) {
  const Eigen::Vector3d u = (centre[b] - centre[a]).normalized();
  const Eigen::Vector3d nrm(-u.y(), u.x(), 0.0);
  const Eigen::Vector3d p0 = centre[a] + P.intersection_radius * u;
  const Eigen::Vector3d p1 = centre[b] - P.intersection_radius * u;
  Road r;
  r.a = a, r.b = b;
  const double amp = B.uniform(-P.curve_amplitude, P.curve_amplitude);
  r.lanes = 1 + static_cast<int>(B.uniform(0, P.max_lanes_per_direction - 1e-9));
  const int n = static_cast<int>(std::ceil((p1 - p0).norm() / kPolylineStep));
  for (int k = 0; k <= n; ++k) {
    const double s = static_cast<double>(k) / n;
    r.ref.push_back(p0 + s * (p1 - p0) + amp * std::pow(std::sin(kPi * s), 2) * nrm);
  }
  r.length = polylineLength(r.ref);
  B.world.stats["road_km"] += r.length / 1000.0;
  Arm& arm_a = arms[a].emplace_back();
  Arm& arm_b = arms[b].emplace_back();
  addLanes(B, r, P.lane_width, arm_a, arm_b, fork_done);
  addLinesAndLamps(B, P, r);
  addRoadEnd(B, P, r, r.ref, has_lights[b]);            // arriving at b
  addRoadEnd(B, P, r, reversed(r.ref), has_lights[a]);  // arriving at a
}

/// Intersection connectors: every arriving lane to every leaving arm (no U-turns).
void addConnectors(WorldBuilder& B, const std::vector<std::vector<Arm>>& arms, double w) {
  for (const auto& node : arms)
    for (std::size_t ai = 0; ai < node.size(); ++ai)
      for (std::size_t bi = 0; bi < node.size(); ++bi) {
        if (ai == bi) continue;
        const Arm &in = node[ai], &out = node[bi];
        for (std::size_t li = 0; li < in.in_lanes.size(); ++li) {
          const std::size_t lo = std::min(li, out.out_lanes.size() - 1);
          const Polyline& c_in = B.world.lanes[in.in_lanes[li]].centerline;
          const Polyline& c_out = B.world.lanes[out.out_lanes[lo]].centerline;
          const Eigen::Vector3d t0 = (c_in.back() - c_in[c_in.size() - 2]).normalized();
          const Eigen::Vector3d t3 = (c_out[1] - c_out.front()).normalized();
          B.addLane(bezier(c_in.back(), t0, c_out.front(), t3), w);
        }
      }
}

}  // namespace

World buildProceduralWorld(const ProceduralParams& P, const geo::GeoOrigin& origin, uint64_t seed) {
  if (P.block_length < 2.0 * P.intersection_radius + 40.0)
    throw ConfigError(
        "procedural world: world_block_length must exceed 2 * "
        "world_intersection_radius + 40 m");
  WorldBuilder B(seed);
  B.world.name = "procedural";
  B.world.truth.origin = origin;
  B.world.truth.source = "simulate ground truth (procedural world)";
  const int G = P.grid_size;
  const std::vector<Eigen::Vector3d> centre = intersectionCentres(B, P);
  std::vector<std::vector<Arm>> arms(G * G);
  std::vector<bool> has_lights(G * G);
  for (int k = 0; k < G * G; ++k) has_lights[k] = B.uniform(0, 1) < P.traffic_light_fraction;
  bool fork_done = false;
  // Roads between grid neighbours.
  for (int i = 0; i < G; ++i)
    for (int j = 0; j < G; ++j)
      for (int dir = 0; dir < 2; ++dir) {
        const int i2 = i + (dir == 0), j2 = j + (dir == 1);
        if (i2 < G && j2 < G)
          addRoad(B, P, centre, i * G + j, i2 * G + j2, has_lights, arms, fork_done);
      }
  addConnectors(B, arms, P.lane_width);
  connectLanesByEndpoints(B.world, 0.05);
  if (P.hill_grade > 0.0) {  // drawn only for a hilly world: flat worlds keep their draws
    const double phase_a = B.uniform(0, 2 * kPi), phase_b = B.uniform(0, 2 * kPi);
    liftOntoTerrain(B.world, P, phase_a, phase_b);
  }
  B.world.stats["intersections"] = G * G;
  B.world.stats["roads"] = 2.0 * G * (G - 1);
  return std::move(B.world);
}

}  // namespace mapfuse::sim
