#include "mapfuse/core/lsm.hpp"

#include <unordered_set>

#include "mapfuse/core/error.hpp"

namespace mapfuse {

std::size_t Lsm::keyframeIndex(int64_t id) const {
  // Keyframe ids are usually their index; fall back to a scan otherwise.
  if (id >= 0 && std::size_t(id) < keyframes.size() && keyframes[id].id == id) return id;
  for (std::size_t i = 0; i < keyframes.size(); ++i)
    if (keyframes[i].id == id) return i;
  throw InputError("LSM " + drive_id + ": no keyframe with id " + std::to_string(id));
}

std::vector<Eigen::Vector3d> Lsm::pointsInFrame(const Element& e) const {
  const Pose3& T = keyframes[keyframeIndex(e.anchor)].T_frame_body;
  std::vector<Eigen::Vector3d> out;
  out.reserve(e.points_body.size());
  for (const auto& p : e.points_body) out.push_back(T * p);
  return out;
}

void validateLsm(const Lsm& lsm, const std::string& source) {
  auto fail = [&](const std::string& problem) { throw InputError(source + ": " + problem); };
  if (lsm.frame == LsmFrame::kEnu && !lsm.origin) fail("frame is enu but no origin is given");
  if (lsm.origin && !geo::isValid(*lsm.origin)) fail("origin is not a valid WGS84 point");
  std::unordered_set<int64_t> kf_ids;
  for (std::size_t i = 0; i < lsm.keyframes.size(); ++i) {
    const auto& k = lsm.keyframes[i];
    if (!kf_ids.insert(k.id).second) fail("duplicate keyframe id " + std::to_string(k.id));
    if (i > 0 && k.stamp < lsm.keyframes[i - 1].stamp)
      fail("keyframes[" + std::to_string(i) + "] stamp goes backwards");
    if (!k.T_frame_body.matrix().allFinite() || !k.covariance.allFinite())
      fail("keyframes[" + std::to_string(i) + "] has non-finite values");
  }
  std::unordered_set<int64_t> el_ids;
  for (std::size_t i = 0; i < lsm.elements.size(); ++i) {
    const auto& e = lsm.elements[i];
    const std::string where = "elements[" + std::to_string(i) + "]";
    if (!el_ids.insert(e.id).second) fail("duplicate element id " + std::to_string(e.id));
    if (!kf_ids.count(e.anchor))
      fail(where + ".anchor " + std::to_string(e.anchor) + " is no keyframe");
    if (e.points_body.empty()) fail(where + " has no points");
    if (e.covariances.size() != e.points_body.size())
      fail(where + " has " + std::to_string(e.covariances.size()) + " covariances for " +
           std::to_string(e.points_body.size()) + " points");
    if (e.confidence < 0.0 || e.confidence > 1.0) fail(where + ".confidence outside [0, 1]");
    if (e.observations < 1) fail(where + ".observations < 1");
  }
}

}  // namespace mapfuse
