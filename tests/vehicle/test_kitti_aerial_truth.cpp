// Issue 21 acceptance on the real KITTI sfnd drive (78 frames, skips without ../shared):
// lsm-build's fallback perception (ENet and the colour cues) finds the signs, lights and poles of
// the hand-checked truth tests/data/kitti_sfnd_aerial_truth.json (precision >= 0.8, recall >= 0.7
// within the truth's match radius, horizontal distance, same class), types the lane lines as they
// are painted (dashed), and no lane line lies on a vehicle
// (lane points projected into the frames that see them fall on the ENet road-user mask in at
// most kMaxOnUsers of them). Poses: tests/data/kitti_sfnd_lidar_poses.txt, lidar-semantic-map's
// odometry of this drive (T_world_cam0, docs/kitti.md).
// MAPFUSE_SEG_CACHE=<folder> reuses ENet's class maps between runs; MAPFUSE_OVERLAY_DIR=<folder>
// writes the pictures of docs/images/kitti-sfnd-aerial-*.png.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <iostream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "mapfuse/io/document.hpp"
#include "mapfuse/stages/lsm_build.hpp"
#include "mapfuse/vehicle/aerial_detection.hpp"
#include "mapfuse/vehicle/camera.hpp"
#include "support/test_support.hpp"
#include "vehicle/segmentation_cache.hpp"

using namespace mapfuse;
namespace fs = std::filesystem;

namespace {
constexpr double kMinPrecision = 0.8;  // issue 21 target
// Recall over the truth elements the drive passes within max_track_range: the target.
// ENet alone finds 1 of the 4 (the mast C: it labels sign A as a vehicle and sees the lights B
// and E in too few frames); the colour cues add A (red ring) and E (lit lamp): 3 of 4.
constexpr double kMinRecallInRange = 0.7;
// Lane styles (by eye in frames 0, 20, 40, 60, 77 every lane line of the drive is dashed): of
// the lane pieces the frames could type, at least this share dashed, and no LSM line solid.
constexpr double kMinDashedShare = 0.9;
constexpr int kMinDashedLsmLines = 2;  // of the LSM's 3 lane lines (docs/lsm-build.md)
constexpr double kMaxOnUsers = 0.5;    // share of a lane line's sightings on a road user
constexpr double kLaneMinDepth = 4.0, kLaneMaxDepth = 30.0;  // m, the BEV band

struct TruthElement {
  std::string id;
  CrowdClass cls;
  Eigen::Vector3d position;
  bool in_range = true;  ///< the drive passes it within max_track_range
};

struct Match {
  int predicted = 0, matched_pred = 0;
  int truth_in_range = 0, matched_in_range = 0, truth = 0, matched_truth = 0;
};

/// Greedy one-to-one matching, nearest pairs first, same class, horizontal distance.
Match matchElements(const std::vector<std::pair<CrowdClass, Eigen::Vector3d>>& pred,
                    const std::vector<TruthElement>& truth, double radius) {
  struct Pair {
    double d;
    std::size_t p, t;
  };
  std::vector<Pair> pairs;
  for (std::size_t p = 0; p < pred.size(); ++p)
    for (std::size_t t = 0; t < truth.size(); ++t)
      if (pred[p].first == truth[t].cls) {
        const double d = (pred[p].second - truth[t].position).head<2>().norm();
        if (d <= radius) pairs.push_back({d, p, t});
      }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.d < b.d; });
  std::vector<bool> up(pred.size()), ut(truth.size());
  Match m;
  m.predicted = int(pred.size());
  m.truth = int(truth.size());
  for (const auto& t : truth) m.truth_in_range += t.in_range ? 1 : 0;
  for (const auto& pr : pairs)
    if (!up[pr.p] && !ut[pr.t]) {
      up[pr.p] = ut[pr.t] = true;
      ++m.matched_pred;
      ++m.matched_truth;
      m.matched_in_range += truth[pr.t].in_range ? 1 : 0;
    }
  return m;
}

