#include "aerial_tracks.hpp"

#include <algorithm>
#include <optional>

namespace mapfuse::vehicle {
namespace {

/// Key points of an aerial observation: given points, else derived from the box.
std::vector<Eigen::Vector2d> keyPoints(const AerialObservation& a) {
  if (!a.points.empty()) return a.points;
  const Eigen::Vector4d& b = a.box;
  if (a.cls == CrowdClass::kTrafficSign)
    return {Eigen::Vector2d(0.5 * (b(0) + b(2)), 0.5 * (b(1) + b(3)))};
  return {Eigen::Vector2d(0.5 * (b(0) + b(2)), b(3)), Eigen::Vector2d(0.5 * (b(0) + b(2)), b(1))};
}

struct Track {
  CrowdClass cls;
  std::vector<std::pair<int, const AerialObservation*>> obs;  ///< (frame, observation)
};

/// Eq. (2)-(3) for each key point of a track; nullopt with the reason when one fails.
std::optional<AerialElement> triangulate(const DriveData& d, const Track& tr,
                                         const TriangulationSettings& s, std::string& reason) {
  std::size_t nkp = 1000;
  for (const auto& [i, a] : tr.obs) nkp = std::min(nkp, keyPoints(*a).size());
  AerialElement el;
  el.cls = tr.cls;
  el.observations = int(tr.obs.size());
  std::map<int64_t, int> votes;
  for (const auto& [i, a] : tr.obs) ++votes[a->truth_id];
  int best = 0;
  for (const auto& [id, c] : votes)
    if (c > best) best = c, el.truth_id = id;
  if (nkp == 0 || nkp >= 1000) return std::nullopt;
  std::vector<Eigen::Vector3d> pts;
  for (std::size_t kp = 0; kp < nkp; ++kp) {
    std::vector<TrackObservation> obs;
    for (const auto& [i, a] : tr.obs)
      obs.push_back({d.T_odom_body[i] * d.calib.T_body_cam, keyPoints(*a)[kp]});
    const auto r = triangulateTrack(d.calib.K, obs, s);
    if (!r.ok) {
      reason = r.reason;
      return std::nullopt;
    }
    pts.push_back(r.p_world);
    el.covariances.push_back(r.covariance);
  }
  if (tr.cls == CrowdClass::kTrafficSign) {
    el.points = pts;
  } else {
    el.points = {pts[0]};
    el.covariances.resize(1);
    el.height = pts.size() > 1 ? std::max(0.0, pts[1].z() - pts[0].z()) : 0.0;
  }
  return el;
}

}  // namespace

AerialTracks triangulateAerialTracks(const DriveData& d, const TriangulationSettings& s) {
  AerialTracks out;
  std::map<std::pair<int, int64_t>, Track> tracks;
  for (std::size_t i = 0; i < d.frames.size(); ++i)
    for (const auto& a : d.frames[i].aerial) {
      if (a.track_id < 0) {
        ++out.unassociated;
        continue;
      }
      auto& tr = tracks[{int(a.cls), a.track_id}];
      tr.cls = a.cls;
      tr.obs.push_back({int(i), &a});
    }
  std::vector<const Track*> track_list;
  for (const auto& [k, tr] : tracks) track_list.push_back(&tr);
  out.tracks = int(track_list.size());
  std::vector<std::optional<AerialElement>> elements(track_list.size());
  std::vector<std::string> reasons(track_list.size());
#pragma omp parallel for schedule(dynamic)
  for (int k = 0; k < int(track_list.size()); ++k)
    elements[k] = triangulate(d, *track_list[k], s, reasons[k]);
  // One element per place and class: of tracks closer than duplicate_radius (two detectors on
  // one sign, a track broken by an occlusion), the one seen in more frames stays.
  for (std::size_t k = 0; k < elements.size(); ++k) {
    if (!elements[k]) continue;
    for (std::size_t j = 0; j < elements.size(); ++j) {
      if (j == k || !elements[j] || elements[j]->cls != elements[k]->cls) continue;
      const double dist = (elements[j]->points[0] - elements[k]->points[0]).head<2>().norm();
      const bool j_wins = elements[j]->observations > elements[k]->observations ||
                          (elements[j]->observations == elements[k]->observations && j < k);
      if (dist < s.duplicate_radius && j_wins) {
        elements[k].reset();
        reasons[k] = "duplicate";
        break;
      }
    }
  }
  for (std::size_t k = 0; k < elements.size(); ++k) {
    if (elements[k])
      out.elements.push_back(*elements[k]);
    else
      ++out.rejected[reasons[k].empty() ? "keypoints" : reasons[k]];
  }
  return out;
}

}  // namespace mapfuse::vehicle
