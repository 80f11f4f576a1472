// Map-relative registration of a new drive (docs/update.md "Registration to the map"): a drive
// whose georeferencing error drifts along it, over a world where some elements changed, is
// brought back onto the map; the truth is the world the drive's observations were made from.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "mapfuse/update/change_detection.hpp"
#include "mapfuse/update/map_registration.hpp"

namespace mapfuse {
namespace {

const geo::GeoOrigin kOrigin{49.0, 8.4, 110.0};
constexpr double kRoad = 900.0;          // m, a straight road along +x (east)
constexpr double kKeyframeStep = 5.0;    // m between keyframes
constexpr double kNoise = 0.03;          // m, 1-sigma of the observed points
constexpr double kRegisteredRms = 0.10;  // m, the brief's bound on unchanged elements
// The injected error: (0.8, 0.3) m at the start drifting linearly to (-0.5, -0.4) m at the end.
const Eigen::Vector3d kDriftStart(0.8, 0.3, 0.0), kDriftEnd(-0.5, -0.4, 0.0);

Eigen::Vector3d drift(double x) {
  return kDriftStart + (kDriftEnd - kDriftStart) * (x / kRoad);
}

// Truth of one element: class, style, world points; `changed` marks elements whose
// observation differs from the map (moved, restriped) or that the map lacks (added).
struct TruthElement {
  CrowdClass cls;
  LineStyle style;
  std::vector<Eigen::Vector3d> world;  ///< as observed (the world after the changes)
  bool changed = false;
};

struct World {
  VectorMap map;                    ///< before the changes
  std::vector<TruthElement> after;  ///< what the drive observes
};

void addMap(World& w, CrowdClass cls, LineStyle style, std::vector<Eigen::Vector3d> pts) {
  MapInstance m;
  m.id = int64_t(w.map.instances.size()) + 1;
  m.cls = cls;
  m.attributes = {style, cls == CrowdClass::kLaneLine ? LineColor::kWhite : LineColor::kNone};
  m.points = std::move(pts);
  m.height = cls == CrowdClass::kPole ? 4.0 : 0.0;
  w.map.instances.push_back(m);
}

std::vector<Eigen::Vector3d> sign(double x) {
  return {{x, 6.0, 2.0}, {x, 6.8, 2.0}, {x, 6.8, 2.8}, {x, 6.0, 2.8}};
}

// Lane lines at y = -3.5 (solid), 0 (dashed, 3 m dashes every 9 m), 3.5 (solid); poles every
// 30 m alternating at y = +-6; a sign every 90 m. Changes: 4 poles moved 1.5 m, 3 removed, 3
// added, the right line re-striped 0.6 m over x in [400, 460].
World makeWorld() {
  World w;
  w.map.origin = kOrigin;
  std::vector<Eigen::Vector3d> right, left, centre;
  for (double x = 0; x <= kRoad; x += 1.0) {
    right.emplace_back(x, -3.5, 0);
    left.emplace_back(x, 3.5, 0);
    centre.emplace_back(x, 0, 0);
  }
  addMap(w, CrowdClass::kLaneLine, LineStyle::kSolid, right);
  addMap(w, CrowdClass::kLaneLine, LineStyle::kSolid, left);
  addMap(w, CrowdClass::kLaneLine, LineStyle::kDashed, centre);
  for (double x0 = 0; x0 + 20 <= kRoad; x0 += 20) {  // observed lines in 20 m pieces
    std::vector<Eigen::Vector3d> r, l;
    bool restriped = false;
    for (double x = x0; x <= x0 + 20; x += 0.75) {
      const bool shifted = x >= 400 && x <= 460;
      restriped |= shifted;
      r.emplace_back(x, shifted ? -2.9 : -3.5, 0);
      l.emplace_back(x, 3.5, 0);
    }
    w.after.push_back({CrowdClass::kLaneLine, LineStyle::kSolid, r, restriped});
    w.after.push_back({CrowdClass::kLaneLine, LineStyle::kSolid, l, false});
  }
  for (double x0 = 0; x0 + 3 <= kRoad; x0 += 9) {
    std::vector<Eigen::Vector3d> dash;
    for (double x = x0; x <= x0 + 3 + 1e-9; x += 0.75) dash.emplace_back(x, 0, 0);
    w.after.push_back({CrowdClass::kLaneLine, LineStyle::kDashed, dash, false});
  }
  int k = 0;
  for (double x = 15; x < kRoad; x += 30, ++k) {
    const Eigen::Vector3d p(x, k % 2 ? 6.0 : -6.0, 0);
    addMap(w, CrowdClass::kPole, LineStyle::kNone, {p});
    if (k % 7 == 3) continue;  // removed: the drive does not see it
    const bool moved = k % 7 == 5;
    w.after.push_back(
        {CrowdClass::kPole, LineStyle::kNone, {p + Eigen::Vector3d(moved ? 1.5 : 0, 0, 0)}, moved});
    if (k % 10 == 1)  // added: a pole the map does not have
      w.after.push_back({CrowdClass::kPole,
                         LineStyle::kNone,
                         {p + Eigen::Vector3d(7, -12.0 * (k % 2), 0)},
                         true});
  }
  for (double x = 45; x < kRoad; x += 90) {
    addMap(w, CrowdClass::kTrafficSign, LineStyle::kNone, sign(x));
    w.after.push_back({CrowdClass::kTrafficSign, LineStyle::kNone, sign(x), false});
  }
  return w;
}

// The drive: keyframes every 5 m at y = -1.75, each placed with the drifting error; every
// element anchored to the keyframe at its start, its points observed (with noise) from the true
// keyframe pose, so the error moves them with their keyframe.
Lsm makeDrive(const World& w) {
  Lsm lsm;
  lsm.drive_id = "new";
  lsm.frame = LsmFrame::kEnu;
  lsm.origin = kOrigin;
  std::vector<Pose3> truth;
  for (int k = 0; k * kKeyframeStep <= kRoad; ++k) {
    Pose3 T = Pose3::Identity();
    T.translation() = Eigen::Vector3d(k * kKeyframeStep, -1.75, 0);
    truth.push_back(T);
    Keyframe kf;
    kf.id = k;
    kf.stamp = k;
    kf.T_frame_body = T;
    kf.T_frame_body.translation() += drift(k * kKeyframeStep);
    lsm.keyframes.push_back(kf);
  }
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, kNoise);
  for (const TruthElement& t : w.after) {
    const int k = std::clamp(int(t.world.front().x() / kKeyframeStep), 0, int(truth.size()) - 1);
    Element e;
    e.id = int64_t(lsm.elements.size());
    e.cls = t.cls;
    e.attributes = {t.style, t.cls == CrowdClass::kLaneLine ? LineColor::kWhite : LineColor::kNone};
    e.anchor = k;
    for (const auto& p : t.world)
      e.points_body.push_back(truth[k].inverse() * p + Eigen::Vector3d(noise(rng), noise(rng), 0));
    e.covariances.assign(e.points_body.size(), Eigen::Matrix3d::Identity() * kNoise * kNoise);
    e.confidence = 0.9;
    e.height = t.cls == CrowdClass::kPole ? 4.0 : 0.0;
    lsm.elements.push_back(e);
  }
  return lsm;
}

// Horizontal RMS of the unchanged elements' observed points from their true positions.
double unchangedRms(const World& w, const Lsm& lsm) {
  double sum = 0;
  int n = 0;
  for (std::size_t i = 0; i < w.after.size(); ++i) {
    if (w.after[i].changed) continue;
    const auto pts = lsm.pointsInFrame(lsm.elements[i]);
    for (std::size_t j = 0; j < pts.size(); ++j, ++n)
      sum += (pts[j] - w.after[i].world[j]).head<2>().squaredNorm();
  }
  return std::sqrt(sum / n);
}

}  // namespace