/// Frame `i` with the road users tinted red, the aerial boxes (track id), the LSM's lane lines
/// (solid green, dashed orange, untyped white) and aerial elements (yellow: position and height)
/// and the truth (magenta).
cv::Mat overlay(const stages::LoadedDrive& d, const Lsm& lsm,
                const std::vector<TruthElement>& truth, const fs::path& cache, std::size_t i) {
  cv::Mat img = cv::imread(d.images[i].string(), cv::IMREAD_COLOR);
  const auto seg = vehicle::readCachedSegmentation(
      vehicle::segmentationCachePath(cache, d.images[i]), img.size());
  if (seg) {  // road users tinted red, 40 %
    cv::Mat tinted;
    cv::addWeighted(img, 0.6, cv::Mat(img.size(), img.type(), cv::Scalar(60, 60, 230)), 0.4, 0,
                    tinted);
    tinted.copyTo(img, vehicle::roadUserMask(seg->classes, 0) & (seg->classes > 0));
  }
  for (const auto& a : d.frames[i].aerial) {
    const cv::Scalar col = a.cls == CrowdClass::kPole           ? cv::Scalar(255, 200, 0)
                           : a.cls == CrowdClass::kTrafficLight ? cv::Scalar(0, 165, 255)
                                                                : cv::Scalar(255, 0, 255);
    cv::rectangle(img, {int(a.box(0)), int(a.box(1))}, {int(a.box(2)), int(a.box(3))}, col, 1);
    cv::putText(img, std::to_string(a.track_id), {int(a.box(0)), int(a.box(3)) + 10},
                cv::FONT_HERSHEY_PLAIN, 0.8, col, 1);
  }
  const Pose3 T_cam_odom = (d.T_odom_body[i] * d.calib.T_body_cam).inverse();
  auto px = [&](const Eigen::Vector3d& q) -> std::optional<cv::Point> {
    const auto p = vehicle::projectPoint(d.calib.K, T_cam_odom * q, 1.0);
    if (!p) return std::nullopt;
    return cv::Point(int(p->x()), int(p->y()));
  };
  for (const auto& e : lsm.elements) {
    const auto pts = lsm.pointsInFrame(e);
    if (e.cls == CrowdClass::kLaneLine) {
      // Solid green, dashed orange, untyped white.
      const cv::Scalar col = e.attributes.style == LineStyle::kSolid    ? cv::Scalar(0, 255, 0)
                             : e.attributes.style == LineStyle::kDashed ? cv::Scalar(0, 140, 255)
                                                                        : cv::Scalar(255, 255, 255);
      for (std::size_t k = 1; k < pts.size(); ++k)
        if (auto a = px(pts[k - 1]), b = px(pts[k]); a && b) cv::line(img, *a, *b, col, 2);
    } else if (e.cls == CrowdClass::kTrafficSign || e.cls == CrowdClass::kTrafficLight ||
               e.cls == CrowdClass::kPole) {
      const Eigen::Vector3d top = pts[0] + Eigen::Vector3d(0, 0, e.height);
      if (auto a = px(pts[0]), b = px(top); a && b) {
        cv::line(img, *a, *b, {0, 255, 255}, 2);
        cv::circle(img, *a, 4, {0, 255, 255}, 2);
      }
    }
  }
  for (const auto& t : truth)
    if (auto a = px(t.position)) {
      cv::drawMarker(img, *a, {255, 0, 255}, cv::MARKER_CROSS, 12, 2);
      cv::putText(img, t.id, *a + cv::Point(4, -4), cv::FONT_HERSHEY_PLAIN, 1.0, {255, 0, 255}, 1);
    }
  return img;
}

}  // namespace

