// evaluate voxels: eq. (10)-(11) on hand-made label sets with known answers, voxel-map
// comparison with moving / parked vehicles, the Table 1 Markdown layout, the stage on a
// synthetic drive and the app's exit codes.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>

#include "mapfuse/eval/voxel_metrics.hpp"
#include "mapfuse/eval/voxel_truth.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/kitti_raw.hpp"
#include "mapfuse/io/kitti_raw_writer.hpp"
#include "mapfuse/io/ply.hpp"
#include "mapfuse/io/semantic_kitti.hpp"
#include "mapfuse/io/velodyne.hpp"
#include "mapfuse/lidar/drive_poses.hpp"
#include "mapfuse/stages/evaluate_voxels.hpp"
#include "mapfuse/stages/simulate_lidar.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;
using namespace mapfuse::eval;
namespace fs = std::filesystem;

namespace {
constexpr double kExact = 1e-12;  // scores are ratios of small integers

const ClassScore& score(const LabelScores& s, LidarClass c) {
  for (const auto& cs : s.classes)
    if (cs.cls == c) return cs;
  throw std::logic_error("class not in Table 1");
}
uint32_t word(uint16_t id, uint16_t instance = 0) {
  return id | (uint32_t(instance) << 16);
}
}  // namespace

TEST_CASE("voxel metrics: accuracy and IoU of a hand-made confusion (eq. 10-11)") {
  ConfusionMatrix m;
  m.add(LidarClass::kRoad, LidarClass::kRoad, 8);
  m.add(LidarClass::kRoad, LidarClass::kSidewalk, 2);
  m.add(LidarClass::kSidewalk, LidarClass::kSidewalk, 5);
  m.add(LidarClass::kSidewalk, LidarClass::kRoad, 1);
  m.add(LidarClass::kVehicle, LidarClass::kVehicle, 3);
  m.add(LidarClass::kVehicle, LidarClass::kUnlabeled, 1);  // missing prediction: FN only
  m.addSpurious(LidarClass::kVehicle);                     // a trace voxel: FP only
  m.add(LidarClass::kUnlabeled, LidarClass::kRoad, 4);     // no truth: ignored
  const LabelScores s = scoreConfusion(m);
  const auto& road = score(s, LidarClass::kRoad);
  CHECK(road.tp == 8);
  CHECK(road.fp == 1);
  CHECK(road.fn == 2);
  CHECK(road.accuracy == Approx(8.0 / 9.0).margin(kExact));
  CHECK(road.iou == Approx(8.0 / 11.0).margin(kExact));
  const auto& sw = score(s, LidarClass::kSidewalk);
  CHECK(sw.accuracy == Approx(5.0 / 7.0).margin(kExact));
  CHECK(sw.iou == Approx(5.0 / 8.0).margin(kExact));
  const auto& veh = score(s, LidarClass::kVehicle);
  CHECK(veh.accuracy == Approx(3.0 / 4.0).margin(kExact));
  CHECK(veh.iou == Approx(3.0 / 5.0).margin(kExact));
  CHECK(std::isnan(score(s, LidarClass::kPole).iou));
  CHECK(s.mean_accuracy == Approx((8.0 / 9 + 5.0 / 7 + 3.0 / 4) / 3).margin(kExact));
  CHECK(s.mean_iou == Approx((8.0 / 11 + 5.0 / 8 + 3.0 / 5) / 3).margin(kExact));
  CHECK(s.evaluated == 8 + 2 + 5 + 1 + 3 + 1);
  const auto j = scoresToJson(s);
  CHECK(j["classes"]["pole"]["iou"].is_null());
  CHECK(j["classes"]["road"]["fn"] == 2);
}

TEST_CASE("voxel metrics: Markdown in the paper's Table 1 layout") {
  ConfusionMatrix m;
  m.add(LidarClass::kRoad, LidarClass::kRoad, 3);
  m.add(LidarClass::kRoad, LidarClass::kBuilding, 1);
  const std::string md = scoresToMarkdown(scoreConfusion(m), "Ours");
  CHECK(md.rfind(
            "| Ours | road | sidewalk | building | fence | pole | vegetation | vehicle | mean |\n",
            0) == 0);
  CHECK(md.find("| Accuracy (%) | 100.0 | - | 0.0 | - | - | - | - | 50.0 |") != std::string::npos);
  CHECK(md.find("| IoU (%) | 75.0 | - | 0.0 | - | - | - | - | 37.5 |") != std::string::npos);
}

