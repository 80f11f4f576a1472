// KITTI odometry / SemanticKITTI sequence folders and poses files: the layout read like a raw
// drive, the calibration's Tr and P2, times.txt, the poses-file convention (T_world_cam0 in,
// T_world_cam0 out), the line-to-frame rules and the checks that run before any other work.
#include <algorithm>
#include <catch2/catch.hpp>
#include <fstream>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/kitti_calib.hpp"
#include "mapfuse/io/kitti_poses.hpp"
#include "mapfuse/io/kitti_raw.hpp"
#include "mapfuse/io/png_frames.hpp"
#include "mapfuse/io/semantic_image.hpp"
#include "mapfuse/io/semantic_kitti.hpp"
#include "mapfuse/io/velodyne.hpp"
#include "mapfuse/lidar/drive_poses.hpp"
#include "mapfuse/stages/lidar_semantic_map.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;
namespace fs = std::filesystem;

namespace {
constexpr double kCalibTol = 1e-12;  // numbers read verbatim from calib.txt
constexpr double kPoseTol = 1e-9;    // poses written with 13 significant digits and read back
const char* const kSeq = "data/kitti_odometry/sequences/00";

/// A SemanticKITTI-like copy of shared sequence 00: velodyne/, calib.txt, times.txt, image_2/
/// (one small PNG), poses.txt and labels/ are optional parts.
fs::path makeSequence(const fs::path& root, bool with_poses) {
  const fs::path src = test::requireShared(kSeq);
  const fs::path seq = root / "sequences" / "00";
  fs::create_directories(seq / "velodyne");
  for (const auto& e : fs::directory_iterator(src / "velodyne"))
    fs::create_symlink(e.path(), seq / "velodyne" / e.path().filename());
  fs::copy_file(src / "calib.txt", seq / "calib.txt");
  test::writeText(seq / "times.txt",
                  "0.000000e+00\n1.036400e-01\n2.072800e-01\n3.109200e-01\n"
                  "4.145600e-01\n5.182000e-01\n");
  io::writePngFrame(seq / "image_2" / "000000.png", cv::Mat(376, 1241, CV_8UC3, cv::Scalar(0)));
  if (with_poses) {
    std::vector<Pose3> poses;
    for (int i = 0; i < 6; ++i) poses.push_back(poseFromXyzRpy(0, 0, 0.7 * i, 0, 0.01 * i, 0));
    io::writeKittiOdometryPoses(seq / "poses.txt", poses);
  }
  return seq;
}
}  // namespace

TEST_CASE("a KITTI odometry sequence folder opens like a raw drive", "[lidar][io]") {
  const fs::path seq = makeSequence(test::tempDir("sequence"), false);
  const auto d = io::openKittiRawDrive(seq, {});
  CHECK(d.layout == "sequence");
  REQUIRE(d.frames.size() == 6);
  CHECK(d.frames[5].name == "000005");
  CHECK(d.frames[3].timestamp == Approx(0.31092).epsilon(1e-12));
  CHECK(d.frames[0].image == seq / "image_2" / "000000.png");
  CHECK(d.frames[1].image.empty());
  CHECK_FALSE(d.has_oxts);
  CHECK(d.poses_file.empty());
  CHECK(d.calib.image_width == 1241);
  CHECK(d.calib.image_height == 376);
  // Tr and P2 exactly as calib.txt says; camera 0 is already rectified.
  const auto file = io::KittiCalibFile::read(seq / "calib.txt");
  CHECK((d.calib.T_rect0_velo().matrix().topRows<3>() - file.matrix("Tr", 3, 4))
            .cwiseAbs()
            .maxCoeff() < 1e-6);  // re-orthonormalised rotation (7 digits in the file)
  CHECK((d.calib.P_rect_02 - file.matrix("P2", 3, 4)).cwiseAbs().maxCoeff() < kCalibTol);
  const auto sub = io::openKittiRawDrive(seq, {1, 4, 2});
  REQUIRE(sub.frames.size() == 2);
  CHECK(sub.frames[1].index == 3);
  // A bad times.txt line names the file and line.
  test::writeText(seq / "times.txt", "0.0\nsoon\n");
  CHECK_THROWS_WITH(io::openKittiRawDrive(seq, {}),
                    Catch::Contains("times.txt") && Catch::Contains("line 2"));
  // Times going back, fewer times than scans, and a missing calib.txt name the file (issue 37).
  test::writeText(seq / "times.txt", "0.0\n0.1\n0.05\n0.3\n0.4\n0.5\n");
  CHECK_THROWS_WITH(io::openKittiRawDrive(seq, {}), Catch::Contains("times.txt") &&
                                                        Catch::Contains("line 3") &&
                                                        Catch::Contains("goes back"));
  test::writeText(seq / "times.txt", "0.0\n0.1\n0.2\n2e10\n2.1e10\n2.2e10\n");
  CHECK_THROWS_WITH(io::openKittiRawDrive(seq, {}), Catch::Contains("times.txt") &&
                                                        Catch::Contains("line 4") &&
                                                        Catch::Contains("outside"));
  test::writeText(seq / "times.txt", "0.0\n0.1\n0.2\n");
  CHECK_THROWS_WITH(io::openKittiRawDrive(seq, {}), Catch::Contains("times.txt") &&
                                                        Catch::Contains("line 4") &&
                                                        Catch::Contains("000003"));
  fs::remove(seq / "calib.txt");
  CHECK_THROWS_WITH(io::openKittiRawDrive(seq, {}),
                    Catch::Contains("calib.txt") && Catch::Contains("missing"));
}

