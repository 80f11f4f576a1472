#include "mapfuse/vehicle/lsm_assembly.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <map>
#include <opencv2/imgproc.hpp>
#include <set>
#include <unordered_map>

#include "mapfuse/core/area_outline.hpp"

namespace mapfuse::vehicle {
namespace {

/// A crosswalk is a quadrilateral (a parallelogram where the road meets the junction skewed).
constexpr std::size_t kCrosswalkVertices = 4;
/// m, complete corner lists of one marking agree within this (area_outline.hpp).
constexpr double kMaxCornerSpread = 0.5;

/// True when some observation has exactly `n` vertices (areaOutline averaged complete ones).
bool sameVertexCount(const std::vector<std::vector<Eigen::Vector3d>>& rings, std::size_t n) {
  for (const auto& r : rings)
    if (r.size() == n) return true;
  return false;
}

/// Oriented minimum-area rectangle of every observed point, z = their mean.
std::vector<Eigen::Vector3d> minAreaRectangle(
    const std::vector<std::vector<Eigen::Vector3d>>& rings) {
  std::vector<cv::Point2f> xy;
  double z = 0.0;
  for (const auto& r : rings)
    for (const auto& p : r) {
      xy.emplace_back(float(p.x()), float(p.y()));
      z += p.z();
    }
  cv::Point2f c[4];
  cv::minAreaRect(xy).points(c);
  std::vector<Eigen::Vector3d> out;
  for (const auto& q : c)
    out.emplace_back(q.x, q.y, z / double(std::max<std::size_t>(1, xy.size())));
  return out;
}

/// Markings of one physical instance, accumulated over frames.
struct Instance {
  CrowdClass cls;
  Attributes attributes;
  std::vector<const RangedMarking*> parts;
};

/// Spatial hash of instance points (per class) for id-less association.
struct PointGrid {
  double cell;
  std::unordered_map<int64_t, std::vector<std::pair<Eigen::Vector3d, int>>> cells;
  int64_t key(int64_t x, int64_t y) const { return (x + (1 << 20)) * (int64_t(1) << 21) + y; }
  void add(const Eigen::Vector3d& p, int inst) {
    cells[key(int64_t(std::floor(p.x() / cell)), int64_t(std::floor(p.y() / cell)))].push_back(
        {p, inst});
  }
  int nearest(const Eigen::Vector3d& p, double radius) const {
    const int64_t cx = int64_t(std::floor(p.x() / cell)), cy = int64_t(std::floor(p.y() / cell));
    int best = -1;
    double best_d = radius * radius;
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy) {
        auto it = cells.find(key(cx + dx, cy + dy));
        if (it == cells.end()) continue;
        for (const auto& [q, inst] : it->second) {
          const double d = (q - p).head<2>().squaredNorm();
          if (d < best_d) best_d = d, best = inst;
        }
      }
    return best;
  }
};

std::vector<Instance> groupInstances(const std::vector<RangedMarking>& markings, double radius) {
  std::vector<Instance> out;
  std::map<std::pair<int, int64_t>, int> by_track;
  std::map<int, PointGrid> grids;
  for (const auto& m : markings) {
    if (m.points.empty()) continue;
    int inst = -1;
    if (m.track_id >= 0) {
      auto it = by_track.find({int(m.cls), m.track_id});
      if (it != by_track.end()) inst = it->second;
    } else {
      // Vote: the instance owning most of this marking's points within `radius`.
      auto& grid =
          grids.try_emplace(int(m.cls), PointGrid{std::max(radius, 0.1), {}}).first->second;
      std::map<int, int> votes;
      for (const auto& p : m.points)
        if (int k = grid.nearest(p, radius); k >= 0) ++votes[k];
      int best = 0;
      for (const auto& [k, n] : votes)
        if (n > best) best = n, inst = k;
      if (best * 3 < int(m.points.size())) inst = -1;
    }
    if (inst < 0) {
      inst = int(out.size());
      out.push_back({m.cls, m.attributes, {}});
      if (m.track_id >= 0) by_track[{int(m.cls), m.track_id}] = inst;
    }
    out[inst].parts.push_back(&m);
    if (m.track_id < 0) {
      auto& grid =
          grids.try_emplace(int(m.cls), PointGrid{std::max(radius, 0.1), {}}).first->second;
      for (const auto& p : m.points) grid.add(p, inst);
    }
  }
  // The line style by majority over the frames that typed it (real frames type a piece only
  // when the camera saw the evidence, line_style.hpp); untyped when none did.
  for (auto& inst : out) {
    int votes[3] = {0, 0, 0};
    for (const auto* p : inst.parts) ++votes[int(p->attributes.style)];
    if (votes[int(LineStyle::kSolid)] + votes[int(LineStyle::kDashed)] > 0)
      inst.attributes.style = votes[int(LineStyle::kSolid)] >= votes[int(LineStyle::kDashed)]
                                  ? LineStyle::kSolid
                                  : LineStyle::kDashed;
  }
  return out;
}

/// Horizontal 1-sigma of a point's covariance, m: sqrt of the x-y trace.
double horizontalSigma(const Eigen::Matrix3d& cov) {
  return std::sqrt(std::max(0.0, cov.topLeftCorner<2, 2>().trace()));
}

/// Mean horizontal 1-sigma of a view's points, m.
double viewSigma(const RangedMarking& m) {
  double sum = 0.0;
  for (const auto& c : m.covariances) sum += horizontalSigma(c);
  return m.covariances.empty() ? 0.0 : sum / double(m.covariances.size());
}

/// The views of an instance whose sigma is at most `ratio` × the lower quartile of its views'.
std::vector<const RangedMarking*> certainViews(const Instance& inst, double ratio) {
  std::vector<double> sigma;
  for (const auto* m : inst.parts) sigma.push_back(viewSigma(*m));
  std::vector<double> sorted = sigma;
  std::sort(sorted.begin(), sorted.end());
  const double bound = ratio * sorted[sorted.size() / 4];
  std::vector<const RangedMarking*> out;
  for (std::size_t k = 0; k < inst.parts.size(); ++k)
    if (sigma[k] <= bound) out.push_back(inst.parts[k]);
  return out;
}

int64_t majorityTruth(const Instance& inst) {
  std::map<int64_t, int> votes;
  for (const auto* p : inst.parts) ++votes[p->truth_id];
  int64_t best = -1;
  int n = 0;
  for (const auto& [id, c] : votes)
    if (c > n) n = c, best = id;
  return best;
}

/// m: a sample above max_line_sigma this close to a sound sample of its class is a ghost of it
/// (far views ranged 1-2 m beside the near views' line on esmini curves_elevation); lines of one
/// class lie a lane width apart, 2.5 m or more.
constexpr double kGhostRadius = 2.0;

/// A resampled point with its covariance and supporting frames.
struct Sample {
  Eigen::Vector3d p;
  Eigen::Matrix3d cov;
  double s;
};

/// Lines: points projected on the instance's principal axis (short lines) or ordered along the
/// trajectory (long lines), averaged in bins of `spacing`.
std::vector<Sample> resampleLine(const Instance& inst, const std::vector<double>& path_s,
                                 const std::vector<Pose3>& poses, double spacing) {
  struct Raw {
    double s;
    Eigen::Vector3d p;
    Eigen::Matrix3d C;
    int frame;
  };
  std::vector<Raw> raw;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto* m : inst.parts)
    for (std::size_t i = 0; i < m->points.size(); ++i) {
      raw.push_back({0.0, m->points[i], m->covariances[i], m->frame});
      mean += m->points[i].head<2>();
    }
  mean /= double(raw.size());
  Eigen::Matrix2d S = Eigen::Matrix2d::Zero();
  for (const auto& r : raw) S += (r.p.head<2>() - mean) * (r.p.head<2>() - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(S);
  const Eigen::Vector2d axis = es.eigenvectors().col(1);
  const double extent = 2.0 * std::sqrt(es.eigenvalues()(1) / double(raw.size())) * 1.732;
  const bool along_track = inst.cls == CrowdClass::kLaneLine && extent > 15.0;
  for (auto& r : raw) {
    if (along_track) {
      // Arc length of the point's projection on the trajectory (searched near the observing
      // frame), a function of the point only, so all frames agree on it.
      const int lo = std::max(0, r.frame - 400),
                hi = std::min(int(poses.size()) - 1, r.frame + 400);
      int best = r.frame;
      double bd = 1e300;
      for (int j = lo; j <= hi; ++j) {
        const double dd = (poses[j].translation() - r.p).head<2>().squaredNorm();
        if (dd < bd) bd = dd, best = j;
      }
      r.s = path_s[best] + (poses[best].inverse() * r.p).x();
    } else {
      r.s = (r.p.head<2>() - mean).dot(axis);
    }
  }
  std::sort(raw.begin(), raw.end(), [](const Raw& a, const Raw& b) { return a.s < b.s; });
  std::vector<Sample> out;
  std::size_t i = 0;
  while (i < raw.size()) {
    const double bin = std::floor(raw[i].s / spacing);
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
    double s = 0.0, w_sum = 0.0;
    std::set<int> frames;
    std::size_t n = 0;
    for (; i < raw.size() && std::floor(raw[i].s / spacing) == bin; ++i, ++n) {
      // Weighted by the inverse of the point's horizontal variance (eq. 1's propagation grows
      // about as range^2: a point seen 5 m ahead outweighs one seen 20 m ahead ~16-fold, and
      // the far one carries the road's unmodelled height ahead as a range error).
      const double w = 1.0 / std::max(raw[i].C.topLeftCorner<2, 2>().trace(), 1e-12);
      p += w * raw[i].p;
      C += w * w * raw[i].C;
      s += w * raw[i].s;
      w_sum += w;
      frames.insert(raw[i].frame);
    }
    // Variance of the weighted mean, Σw²C / (Σw)²; same-frame points are correlated through
    // the attitude error, so the bin counts its frames, not its points (× n / frames).
    out.push_back({p / w_sum, C / (w_sum * w_sum) * double(n) / double(frames.size()), s / w_sum});
  }
  return out;
}

double horizontalSigma(const Sample& smp) {
  return horizontalSigma(smp.cov);
}

/// Line samples at most max_line_sigma, hashed by class and cell of kGhostRadius.
class SoundSamples {
 public:
  void add(CrowdClass cls, const Eigen::Vector3d& p) {
    cells_[key(cls, p, 0, 0)].push_back(p.head<2>());
  }
  /// True when a sound sample of `cls` lies within kGhostRadius of p.
  bool beside(CrowdClass cls, const Eigen::Vector3d& p) const {
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy) {
        const auto it = cells_.find(key(cls, p, dx, dy));
        if (it == cells_.end()) continue;
        for (const auto& q : it->second)
          if ((q - p.head<2>()).squaredNorm() <= kGhostRadius * kGhostRadius) return true;
      }
    return false;
  }