TEST_CASE("voxel metrics: per-scan labels, moving cars count as vehicles, instances ignored") {
  const std::vector<uint32_t> truth{word(40),        word(60),    word(48),
                                    word(252, 1001), word(10, 3), word(0)};
  const std::vector<uint32_t> pred{word(40), word(40), word(40), word(10), word(10), word(40)};
  const LabelScores s = scoreConfusion(compareScanLabels(pred, truth));
  CHECK(score(s, LidarClass::kRoad).tp == 2);  // lane marking 60 is road
  CHECK(score(s, LidarClass::kRoad).fp == 1);  // sidewalk called road; unlabeled truth ignored
  CHECK(score(s, LidarClass::kVehicle).iou == Approx(1.0).margin(kExact));
  CHECK(score(s, LidarClass::kSidewalk).iou == Approx(0.0).margin(kExact));
  CHECK_THROWS_AS(compareScanLabels({word(40)}, truth), InputError);
}

TEST_CASE("voxel metrics: a voxel map against truth voxels with moving and parked cars") {
  VoxelTruth truth(0.5);
  // Two road voxels, one building voxel, one parked car voxel, two moving car voxels.
  truth.addPoint({0.1, 0.1, 0.1}, word(40));
  truth.addPoint({0.2, 0.2, 0.2}, word(40));
  truth.addPoint({0.6, 0.1, 0.1}, word(40));
  truth.addPoint({5.1, 0.1, 2.1}, word(50));
  truth.addPoint({3.1, 3.1, 0.6}, word(10, 5));
  truth.addPoint({8.1, 0.1, 0.6}, word(252, 1000));
  truth.addPoint({9.1, 0.1, 0.6}, word(252, 1000));
  truth.addPoint({9.2, 0.1, 0.6}, word(10, 5));  // majority moving: still a moving voxel
  truth.addPoint({9.3, 0.1, 0.6}, word(252, 1000));
  REQUIRE(truth.size() == 6);
  LabeledCloud map;
  auto put = [&](Eigen::Vector3f p, LidarClass c) {
    map.points.push_back(p);
    map.labels.push_back(static_cast<uint8_t>(c));
    map.confidence.push_back(1.f);
  };
  put({0.25f, 0.25f, 0.25f}, LidarClass::kRoad);      // TP road
  put({0.75f, 0.25f, 0.25f}, LidarClass::kSidewalk);  // road voxel called sidewalk
  put({3.25f, 3.25f, 0.75f}, LidarClass::kVehicle);   // parked car kept
  put({8.25f, 0.25f, 0.75f}, LidarClass::kVehicle);   // a trace voxel left in the map
  put({20.25f, 0.25f, 0.25f}, LidarClass::kRoad);     // nothing there in the truth: unmatched
  // building voxel missing from the map: FN building
  const MapComparison c = compareVoxelMap(map, truth);
  CHECK(c.map_voxels == 5);
  CHECK(c.unmatched == 1);
  CHECK(c.truth_voxels == 4);
  CHECK(c.moving_truth == 2);
  CHECK(c.moving_in_map == 1);
  CHECK(c.parked_truth == 1);
  CHECK(c.parked_in_map == 1);
  const LabelScores s = scoreConfusion(c.confusion);
  CHECK(score(s, LidarClass::kRoad).iou == Approx(1.0 / 2.0).margin(kExact));
  CHECK(score(s, LidarClass::kSidewalk).iou == Approx(0.0).margin(kExact));
  CHECK(score(s, LidarClass::kBuilding).iou == Approx(0.0).margin(kExact));
  CHECK(score(s, LidarClass::kVehicle).accuracy == Approx(1.0 / 2.0).margin(kExact));
  CHECK(score(s, LidarClass::kVehicle).iou == Approx(1.0 / 2.0).margin(kExact));
}

