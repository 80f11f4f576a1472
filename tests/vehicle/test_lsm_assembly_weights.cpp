// lsm-build's assembly averages the frames' observations of a line weighted by their ranging
// covariance (vehicle/lsm_assembly.cpp): a stretch seen near and far lands where the near view
// puts it. Far views carry what eq. (1) does not model (the road's height ahead) as a range
// error that grows ~d²; equal weights let them pull the line.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>

#include "mapfuse/vehicle/lsm_assembly.hpp"

using namespace mapfuse;
using namespace mapfuse::vehicle;

namespace {
constexpr double kTrueY = 2.0;         // m, the line's lateral position
constexpr double kFarBias = 0.3;       // m, the far view's lateral error
constexpr double kNearSigma = 0.02;    // m, ranging sigma 5 m ahead
constexpr double kFarSigma = 0.32;     // m, ~16x the near one: 20 m ahead (σ ∝ d²)
constexpr double kWeightedTol = 0.01;  // m: the near view dominates (bias / (1 + 256) = 1 mm)

RangedMarking view(int frame, double bias, double sigma) {
  RangedMarking m;
  m.cls = CrowdClass::kLaneLine;
  m.track_id = 7;  // one physical line
  m.frame = frame;
  for (double x = 20.0; x <= 24.0; x += 0.25) {
    m.points.emplace_back(x, kTrueY + bias, 0.0);
    m.covariances.push_back(Eigen::Vector3d(sigma * sigma, sigma * sigma, 1e-4).asDiagonal());
  }
  return m;
}
/// 30 frames 1 m apart along x, 0.1 s apart.
void straightDrive(std::vector<Pose3>& poses, std::vector<double>& stamps) {
  for (int k = 0; k < 30; ++k) {
    Pose3 T = Pose3::Identity();
    T.translation() = Eigen::Vector3d(double(k), 0.0, 0.0);
    poses.push_back(T);
    stamps.push_back(0.1 * k);
  }
}
}  // namespace

TEST_CASE("lsm assembly: a line seen near and far lands where the near view puts it") {
  std::vector<Pose3> poses;
  std::vector<double> stamps;
  straightDrive(poses, stamps);
  // Frame 2 sees the stretch 18-22 m ahead, biased; frame 17 sees it 3-7 m ahead.
  const std::vector<RangedMarking> markings = {view(2, kFarBias, kFarSigma),
                                               view(17, 0.0, kNearSigma)};
  const Lsm lsm = assembleLsm(poses, stamps, {0, 10, 20, 29}, markings, {}, AssemblySettings{});
  REQUIRE(lsm.elements.size() == 1);
  const Element& e = lsm.elements[0];
  const Pose3& anchor = lsm.keyframes[std::size_t(e.anchor)].T_frame_body;
  double worst = 0.0;
  for (const auto& p : e.points_body) worst = std::max(worst, std::abs((anchor * p).y() - kTrueY));
  INFO("largest lateral error " << worst << " m (equal weights: " << kFarBias / 2 << " m)");
  CHECK(worst <= kWeightedTol);
}