TEST_CASE("poses files: T_world_cam0 in and out, lines matched to frames", "[lidar][io]") {
  const fs::path root = test::tempDir("sequence_poses");
  const fs::path seq = makeSequence(root, true);
  const auto d = io::openKittiRawDrive(seq, {});
  CHECK(d.poses_file == seq / "poses.txt");
  // Velodyne poses from camera poses: T_velo0_velo_i = inv(T_cam_velo) T_cam0_cam_i T_cam_velo.
  const auto velo = lidar::veloPosesFromFile(d, d.poses_file);
  const Pose3 T_cam_velo = d.calib.T_rect0_velo();
  const auto cam = io::readKittiOdometryPoses(d.poses_file);
  for (std::size_t i = 0; i < 6; ++i) {
    const Pose3 expect = T_cam_velo.inverse() * cam[i] * T_cam_velo;
    CHECK((velo[i].matrix() - expect.matrix()).cwiseAbs().maxCoeff() < kPoseTol);
  }
  // Written back in the KITTI convention, read back identical; rotations orthonormal.
  io::writeKittiOdometryPoses(root / "out.txt", lidar::cameraPosesForFile(velo, T_cam_velo));
  const auto back = io::readKittiOdometryPoses(root / "out.txt");
  for (std::size_t i = 0; i < 6; ++i) {
    CHECK((back[i].matrix() - cam[i].matrix()).cwiseAbs().maxCoeff() < kPoseTol);
    CHECK((back[i].linear().transpose() * back[i].linear() - Eigen::Matrix3d::Identity())
              .cwiseAbs()
              .maxCoeff() < kPoseTol);
  }
  // A selection: line = frame index (a full file) or line k = k-th selected frame.
  const auto sel = io::openKittiRawDrive(seq, {1, 5, 2});  // frames 1, 3, 5
  const auto by_index = lidar::veloPosesFromFile(sel, d.poses_file);
  CHECK((by_index[1].translation() - (velo[1].inverse() * velo[3]).translation()).norm() <
        kPoseTol);
  io::writeKittiOdometryPoses(root / "three.txt", {cam[1], cam[3], cam[5]});
  const auto by_order = lidar::veloPosesFromFile(sel, root / "three.txt");
  for (std::size_t k = 0; k < 3; ++k)
    CHECK((by_order[k].matrix() - by_index[k].matrix()).cwiseAbs().maxCoeff() < kPoseTol);
  io::writeKittiOdometryPoses(root / "two.txt", {cam[1], cam[3]});
  CHECK_THROWS_WITH(lidar::veloPosesFromFile(sel, root / "two.txt"),
                    Catch::Contains("two.txt has 2 poses"));
}

