#include "synthetic_world.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mapfuse/aggregate/geometry2d.hpp"

namespace mapfuse::test {
namespace {

using Vec3 = Eigen::Vector3d;

std::vector<Vec3> line(const Vec3& a, const Vec3& b, double step = 1.0) {
  const int n = std::max(1, int(std::ceil((b - a).norm() / step)));
  std::vector<Vec3> out;
  for (int i = 0; i <= n; ++i) out.push_back(a + (b - a) * double(i) / n);
  return out;
}

std::vector<Vec3> rect(const Vec3& c, double along, double across, double z = 0.0) {
  return {c + Vec3(-along / 2, -across / 2, z), c + Vec3(along / 2, -across / 2, z),
          c + Vec3(along / 2, across / 2, z), c + Vec3(-along / 2, across / 2, z)};
}

}  // namespace

SynthWorld makeSynthWorld(const SynthOptions& o) {
  SynthWorld w;
  w.truth.origin = o.origin;
  w.truth.source = "synthetic truth";
  int64_t id = 1;
  auto add = [&](CrowdClass cls, std::vector<Vec3> pts, Attributes attr = {}, double h = 0) {
    MapInstance m;
    m.id = id++;
    m.cls = cls;
    m.points = std::move(pts);
    m.attributes = attr;
    m.height = h;
    w.truth.instances.push_back(std::move(m));
  };
  const double L = o.length, mid = L / 2;
  const Attributes solid{LineStyle::kSolid, LineColor::kWhite};
  const Attributes dashed{LineStyle::kDashed, LineColor::kWhite};
  add(CrowdClass::kLaneLine, line({0, 0, 0}, {L, 0, 0}), solid);
  add(CrowdClass::kLaneLine, line({0, 3.5, 0}, {L, 3.5, 0}), dashed);
  add(CrowdClass::kLaneLine, line({0, 7, 0}, {L, 7, 0}), {LineStyle::kSolid, LineColor::kYellow});
  if (o.fork) {
    const double a = -6.0 * M_PI / 180, len = 60.0;
    add(CrowdClass::kLaneLine, line({mid, 0, 0}, {mid + len * std::cos(a), len * std::sin(a), 0}),
        solid);
  }
  if (o.merge) {
    const double a = -6.0 * M_PI / 180, len = 60.0;
    add(CrowdClass::kLaneLine,
        line({mid - len * std::cos(a), 7 - len * std::sin(a), 0}, {mid, 7, 0}), solid);
  }
  if (o.crossing_deg > 0) {  // a painted line crossing the road inside a junction
    const double a = o.crossing_deg * M_PI / 180, half = 15.0;
    const Vec3 c(o.crossing_x, 3.5, 0), d(std::cos(a), std::sin(a), 0);
    add(CrowdClass::kLaneLine, line(c - half * d, c + half * d, 0.5), solid);
  }
  if (o.discrete) {
    for (double x = 10; x < L - o.view; x += 25) add(CrowdClass::kPole, {{x, -4, 0.1}}, {}, 5.0);
    for (double x = 20; x < L - o.view; x += 50) {
      const double y = -4.5;
      add(CrowdClass::kTrafficSign,
          {{x, y - 0.3, 2.0}, {x, y + 0.3, 2.0}, {x, y + 0.3, 2.6}, {x, y - 0.3, 2.6}});
    }
    for (double x = 30; x < L - 40; x += 40)
      add(CrowdClass::kGroundArrow, rect({x, 1.75, 0}, 3, 1));
    {  // a parallelogram: 4 m along the road, sides of 7 m at crosswalk_deg to it
      const double a = o.crosswalk_deg * M_PI / 180;
      const Vec3 c(L - o.view - 15, 3.5, 0), u(2, 0, 0), v(3.5 * std::cos(a), 3.5 * std::sin(a), 0);
      add(CrowdClass::kCrosswalk, {c - u - v, c + u - v, c + u + v, c - u + v});
    }
    add(CrowdClass::kStopLine, line({L - o.view - 20, 0, 0}, {L - o.view - 20, 3.5, 0}, 3.5));
  }

  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> g(0.0, 1.0);
  auto noise2 = [&](double s) { return Vec3(s * g(rng), s * g(rng), 0.3 * s * g(rng)); };
  for (int d = 0; d < o.drives; ++d) {
    Lsm lsm;
    lsm.drive_id = "synth_" + std::to_string(d);
    lsm.vehicle_id = "veh_" + std::to_string(d % 3);
    lsm.frame = LsmFrame::kEnu;
    lsm.origin = o.origin;
    const bool reverse = d % 2 == 1;
    const Vec3 drive_offset = noise2(o.drive_sigma);
    const double lane_y = reverse ? 5.25 : 1.75;
    int64_t eid = 1;
    std::vector<double> stations;
    for (double s = 0; s <= L - o.view + 1e-9; s += o.keyframe_step) stations.push_back(s);
    for (std::size_t k = 0; k < stations.size(); ++k) {
      const double s = reverse ? L - o.view - stations[k] : stations[k];
      Keyframe kf;
      kf.id = int64_t(k);
      kf.stamp = double(k);
      kf.T_frame_body =
          poseFromXyzRpy(reverse ? s + o.view : s, lane_y, 0, 0, 0, reverse ? M_PI : 0.0);
      lsm.keyframes.push_back(kf);
      const Pose3 T_body_enu = kf.T_frame_body.inverse();
      for (const auto& t : w.truth.instances) {
        // seen when its first point (lines: the visible part) lies within the view window
        std::vector<std::vector<Vec3>> pieces;  // one element each
        if (t.cls == CrowdClass::kLaneLine && t.attributes.style == LineStyle::kDashed &&
            o.dash_length > 0) {  // the dashes (of the straight y = 3.5 line) in view
          const double y = t.points.front().y();
          for (double x = 0; x < L; x += o.dash_length + o.dash_gap) {
            const double a = std::max(x, s), b = std::min(x + o.dash_length, s + o.view);
            if (b - a > 0.2) pieces.push_back(line({a, y, 0}, {b, y, 0}, 0.5));
          }
        } else if (t.cls == CrowdClass::kLaneLine) {
          std::vector<Vec3> pts;
          for (const auto& p : t.points)
            if (p.x() >= s - 1e-9 && p.x() <= s + o.view + 1e-9) pts.push_back(p);
          if (pts.size() < 2) continue;
          pieces.push_back(std::move(pts));
        } else {
          Vec3 c = Vec3::Zero();
          for (const auto& p : t.points) c += p;
          c /= double(t.points.size());
          // each discrete element is observed once per drive: from the keyframe before it
          if (!(c.x() >= s && c.x() < s + o.keyframe_step)) continue;
          pieces.push_back(t.points);
        }
        for (const auto& pts : pieces) {
          const Vec3 elem_offset = noise2(o.element_sigma);
          Element e;
          e.id = eid++;
          e.cls = t.cls;
          e.attributes = t.attributes;
          e.anchor = kf.id;
          e.height = t.height;
          e.truth_id = t.id;
          e.confidence = 0.9;
          e.observations = 5;
          for (const auto& p : pts) {
            const Vec3 noisy = p + drive_offset + elem_offset + noise2(o.point_sigma);
            e.points_body.push_back(T_body_enu * noisy);
            e.covariances.push_back(Eigen::Matrix3d::Identity() * 0.01);
          }
          if (reverse && t.cls == CrowdClass::kLaneLine)
            std::reverse(e.points_body.begin(), e.points_body.end());
          lsm.elements.push_back(std::move(e));
        }
      }
    }
    std::uniform_real_distribution<double> ux(0, L), uy(-8, 15);
    for (int f = 0; f < o.false_positives; ++f) {
      Element e;
      e.id = eid++;
      e.anchor = 0;
      e.confidence = 0.3;
      const Vec3 c(ux(rng), uy(rng), 0);
      const int kind = f % 3;
      e.cls = kind == 0   ? CrowdClass::kPole
              : kind == 1 ? CrowdClass::kGroundArrow
                          : CrowdClass::kLaneLine;
      std::vector<Vec3> pts = kind == 0   ? std::vector<Vec3>{c}
                              : kind == 1 ? rect(c, 3, 1)
                                          : line(c, c + Vec3(6, 2, 0));
      if (kind == 0) e.height = 4.0;
      const Pose3 T_body_enu = lsm.keyframes[0].T_frame_body.inverse();
      for (const auto& p : pts) {
        e.points_body.push_back(T_body_enu * p);
        e.covariances.push_back(Eigen::Matrix3d::Identity() * 0.01);
      }
      lsm.elements.push_back(std::move(e));
    }
    w.lsms.push_back(std::move(lsm));
  }
  return w;
}

aggregate::ObservationSet observe(const SynthWorld& w) {
  std::vector<std::string> names;
  for (const auto& l : w.lsms) names.push_back(l.drive_id);
  return aggregate::collectObservations(w.lsms, names);
}

std::vector<const MapInstance*> ofClass(const VectorMap& m, CrowdClass c) {
  std::vector<const MapInstance*> out;
  for (const auto& i : m.instances)
    if (i.cls == c) out.push_back(&i);
  return out;
}

double distanceToTruth(const Eigen::Vector3d& p, const VectorMap& truth, CrowdClass c) {
  double best = 1e300;
  for (const auto* t : ofClass(truth, c))
    best = std::min(best, aggregate::distanceToPolyline2d(p, t->points));
  return best;
}

}  // namespace mapfuse::test