 private:
  static int64_t key(CrowdClass cls, const Eigen::Vector3d& p, int dx, int dy) {
    const int64_t cx = int64_t(std::floor(p.x() / kGhostRadius)) + dx,
                  cy = int64_t(std::floor(p.y() / kGhostRadius)) + dy;
    return (int64_t(cls) << 56) ^ ((cx & 0xfffffff) << 28) ^ (cy & 0xfffffff);
  }
  std::unordered_map<int64_t, std::vector<Eigen::Vector2d>> cells_;
};

/// Every line instance resampled (planar ones left empty), its sound samples added to `sound`:
/// a sample above max_line_sigma (no near view reached it) is a ghost where a sound sample of
/// its class lies within kGhostRadius (far views ranged beside the near views' line), and
/// elsewhere all there is of that stretch (a side road seen from afar).
std::vector<std::vector<Sample>> resampleLines(const std::vector<Instance>& instances,
                                               const std::vector<double>& path_s,
                                               const std::vector<Pose3>& poses,
                                               const AssemblySettings& s, SoundSamples& sound) {
  std::vector<std::vector<Sample>> out(instances.size());
  for (std::size_t k = 0; k < instances.size(); ++k) {
    if (geometryKind(instances[k].cls) == GeometryKind::kPlanar) continue;
    out[k] = resampleLine(instances[k], path_s, poses, s.point_spacing);
    for (const auto& smp : out[k])
      if (horizontalSigma(smp) <= s.max_line_sigma) sound.add(instances[k].cls, smp.p);
  }
  return out;
}