TEST_CASE("lsm assembly: a ghost seen only from afar beside a line is not mapped, and is counted") {
  // A line seen near by two frames; a ghost of it (far views ranged 1 m aside where the road
  // ahead was not what eq. (1) assumed) seen only from afar; and another line 6 m aside, also
  // seen only from afar, with nothing sound near it: all there is of that line.
  std::vector<Pose3> poses;
  std::vector<double> stamps;
  straightDrive(poses, stamps);
  AssemblySettings s;
  // per axis; three frames average to a sample whose horizontal σ is σ √(2/3): 1.6x the gate
  const double far_sigma = 2.0 * s.max_line_sigma;
  std::vector<RangedMarking> markings = {view(16, 0.0, kNearSigma), view(17, 0.0, kNearSigma)};
  for (int f : {1, 2, 3}) {
    RangedMarking ghost = view(f, 1.0, far_sigma);
    ghost.track_id = 8;
    markings.push_back(ghost);
    RangedMarking other = view(f, 6.0, far_sigma);
    other.track_id = 9;
    markings.push_back(other);
  }
  AssemblyStats st;
  const Lsm lsm = assembleLsm(poses, stamps, {0, 10, 20, 29}, markings, {}, s, &st);
  REQUIRE(lsm.elements.size() == 2);  // the near line and the lone far one
  int near = 0, lone = 0;
  for (const auto& e : lsm.elements) {
    const Pose3& anchor = lsm.keyframes[std::size_t(e.anchor)].T_frame_body;
    const double y = (anchor * e.points_body.front()).y();
    near += std::abs(y - kTrueY) <= kWeightedTol;
    lone += std::abs(y - kTrueY - 6.0) <= kWeightedTol;
  }
  CHECK(near == 1);
  CHECK(lone == 1);
  CHECK(st.line_samples_dropped >= 8);  // the ghost's 4 m at 0.5 m spacing
  CHECK(st.line_samples_dropped < st.line_samples);
  // With the gate opened the ghost is mapped: the gate, not the grouping, removed it.
  s.max_line_sigma = 10.0;
  CHECK(assembleLsm(poses, stamps, {0, 10, 20, 29}, markings, {}, s).elements.size() == 3);
}

TEST_CASE(
    "lsm assembly: far views spilling past a dash's end are not mapped where the drive passed") {
  // A dash from 20 to 23 m seen near by two frames; three far frames saw it 1-4 m too far
  // (their range error runs along the view) and 0.3 m aside: beyond 23 m only they put paint,
  // where the two near frames, which passed there, saw none. The same spill past a dash ahead of
  // the drive's last frame is all there is of it and stays.
  std::vector<Pose3> poses;
  std::vector<double> stamps;
  straightDrive(poses, stamps);  // frames at x = 0..29 m
  const AssemblySettings s;
  auto dash = [](int frame, double x0, double x1, double bias, double sigma, int64_t track) {
    RangedMarking m;
    m.cls = CrowdClass::kLaneLine;
    m.track_id = track;
    m.frame = frame;
    for (double x = x0; x <= x1 + 1e-9; x += 0.25) {
      m.points.emplace_back(x, kTrueY + bias, 0.0);
      m.covariances.push_back(Eigen::Vector3d(sigma * sigma, sigma * sigma, 1e-4).asDiagonal());
    }
    return m;
  };
  constexpr double kSpillSigma = 0.3;  // m: 15x the near one, under max_line_sigma
  constexpr double kSpillBias = 0.3;   // m aside
  constexpr double kDashEnd = 23.0;    // m, where the paint ends
  constexpr double kEndTol = 0.5;      // m: one sample spacing
  std::vector<RangedMarking> markings = {dash(16, 20.0, kDashEnd, 0.0, kNearSigma, 7),
                                         dash(17, 20.0, kDashEnd, 0.0, kNearSigma, 7)};
  for (int f : {1, 2, 3}) markings.push_back(dash(f, 21.0, 27.0, kSpillBias, kSpillSigma, 7));
  // a dash 30-33 m, beyond the last frame (29 m): seen by frames 27-29, far views reach 36 m
  for (int f : {27, 28}) markings.push_back(dash(f, 30.0, 33.0, 0.0, kNearSigma, 8));
  for (int f : {25, 26, 27}) markings.push_back(dash(f, 31.0, 36.0, kSpillBias, kSpillSigma, 8));
  AssemblyStats st;
  const Lsm lsm = assembleLsm(poses, stamps, {0, 10, 20, 29}, markings, {}, s, &st);
  double passed_end = -1e9, ahead_end = -1e9;
  for (const auto& e : lsm.elements) {
    const Pose3& anchor = lsm.keyframes[std::size_t(e.anchor)].T_frame_body;
    for (const auto& pb : e.points_body) {
      const Eigen::Vector3d p = anchor * pb;
      if (p.x() < 29.0)
        passed_end = std::max(passed_end, p.x());
      else
        ahead_end = std::max(ahead_end, p.x());
    }
  }
  INFO("passed dash ends at " << passed_end << " m, the dash ahead at " << ahead_end << " m");
  CHECK(std::abs(passed_end - kDashEnd) <= kEndTol);
  CHECK(ahead_end >= 36.0 - kEndTol);  // beyond the drive: the far views are all there is
  CHECK(st.line_samples_spill >= 6);   // 23.5-27 m at 0.5 m spacing
  // With the ratio opened the spill is mapped: the rule, not the grouping, removed it.
  AssemblySettings open = s;
  open.line_end_sigma_ratio = 1000.0;
  AssemblyStats st_open;
  assembleLsm(poses, stamps, {0, 10, 20, 29}, markings, {}, open, &st_open);
  CHECK(st_open.line_samples_spill == 0);
}