TEST_CASE("poses files: singular and mirrored rotations are refused naming the line",
          "[lidar][io]") {
  const fs::path dir = test::tempDir("poses_bad");
  test::writeText(dir / "singular.txt",
                  "1 0 0 0 0 1 0 0 0 0 1 0\n0 0 0 1 0 0 0 0 0 0 0 2\n");  // det 0 on line 2
  CHECK_THROWS_WITH(io::readKittiOdometryPoses(dir / "singular.txt"),
                    Catch::Contains("singular.txt") && Catch::Contains("line 2"));
  test::writeText(dir / "mirror.txt", "-1 0 0 0 0 1 0 0 0 0 1 0\n");  // det -1
  CHECK_THROWS_WITH(io::readKittiOdometryPoses(dir / "mirror.txt"),
                    Catch::Contains("line 1") && Catch::Contains("det"));
  test::writeText(dir / "empty.txt", "\n\n");
  CHECK_THROWS_AS(io::readKittiOdometryPoses(dir / "empty.txt"), ParseError);
}

TEST_CASE("lidar-semantic-map on a sequence folder: odometry, then the sequence's own poses",
          "[lidar][stage]") {
  const fs::path root = test::tempDir("sequence_stage");
  const fs::path seq = makeSequence(root, false);
  // Synthetic label images (rows below the horizon road, above building) stand in for ENet.
  std::vector<uint8_t> labels(1241 * 376);
  for (int v = 0; v < 376; ++v)
    for (int u = 0; u < 1241; ++u) labels[std::size_t(v) * 1241 + std::size_t(u)] = v > 190 ? 1 : 3;
  for (int i = 0; i < 6; ++i) {
    char name[16];
    std::snprintf(name, sizeof name, "%06d", i);
    io::writeSemanticImage(seq / "semantics_02" / (std::string(name) + ".png"),
                           io::SemanticImage::fromLabels(1241, 376, labels));
  }
  stages::LidarSemanticMapParams p;
  stages::runLidarSemanticMap(seq, root / "a", p);
  const auto a = test::readSummary(root / "a", "lidar-semantic-map");
  CHECK(a["poses"]["source"] == "odometry");
  CHECK(a["poses"]["untrusted_steps"].empty());
  CHECK(a["frames"] == 6);
  for (int i = 0; i < 6; ++i) {
    char name[16];
    std::snprintf(name, sizeof name, "%06d", i);
    const auto scan = io::readVelodyneBin(seq / "velodyne" / (std::string(name) + ".bin"));
    CHECK(io::readSemanticKittiLabels(root / "a/labels" / (std::string(name) + ".label")).size() ==
          scan.size());
  }
  // 5 steps of 0.68-0.75 m (docs/lidar.md): the camera moves ~3.6 m along its z axis.
  const auto cam = io::readKittiOdometryPoses(root / "a/poses.txt");
  REQUIRE(cam.size() == 6);
  CHECK(cam[5].translation().z() == Approx(3.6).margin(0.2));
  // With the odometry's poses.txt beside the scans, auto uses it (SemanticKITTI layout).
  fs::copy_file(root / "a/poses.txt", seq / "poses.txt");
  stages::runLidarSemanticMap(seq, root / "b", p);
  const auto b = test::readSummary(root / "b", "lidar-semantic-map");
  CHECK(b["poses"]["source"] == "poses_file");
  CHECK(b["voxels"].get<double>() == Approx(a["voxels"].get<double>()).epsilon(0.001));
}

TEST_CASE("lidar-semantic-map refuses a sequence without image_2 before any work, as documented",
          "[lidar][stage]") {
  // The shared sequence 00 ships velodyne/ and calib.txt only (docs/kitti.md "Without images").
  const fs::path seq = test::requireShared(kSeq);
  REQUIRE_FALSE(fs::exists(seq / "image_2"));
  const fs::path root = test::tempDir("sequence_no_images");
  const auto app = test::appPath("lidar-semantic-map").string();
  for (const char* segmenter : {"auto", "enet", "precomputed"}) {
    const fs::path out = root / segmenter;
    const fs::path err = root / (std::string(segmenter) + ".err");
    CHECK(test::runCommand(app + " " + seq.string() + " -o " + out.string() + " --segmenter " +
                           segmenter + " --quiet 2> " + err.string()) == 4);
    const std::string text = test::readText(err);
    CHECK_THAT(text, Catch::StartsWith("lidar-semantic-map: error: " +
                                       fs::absolute(seq / "image_2").lexically_normal().string() +
                                       ": no camera image in the selected frames"));
    CHECK(std::count(text.begin(), text.end(), '\n') == 1);  // one line, before any other
    CHECK_FALSE(fs::exists(out / "map.ply"));
    CHECK_FALSE(fs::exists(out / "lidar-semantic-map.summary.json"));
  }
}