/// Index of the frame nearest to p (horizontally).
std::size_t nearestFrame(const std::vector<Pose3>& poses, const Eigen::Vector3d& p) {
  std::size_t best = 0;
  double bd = 1e300;
  for (std::size_t j = 0; j < poses.size(); ++j) {
    const double d = (poses[j].translation() - p).head<2>().squaredNorm();
    if (d < bd) bd = d, best = j;
  }
  return best;
}

/// Far views put a line's end a few metres beyond the paint (their range error grows ~d² and
/// runs along the view ray); the near views that passed there saw none. At each end of a run of
/// samples (split at gap_split) whose lower quartile is sound, samples less certain than
/// line_end_sigma_ratio × that quartile are dropped while the drive passed them: their nearest
/// frame is neither the first nor the last (beyond the drive's ends the far view is all there
/// is). `samples` are ordered along the line.
std::vector<Sample> trimFarSpill(const std::vector<Sample>& samples,
                                 const std::vector<Pose3>& poses, const AssemblySettings& s,
                                 int& dropped) {
  std::vector<bool> keep(samples.size(), true);
  auto passed = [&](const Sample& smp) {
    const std::size_t j = nearestFrame(poses, smp.p);
    return j > 0 && j + 1 < poses.size();
  };
  std::size_t begin = 0;
  for (std::size_t i = 1; i <= samples.size(); ++i) {
    if (i < samples.size() && samples[i].s - samples[i - 1].s <= s.gap_split) continue;
    if (i - begin >= 3) {
      std::vector<double> sig;
      for (std::size_t j = begin; j < i; ++j) sig.push_back(horizontalSigma(samples[j]));
      // the run's sound quarter: a spill may be longer than the dash it spills from
      std::nth_element(sig.begin(), sig.begin() + long(sig.size() / 4), sig.end());
      const double core = sig[sig.size() / 4];
      const double limit = s.line_end_sigma_ratio * core;
      if (core <= s.max_line_sigma) {
        std::size_t b = begin, e = i;
        while (b < e && horizontalSigma(samples[b]) > limit && passed(samples[b]))
          keep[b++] = false;
        while (e > b && horizontalSigma(samples[e - 1]) > limit && passed(samples[e - 1]))
          keep[--e] = false;
      }
    }
    begin = i;
  }
  std::vector<Sample> out;
  for (std::size_t j = 0; j < samples.size(); ++j)
    if (keep[j])
      out.push_back(samples[j]);
    else
      ++dropped;
  return out;
}

}  // namespace

