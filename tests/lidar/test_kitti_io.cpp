// KITTI raw reader, calibration, Velodyne .bin and semantics-image format.
#include <catch2/catch.hpp>
#include <cmath>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/kitti_raw.hpp"
#include "mapfuse/io/semantic_image.hpp"
#include "mapfuse/io/velodyne.hpp"
#include "support/error_matchers.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;
namespace fs = std::filesystem;

namespace {
constexpr double kCalibTol = 1e-9;  // numbers are read verbatim from the text file
const char* const kDate = "data/kitti_raw/2011_09_26";
}  // namespace

TEST_CASE("semantic label png and prob images round-trip", "[lidar][io]") {
  const auto dir = test::tempDir("semimg");
  std::vector<uint8_t> labels(7 * 5);
  for (std::size_t i = 0; i < labels.size(); ++i) labels[i] = static_cast<uint8_t>(i % 8);
  const auto lab = io::SemanticImage::fromLabels(7, 5, labels);
  io::writeSemanticImage(dir / "semantics_02" / "0000000003.png", lab);
  const auto back = io::readSemanticImage(dir / "semantics_02" / "0000000003.png");
  CHECK(back.isLabels());
  CHECK(back.width == 7);
  CHECK(back.height == 5);
  CHECK(back.data == labels);

  std::vector<uint8_t> probs(7 * 5 * 8);
  for (std::size_t i = 0; i < probs.size(); ++i) probs[i] = static_cast<uint8_t>(i * 13);
  io::writeSemanticImage(dir / "semantics_02" / "0000000003.prob",
                         io::SemanticImage::fromProbabilities(7, 5, probs));
  // .prob wins over .png when both exist
  const auto found = io::findSemanticImage(dir, "0000000003");
  REQUIRE(found);
  CHECK(found->extension() == ".prob");
  const auto pb = io::readSemanticImage(*found);
  CHECK(pb.channels == 8);
  CHECK(pb.data == probs);
  CHECK(pb.prob(2, 1)[3] == probs[(1 * 7 + 2) * 8 + 3]);
  CHECK_FALSE(io::findSemanticImage(dir, "0000000004"));
}

TEST_CASE("malformed prob and label images throw ParseError naming the field", "[lidar][io]") {
  const auto dir = test::tempDir("semimg-bad");
  test::writeText(dir / "a.prob", "mapfuse-prob 1 2 2 8\n" + std::string(31, 'x'));
  CHECK_THROWS_MATCHES(io::readSemanticImage(dir / "a.prob"), ParseError,
                       test::ParseErrorAt("data", (dir / "a.prob").string()));
  test::writeText(dir / "b.prob", "mapfuse-prob 1 2 2 20\n" + std::string(80, 'x'));
  CHECK_THROWS_MATCHES(io::readSemanticImage(dir / "b.prob"), ParseError,
                       test::ParseErrorAt("channels"));
  test::writeText(dir / "c.prob", "P5 2 2 255\n....");
  CHECK_THROWS_AS(io::readSemanticImage(dir / "c.prob"), ParseError);
  test::writeText(dir / "d.png", "not a png");
  CHECK_THROWS_AS(io::readSemanticImage(dir / "d.png"), ParseError);
  CHECK_THROWS_AS(io::readSemanticImage(dir / "missing.png"), IoError);
}

TEST_CASE("velodyne bin round-trips and truncated files are rejected", "[lidar][io]") {
  const auto dir = test::tempDir("velo");
  io::VelodyneScan scan;
  for (int i = 0; i < 100; ++i) {
    scan.points.emplace_back(0.5f * i, -1.0f * i, 0.25f);
    scan.reflectance.push_back(0.01f * i);
  }
  io::writeVelodyneBin(dir / "s.bin", scan);
  const auto back = io::readVelodyneBin(dir / "s.bin");
  REQUIRE(back.size() == 100);
  CHECK(back.points[42] == scan.points[42]);
  CHECK(back.reflectance[99] == scan.reflectance[99]);
  test::writeText(dir / "t.bin", std::string(16 * 3 + 5, '\0'));
  try {
    io::readVelodyneBin(dir / "t.bin");
    FAIL("no throw");
  } catch (const ParseError& e) {
    CHECK(e.field() == "size");
    CHECK(std::string(e.what()).find("t.bin") != std::string::npos);
    CHECK(static_cast<int>(e.exitCode()) == 3);
  }
}