TEST_CASE("lsm assembly: a crosswalk's outline comes from its certain views, not their union") {
  // A 4 x 7 m crosswalk 20-24 m ahead seen whole by four near frames (mask outlines of five
  // vertices) and, partially and skewed, by three far ones (oblique views while the drive
  // turns: 2 m off at one side, 8x the sigma). Of every view, the far ones are the only rings of
  // four corners and make the outline; of the certain views, the near views' hull does.
  std::vector<Pose3> poses;
  std::vector<double> stamps;
  straightDrive(poses, stamps);
  constexpr double kCwSigma = 0.05, kObliqueSigma = 0.4;  // m
  constexpr double kOutlineTol = 0.3;                       // m, each corner
  auto ring = [](int frame, std::vector<Eigen::Vector3d> pts, double sigma) {
    RangedMarking m;
    m.cls = CrowdClass::kCrosswalk;
    m.track_id = 3;
    m.frame = frame;
    m.points = std::move(pts);
    m.covariances.assign(m.points.size(),
                         Eigen::Vector3d(sigma * sigma, sigma * sigma, 1e-4).asDiagonal());
    return m;
  };
  const std::vector<Eigen::Vector3d> truth = {
      {20, -3.5, 0}, {24, -3.5, 0}, {24, 3.5, 0}, {20, 3.5, 0}};
  std::vector<RangedMarking> markings;
  for (int f : {14, 15, 16, 17}) {
    auto pts = truth;
    pts.emplace_back(22.0, 3.5, 0.0);  // a mask outline: five vertices, one on an edge
    markings.push_back(ring(f, pts, kCwSigma));
  }
  for (int f : {2, 3, 4})  // a far partial view, its far side 2 m beyond and skewed
    markings.push_back(ring(f, {{20, 0, 0}, {24, 0, 0}, {26, 3.5, 0}, {21, 5.5, 0}}, kObliqueSigma));
  auto outline = [&](const AssemblySettings& s) {
    const Lsm lsm = assembleLsm(poses, stamps, {0, 10, 20, 29}, markings, {}, s);
    REQUIRE(lsm.elements.size() == 1);
    const Element& e = lsm.elements[0];
    const Pose3& anchor = lsm.keyframes[std::size_t(e.anchor)].T_frame_body;
    double worst = 0.0;  // the farthest of the true corners from the outline's nearest vertex
    for (const auto& t : truth) {
      double best = 1e9;
      for (const auto& pb : e.points_body) best = std::min(best, ((anchor * pb) - t).norm());
      worst = std::max(worst, best);
    }
    return std::make_pair(worst, e.points_body.size());
  };
  const auto [certain, n] = outline(AssemblySettings{});
  INFO("certain views: worst corner " << certain << " m, " << n << " vertices");
  CHECK(certain <= kOutlineTol);
  AssemblySettings all;
  all.area_sigma_ratio = 1000.0;
  CHECK(outline(all).first > 1.0);  // the union: the oblique views' corners
}