TEST_CASE(
    "real KITTI drive: signs, lights and poles against the hand-checked truth, and no lane "
    "line on a vehicle",
    "[vehicle][kitti][aerial]") {
  const fs::path drive =
      test::requireShared("data/kitti_raw/2011_09_26/2011_09_26_drive_sfnd_sync");
  const fs::path model = test::requireShared("models/enet-cityscapes/enet-model.net");
  const fs::path data = fs::path(MAPFUSE_SOURCE_DIR) / "tests/data";
  const auto truth_doc = io::readDocument(data / "kitti_sfnd_aerial_truth.json");
  const double radius = truth_doc.at("match_radius_m").get<double>();
  std::vector<TruthElement> truth;
  for (const auto& e : truth_doc.at("elements"))
    truth.push_back(
        {e.at("id").get<std::string>(), *crowdClassFromName(e.at("class").get<std::string>()),
         Eigen::Vector3d(e.at("position")[0].get<double>(), e.at("position")[1].get<double>(),
                         e.at("position")[2].get<double>()),
         e.at("in_range").get<bool>()});
  REQUIRE(truth.size() >= 5);

  stages::LsmBuildParams p;
  p.perception.model = model.string();
  const char* cache_env = std::getenv("MAPFUSE_SEG_CACHE");
  const fs::path cache = cache_env ? fs::path(cache_env) : test::tempDir("kitti_aerial_seg");
  p.perception.segmentation_cache = cache.string();
  p.egomotion = "poses";
  stages::LsmBuildInputs in;
  in.drive = drive;
  in.poses = data / "kitti_sfnd_lidar_poses.txt";
  const stages::LoadedDrive d = stages::loadDrive(in, p);
  REQUIRE(d.frames.size() == 78);
  const vehicle::LsmBuildResult r = vehicle::buildLsm(d, p.build);
  if (std::getenv("MAPFUSE_AERIAL_TRACKS")) {  // per track: class, frames, first and last box
    std::map<int64_t, std::vector<std::pair<std::size_t, const AerialObservation*>>> tracks;
    for (std::size_t i = 0; i < d.frames.size(); ++i)
      for (const auto& a : d.frames[i].aerial) tracks[a.track_id].push_back({i, &a});
    for (const auto& [id, obs] : tracks) {
      const auto& f = *obs.front().second;
      const auto& l = *obs.back().second;
      std::cout << "track " << id << " " << crowdClassName(f.cls) << " n " << obs.size()
                << " frames " << obs.front().first << "-" << obs.back().first << " box0 "
                << f.box.transpose() << " conf " << f.confidence << " boxN " << l.box.transpose()
                << "\n";
    }
  }

  // Aerial elements against the truth.
  std::vector<std::pair<CrowdClass, Eigen::Vector3d>> pred;
  std::vector<std::vector<Eigen::Vector3d>> lanes;
  for (const auto& e : r.lsm.elements) {
    const auto pts = r.lsm.pointsInFrame(e);
    if (e.cls == CrowdClass::kTrafficSign || e.cls == CrowdClass::kTrafficLight ||
        e.cls == CrowdClass::kPole) {
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (const auto& q : pts) c += q / double(pts.size());
      pred.push_back({e.cls, c});
      std::cout << "element " << crowdClassName(e.cls) << " (" << c.transpose() << ") frames "
                << e.observations << "\n";
    } else if (e.cls == CrowdClass::kLaneLine) {
      lanes.push_back(pts);
    }
  }
  const Match m = matchElements(pred, truth, radius);
  const double precision = m.predicted ? double(m.matched_pred) / m.predicted : 0.0;
  const double recall = double(m.matched_in_range) / m.truth_in_range;
  std::cout << "aerial: " << m.predicted << " elements, " << m.truth_in_range << " true in range ("
            << m.truth << " in all); precision " << precision << ", recall " << recall
            << " in range, " << double(m.matched_truth) / m.truth << " of all (radius " << radius
            << " m); tracks " << r.aerial_tracks << ", triangulated " << r.aerial_triangulated
            << "\n";
  for (const auto& [why, n] : r.aerial_rejected)
    std::cout << "  rejected " << why << ": " << n << "\n";
  if (const char* dir = std::getenv("MAPFUSE_OVERLAY_DIR")) {
    fs::create_directories(dir);
    for (std::size_t i : {0, 20, 40, 60, 77}) {
      char name[64];
      std::snprintf(name, sizeof name, "frame_%04zu.png", i);
      cv::imwrite((fs::path(dir) / name).string(), overlay(d, r.lsm, truth, cache, i));
    }
  }
  CHECK(precision >= kMinPrecision);
  CHECK(recall >= kMinRecallInRange);

  // Lane line styles: every lane line of this drive is dashed (by eye in frames 0, 20, 40, 60,
  // 77: the urban "Leitlinie", 3 m dash / 6 m gap, then before the junction the "Warnlinie",
  // 6 m / 3 m; both of period 9 m, RMS / StVO).
  const auto& ls = d.lane_styles;
  std::cout << "lane pieces: " << ls.solid << " solid, " << ls.dashed << " dashed, " << ls.untyped
            << " untyped; dash period " << ls.dash_period << " m\n";
  int lsm_dashed = 0, lsm_solid = 0;
  for (const auto& e : r.lsm.elements)
    if (e.cls == CrowdClass::kLaneLine) {
      lsm_dashed += e.attributes.style == LineStyle::kDashed ? 1 : 0;
      lsm_solid += e.attributes.style == LineStyle::kSolid ? 1 : 0;
    }
  std::cout << "LSM lane lines: " << lsm_dashed << " dashed, " << lsm_solid << " solid\n";
  REQUIRE(ls.solid + ls.dashed > 0);
  CHECK(double(ls.dashed) / (ls.solid + ls.dashed) >= kMinDashedShare);
  CHECK(lsm_dashed >= kMinDashedLsmLines);
  CHECK(lsm_solid == 0);

  // Lane lines against the road-user mask of every frame that sees them in the BEV band.
  REQUIRE(!lanes.empty());
  int on_users = 0;
  for (std::size_t l = 0; l < lanes.size(); ++l) {
    int seen = 0, hit = 0;
    for (std::size_t i = 0; i < d.frames.size(); ++i) {
      const auto seg = vehicle::readCachedSegmentation(
          vehicle::segmentationCachePath(cache, d.images[i]), {d.calib.width, d.calib.height});
      REQUIRE(seg);
      const cv::Mat users = vehicle::roadUserMask(seg->classes, 0);
      const Pose3 T_cam_odom = (d.T_odom_body[i] * d.calib.T_body_cam).inverse();
      int n = 0, h = 0;
      for (const auto& q : lanes[l]) {
        const Eigen::Vector3d c = T_cam_odom * q;
        if (c.z() < kLaneMinDepth || c.z() > kLaneMaxDepth) continue;
        const auto px = vehicle::projectPoint(d.calib.K, c);
        if (!px || px->x() < 0 || px->y() < 0 || px->x() >= users.cols || px->y() >= users.rows)
          continue;
        ++n;
        h += users.at<uint8_t>(int(px->y()), int(px->x())) ? 1 : 0;
      }
      if (n == 0) continue;
      ++seen;
      hit += 2 * h > n ? 1 : 0;  // this frame sees the line mostly on a road user
    }
    const double share = seen ? double(hit) / seen : 0.0;
    std::cout << "lane " << l << ": " << lanes[l].size() << " points, on a road user in " << hit
              << " of " << seen << " frames\n";
    on_users += share > kMaxOnUsers ? 1 : 0;
  }
  CHECK(on_users == 0);
}