TEST_CASE("calibration: missing key and bad number name file and field", "[lidar][io]") {
  const auto dir = test::tempDir("calib-bad");
  const std::string cam = test::readText(test::requireShared(kDate) / "calib_cam_to_cam.txt");
  const std::string velo = test::readText(test::requireShared(kDate) / "calib_velo_to_cam.txt");
  // missing R_rect_00
  std::string no_rect;
  std::istringstream in(cam);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("R_rect_00", 0) != 0) no_rect += line + "\n";
  test::writeText(dir / "calib_cam_to_cam.txt", no_rect);
  test::writeText(dir / "calib_velo_to_cam.txt", velo);
  CHECK_THROWS_MATCHES(io::readKittiCalibration(dir), ParseError,
                       test::ParseErrorAt("R_rect_00", (dir / "calib_cam_to_cam.txt").string()));
  test::writeText(dir / "calib_cam_to_cam.txt", cam);
  std::string bad = velo;
  bad.replace(bad.find("T: ") + 3, 1, "x");
  test::writeText(dir / "calib_velo_to_cam.txt", bad);
  CHECK_THROWS_MATCHES(io::readKittiCalibration(dir), ParseError,
                       test::ParseErrorAt("T", (dir / "calib_velo_to_cam.txt").string()));
  fs::remove(dir / "calib_velo_to_cam.txt");
  CHECK_THROWS_AS(io::readKittiCalibration(dir), IoError);
}

TEST_CASE("KITTI raw calibration reads the published matrices", "[lidar][io]") {
  const auto calib = io::readKittiCalibration(test::requireShared(kDate));
  CHECK(calib.P_rect_02(0, 0) == Approx(7.215377e+02).epsilon(kCalibTol));
  CHECK(calib.P_rect_02(0, 3) == Approx(4.485728e+01).epsilon(kCalibTol));
  CHECK(calib.P_rect_02(2, 3) == Approx(2.745884e-03).epsilon(kCalibTol));
  CHECK(calib.R_rect_00(0, 1) == Approx(9.837760e-03).epsilon(kCalibTol));
  CHECK(calib.T_cam0_velo.translation().x() == Approx(-4.069766e-03).epsilon(1e-6));
  CHECK(calib.T_velo_imu.translation().x() == Approx(-8.086759e-01).epsilon(1e-6));
  CHECK(calib.has_imu);
  CHECK(calib.image_width == 1242);
  CHECK(calib.image_height == 375);
}

TEST_CASE("KITTI raw drive lists frames present, ranges and strides", "[lidar][io]") {
  const auto sfnd = test::requireShared(std::string(kDate) + "/2011_09_26_drive_sfnd_sync");
  // The reference is the folder itself: one Velodyne .bin per frame, numbered from 0 without a
  // gap (the drive grew from 30 to 78 frames once; the test follows the data).
  std::size_t scans_on_disk = 0;
  for (const auto& e : fs::directory_iterator(sfnd / "velodyne_points" / "data"))
    if (e.path().extension() == ".bin") ++scans_on_disk;
  REQUIRE(scans_on_disk >= 30);
  const auto all = io::openKittiRawDrive(sfnd, {});
  REQUIRE(all.frames.size() == scans_on_disk);
  CHECK_FALSE(all.has_oxts);
  for (std::size_t i = 0; i < all.frames.size(); ++i)
    CHECK(all.frames[i].index == static_cast<int>(i));
  CHECK(std::isnan(all.frames[0].timestamp));
  CHECK_FALSE(all.frames[0].image.empty());
  const auto sub = io::openKittiRawDrive(sfnd, {5, 14, 3});
  REQUIRE(sub.frames.size() == 4);
  CHECK(sub.frames[0].index == 5);
  CHECK(sub.frames[3].index == 14);
  CHECK_THROWS_AS(io::openKittiRawDrive(sfnd, {static_cast<int>(scans_on_disk) + 10, -1, 1}),
                  InputError);
  CHECK_THROWS_AS(io::openKittiRawDrive(sfnd, {0, -1, 0}), InputError);

  const auto d5 = io::openKittiRawDrive(
      test::requireShared(std::string(kDate) + "/2011_09_26_drive_0005_sync"), {});
  REQUIRE(d5.frames.size() == 1);
  CHECK(d5.has_oxts);
  // 13:04:32.335337762
  CHECK(d5.frames[0].timestamp == Approx(13 * 3600 + 4 * 60 + 32.335337762).epsilon(1e-12));
  CHECK(d5.frames[0].scan_end - d5.frames[0].scan_start == Approx(0.10327).margin(1e-4));
  const auto scan = io::readVelodyneBin(d5.frames[0].velodyne);
  CHECK(scan.size() == 123397);
  const auto ox = io::readOxts(d5.frames[0]);
  CHECK(ox.lat == Approx(49.011212804408).epsilon(1e-12));
}