TEST_CASE("registration to the map removes an error drifting along the drive", "[update]") {
  const World w = makeWorld();
  std::vector<Lsm> drives = {makeDrive(w)};
  const double before = unchangedRms(w, drives[0]);
  CHECK(before > 0.4);  // the injected error is there (0.3-0.85 m)
  const auto stretches = update::registerToMap(w.map, drives, update::RegistrationSettings{});
  REQUIRE(stretches.size() == 6);  // 900 m in stretches of 150 m
  for (const auto& s : stretches) {
    CHECK(s.registered);
    // each stretch's offset undoes the drift at its centre (to within 0.1 m)
    const double mid = s.centre.x();
    CHECK((s.t.head<2>() + drift(mid).head<2>()).norm() < kRegisteredRms);
  }
  const double after = unchangedRms(w, drives[0]);
  INFO("RMS before " << before << " m, after " << after << " m");
  CHECK(after < kRegisteredRms);
}

TEST_CASE("update finds the changes of a drifting drive only when registered", "[update]") {
  const World w = makeWorld();
  const std::vector<Lsm> drives = {makeDrive(w)};
  update::UpdateSettings s;
  const auto r = update::detectChanges(w.map, drives, {"new.lsm.json"}, s);
  int moved = 0, restriped = 0, removed = 0, added = 0;
  for (const auto& c : r.changes.changes) {
    moved += c.kind == ChangeKind::kMoved;
    restriped += c.kind == ChangeKind::kRestriped;
    removed += c.kind == ChangeKind::kRemoved;
    added += c.kind == ChangeKind::kAdded;
  }
  // the restriped line is the right one (id 1), shifted about 0.6 m to the left on [400, 460]
  for (const auto& c : r.changes.changes)
    if (c.kind == ChangeKind::kRestriped) {
      CHECK(c.before->id == 1);
      const auto& pts = c.after->points;
      const auto at430 = std::min_element(pts.begin(), pts.end(), [](const auto& a, const auto& b) {
        return std::abs(a.x() - 430) < std::abs(b.x() - 430);
      });
      CHECK(at430->y() == Approx(-3.5 + 0.6).margin(0.1));
    }
  CHECK(moved == 4);  // poles k = 5, 12, 19, 26
  CHECK(restriped == 1);
  CHECK(added == 3);
  CHECK(removed == 0);  // one traversal's miss is no removal (docs/update.md)
  CHECK(r.changes.changes.size() == 8);
  // without registration the drift (up to 0.85 m) makes false restripes of unchanged lines
  s.registration.enabled = false;
  const auto raw = update::detectChanges(w.map, drives, {"new.lsm.json"}, s);
  int raw_restriped = 0;
  for (const auto& c : raw.changes.changes) raw_restriped += c.kind == ChangeKind::kRestriped;
  CHECK(raw_restriped > 1);
}

}  // namespace mapfuse