TEST_CASE("evaluate voxels: stage on a synthetic drive, scans and voxel map") {
  const auto dir = test::tempDir("eval_voxels_stage");
  stages::SimulateLidarParams sp;
  sp.lidar.frames = 3;
  sp.lidar.sensor.azimuth_steps = 400;
  sp.seed = 4;
  stages::runSimulateLidar(dir / "sim", sp);
  const fs::path drive = io::kittiDriveDir(dir / "sim", sp.date, sp.drive);

  // Per-scan mode: predictions = truth except every road point of frame 0 called sidewalk.
  const fs::path pred = dir / "pred";
  fs::create_directories(pred);
  uint64_t road0 = 0, road_all = 0;
  for (int k = 0; k < 3; ++k) {
    const std::string name = io::kittiFrameName(k);
    auto labels = io::readSemanticKittiLabels(drive / "labels" / (name + ".label"));
    for (auto& w : labels)
      if (lidarClassFromSemanticKitti(w & 0xFFFF) == LidarClass::kRoad) {
        ++road_all;
        if (k == 0) ++road0, w = 48;
      }
    io::writeSemanticKittiLabels(pred / (name + ".label"), labels);
  }
  stages::EvaluateVoxelsInputs in;
  in.drive = drive;
  in.predicted_labels = pred;
  const auto doc = stages::runEvaluateVoxels(in, dir / "scans", stages::EvaluateVoxelsParams{});
  CHECK(doc["mode"] == "scans");
  CHECK(doc["scores"]["classes"]["road"]["iou"].get<double>() ==
        Approx(double(road_all - road0) / road_all).margin(kExact));
  CHECK(doc["scores"]["classes"]["building"]["iou"].get<double>() == Approx(1.0).margin(kExact));
  CHECK(fs::exists(dir / "scans" / "voxels.md"));
  CHECK(fs::exists(dir / "scans" / "evaluate-voxels.summary.json"));

  // Voxel mode: a map made of exactly the static truth voxels scores 1 and removes every trace.
  stages::EvaluateVoxelsParams vp;
  in.predicted_labels.clear();
  in.map = dir / "empty.ply";
  io::writePly(in.map, LabeledCloud{});
  const auto empty = stages::runEvaluateVoxels(in, dir / "vox0", vp);
  CHECK(empty["scores"]["mean_iou"].get<double>() == Approx(0.0).margin(kExact));
  const uint64_t truth_voxels = empty["counts"]["truth_voxels"];
  CHECK(truth_voxels > 1000);
  // Independent truth built here from the files (reader, OXTS poses, recentred), written as a map
  // with every static voxel and no moving voxel: perfect scores, all traces removed.
  const io::KittiRawDrive d = io::openKittiRawDrive(drive, io::FrameRange{});
  std::vector<Pose3> poses = lidar::oxtsVeloPoses(d, false);
  lidar::recenter(poses);
  VoxelTruth truth(vp.truth.voxel_size);
  const Eigen::Matrix<double, 3, 4> P2 = d.calib.veloToImage2();
  for (std::size_t k = 0; k < d.frames.size(); ++k)
    addLabelledScan(truth, io::readVelodyneBin(d.frames[k].velodyne).points,
                    io::readSemanticKittiLabels(drive / "labels" / (d.frames[k].name + ".label")),
                    poses[k], vp.truth.min_range, vp.truth.max_range, &P2, 1242, 375);
  LabeledCloud perfect;
  for (const auto& [key, label] : truth.all()) {
    if (label.moving || label.cls == LidarClass::kUnlabeled) continue;
    Eigen::Vector3f c;
    for (int a = 0; a < 3; ++a)
      c[a] = static_cast<float>(
          ((static_cast<int64_t>((key >> (21 * a)) & 0x1FFFFF) - (1 << 20)) + 0.5) *
          vp.truth.voxel_size);
    perfect.points.push_back(c);
    perfect.labels.push_back(static_cast<uint8_t>(label.cls));
    perfect.confidence.push_back(1.f);
  }
  in.map = dir / "perfect.ply";
  io::writePly(in.map, perfect);
  const auto best = stages::runEvaluateVoxels(in, dir / "vox1", vp);
  CHECK(best["counts"]["truth_voxels"] == truth_voxels);
  CHECK(best["counts"]["unmatched_map_voxels"] == 0);
  CHECK(best["scores"]["mean_iou"].get<double>() == Approx(1.0).margin(kExact));
  if (best["trace_removal"]["parked_truth_voxels"].get<uint64_t>() > 0)
    CHECK(best["trace_removal"]["parked_kept_share"].get<double>() == Approx(1.0).margin(kExact));
  if (best["trace_removal"]["moving_truth_voxels"].get<uint64_t>() > 0)
    CHECK(best["trace_removal"]["moving_removed_share"].get<double>() ==
          Approx(1.0).margin(kExact));
  CHECK_THROWS_AS(stages::runEvaluateVoxels({drive, {}, {}}, dir / "x", vp), InputError);
}

TEST_CASE("evaluate voxels: app exit codes") {
  const auto dir = test::tempDir("eval_voxels_app");
  const std::string app = test::appPath("evaluate").string();
  CHECK(test::runCommand(app + " voxels --help > /dev/null") == 0);
  CHECK(test::runCommand(app + " voxels -o " + dir.string() + " 2>/dev/null") == 2);  // --drive
  CHECK(test::runCommand(app + " voxels --drive " + (dir / "nope").string() + " --map m.ply -o " +
                         (dir / "o").string() + " 2>/dev/null") == 4);
  CHECK(test::runCommand(app + " voxels --drive x --map a.ply --predicted-labels p -o " +
                         (dir / "o").string() + " 2>/dev/null") == 2);
  CHECK(test::runCommand(app + " voxels --drive x --map a.ply --voxel-size 0 -o " +
                         (dir / "o").string() + " 2>/dev/null") == 2);
}

TEST_CASE("evaluate voxels: configs/evaluate-voxels.json mirrors the defaults") {
  const auto j =
      io::readDocument(fs::path(MAPFUSE_SOURCE_DIR) / "configs" / "evaluate-voxels.json");
  CHECK(j == paramsToJson(stages::EvaluateVoxelsParams{}));
  CHECK_NOTHROW(validateParams(stages::EvaluateVoxelsParams{}));
}