Lsm assembleLsm(const std::vector<Pose3>& poses, const std::vector<double>& stamps,
                const std::vector<std::size_t>& keyframes,
                const std::vector<RangedMarking>& markings,
                const std::vector<AerialElement>& aerial, const AssemblySettings& s,
                AssemblyStats* stats) {
  Lsm lsm;
  AssemblyStats st;
  for (std::size_t k = 0; k < keyframes.size(); ++k) {
    Keyframe kf;
    kf.id = int64_t(k);
    kf.stamp = stamps[keyframes[k]];
    kf.T_frame_body = poses[keyframes[k]];
    kf.covariance = diagonalCovariance(s.keyframe_sigma_translation, s.keyframe_sigma_rotation);
    lsm.keyframes.push_back(kf);
  }
  std::vector<double> path_s(poses.size(), 0.0);
  for (std::size_t i = 1; i < poses.size(); ++i)
    path_s[i] = path_s[i - 1] + (poses[i].translation() - poses[i - 1].translation()).norm();

  std::vector<Pose3> keyframe_poses;
  for (const std::size_t f : keyframes) keyframe_poses.push_back(poses[f]);
  auto addElement = [&](CrowdClass cls, const Attributes& attr,
                        const std::vector<Eigen::Vector3d>& pts,
                        const std::vector<Eigen::Matrix3d>& covs, int observations, int64_t truth,
                        double height) {
    Eigen::Vector3d mid = Eigen::Vector3d::Zero();
    for (const auto& p : pts) mid += p;
    mid /= double(pts.size());
    const std::size_t k = nearestFrame(keyframe_poses, mid);
    const Pose3 T_body_odom = poses[keyframes[k]].inverse();
    Element e;
    e.id = int64_t(lsm.elements.size());
    e.cls = cls;
    e.attributes = attr;
    e.anchor = int64_t(k);
    for (std::size_t i = 0; i < pts.size(); ++i) {
      e.points_body.push_back(T_body_odom * pts[i]);
      e.covariances.push_back(rotateCovariance(T_body_odom.linear(), covs[i]));
    }
    e.observations = std::max(1, observations);
    e.confidence = std::min(1.0, double(e.observations) / 5.0);
    e.truth_id = truth;
    e.height = height;
    lsm.elements.push_back(std::move(e));
  };

  const std::vector<Instance> instances = groupInstances(markings, s.association_radius);
  SoundSamples sound;
  const auto line_samples = resampleLines(instances, path_s, poses, s, sound);

  for (std::size_t k = 0; k < instances.size(); ++k) {
    const Instance& inst = instances[k];
    ++st.ground_instances;
    std::set<int> frames;
    for (const auto* m : inst.parts) frames.insert(m->frame);
    if (int(frames.size()) < s.min_observations) {
      ++st.ground_dropped;
      continue;
    }
    const int64_t truth = majorityTruth(inst);
    if (geometryKind(inst.cls) == GeometryKind::kPlanar) {
      // The outline (area_outline.hpp): averaged corners, or the simplified hull.
      std::vector<std::vector<Eigen::Vector3d>> rings;
      Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
      std::size_t n = 0;
      for (const auto* m : certainViews(inst, s.area_sigma_ratio)) {
        rings.push_back(m->points);
        for (const auto& c : m->covariances) C += c, ++n;
      }
      // crosswalks: only rings of four corners are complete (one corner out of the range band
      // leaves a partial view), and a hull of three corners is completed (area_outline.hpp)
      std::vector<Eigen::Vector3d> pts =
          areaOutline(rings, s.min_observations, kCrosswalkVertices, kMaxCornerSpread,
                      inst.cls == CrowdClass::kCrosswalk ? kCrosswalkVertices : 0);
      if (inst.cls != CrowdClass::kCrosswalk && !sameVertexCount(rings, pts.size()))
        pts = minAreaRectangle(rings);  // an arrow seen only in parts: its hull is no outline
      addElement(inst.cls, inst.attributes, pts,
                 std::vector<Eigen::Matrix3d>(pts.size(), C / double(n) / double(frames.size())),
                 int(frames.size()), truth, 0.0);
      continue;
    }
    std::vector<Sample> samples;
    for (const auto& smp : line_samples[k]) {
      ++st.line_samples;
      if (horizontalSigma(smp) > s.max_line_sigma && sound.beside(inst.cls, smp.p))
        ++st.line_samples_dropped;  // a ghost: a gap in this line
      else
        samples.push_back(smp);
    }
    samples = trimFarSpill(samples, poses, s, st.line_samples_spill);
    // Split at gaps and at the maximum length.
    std::size_t begin = 0;
    for (std::size_t i = 1; i <= samples.size(); ++i) {
      const bool end = i == samples.size() || samples[i].s - samples[i - 1].s > s.gap_split ||
                       samples[i].s - samples[begin].s > s.max_element_length;
      if (!end) continue;
      if (i - begin >= 2) {
        std::vector<Eigen::Vector3d> pts;
        std::vector<Eigen::Matrix3d> covs;
        for (std::size_t j = begin; j < i; ++j)
          pts.push_back(samples[j].p), covs.push_back(samples[j].cov);
        addElement(inst.cls, inst.attributes, pts, covs, int(frames.size()), truth, 0.0);
      }
      // Consecutive pieces share their joint point unless split at a gap.
      begin = (i < samples.size() && samples[i].s - samples[i - 1].s <= s.gap_split) ? i - 1 : i;
    }
  }
  for (const auto& a : aerial)
    addElement(a.cls, Attributes{}, a.points, a.covariances, a.observations, a.truth_id, a.height);
  st.elements = int(lsm.elements.size());
  if (stats) *stats = st;
  return lsm;
}

}  // namespace mapfuse::vehicle
