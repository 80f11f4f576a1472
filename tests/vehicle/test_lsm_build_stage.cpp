// lsm-build stage and app: configuration mirror, read-back of the LSM, masks path, bad inputs
// with their exception types and exit codes.
#include <catch2/catch.hpp>
#include <fstream>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/drive_frames.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/stages/lsm_build.hpp"
#include "sim_fixture.hpp"
#include "vehicle/centerline.hpp"

using namespace mapfuse;
namespace fs = std::filesystem;

namespace {
/// Copy of the simulated drive that a test may damage.
fs::path damagedCopy(const std::string& name, bool masks = false) {
  const fs::path src = test::simulatedDrive(false, masks);
  const fs::path dst = test::tempDir(name) / src.filename();
  fs::copy(src, dst, fs::copy_options::recursive);
  return dst;
}

int runApp(const fs::path& drive, const fs::path& out, const std::string& extra = "") {
  return test::runCommand(test::appPath("lsm-build").string() + " " + drive.string() + " -o " +
                          out.string() + " -q " + extra + " > /dev/null 2> " +
                          (out.parent_path() / "stderr.txt").string());
}
}  // namespace

TEST_CASE("configs/lsm-build.json mirrors the defaults, which are valid") {
  const auto j = io::readDocument(fs::path(MAPFUSE_SOURCE_DIR) / "configs/lsm-build.json");
  CHECK(j == paramsToJson(stages::LsmBuildParams{}));
  CHECK_NOTHROW(validateParams(stages::LsmBuildParams{}));
  stages::LsmBuildParams bad;
  bad.build.ranging.max_range = 1.0;
  CHECK_THROWS_AS(validateParams(bad), ConfigError);
  bad = {};
  bad.semantics = "lidar";
  CHECK_THROWS_WITH(validateParams(bad), Catch::Contains("semantics"));
  bad = {};
  bad.build.tilt_window = -1.0;
  CHECK_THROWS_AS(validateParams(bad), ConfigError);
  CHECK_THROWS_WITH(validateParams(bad), Catch::Contains("tilt_window"));
  bad = {};
  bad.build.triangulation.max_range = 0.0;
  CHECK_THROWS_AS(validateParams(bad), ConfigError);
  CHECK_THROWS_WITH(validateParams(bad), Catch::Contains("max_track_range"));
}

TEST_CASE("lsm-build writes an LSM that reads back, validates and keeps the GPS fixes") {
  const fs::path drive = test::simulatedDrive(false, false);
  const fs::path out = test::tempDir("lsm_build_ok") / "out";
  REQUIRE(runApp(drive, out) == 0);
  const fs::path file = out / (drive.filename().string() + ".lsm.json");
  const Lsm lsm = io::readLsm(file);
  CHECK_NOTHROW(validateLsm(lsm, file.string()));
  CHECK(lsm.frame == LsmFrame::kOdom);
  CHECK(lsm.keyframes.size() > 10);
  CHECK(lsm.elements.size() > 20);
  CHECK(lsm.gps.size() == io::readDriveFrames(drive).gps.size());
  CHECK(fs::exists(out / "lsm-build.summary.json"));
  CHECK(fs::exists(out / "lsm-build.config.json"));
  // The body attitude the planes follow, as the summary reports it: the simulator's pitch
  // oscillation (0.01 rad amplitude, 0.0071 rad RMS) and the camera height it moves (1.8 m
  // ahead of the pivot: 0.0127 m RMS).
  const auto summary = io::readDocument(out / "lsm-build.summary.json");
  const auto& tilt = summary.at("body_tilt");
  CHECK(tilt.at("source") == "ego-motion");
  CHECK(tilt.at("weighting") == "hann");
  CHECK(tilt.at("frames").get<int>() == int(io::readDriveFrames(drive).frames.size()));
  CHECK(tilt.at("pitch_rms_rad").get<double>() == Approx(0.0071).epsilon(0.15));
  CHECK(tilt.at("height_change_rms_m").get<double>() == Approx(0.0127).epsilon(0.15));
  CHECK(fs::exists(out / (drive.filename().string() + ".bev.png")));
  // Determinism: a second run gives the same bytes.
  const fs::path out2 = test::tempDir("lsm_build_ok2") / "out";
  REQUIRE(runApp(drive, out2) == 0);
  CHECK(test::readText(file) == test::readText(out2 / file.filename()));
}

TEST_CASE("lsm-build on masks (no ids) merges markings spatially") {
  const fs::path drive = test::simulatedDrive(false, true);
  stages::LsmBuildParams p;
  p.semantics = "masks";
  p.render = false;
  const auto r = stages::runLsmBuild({drive, test::tempDir("lsm_build_masks"), {}, {}}, p);
  int lanes = 0;
  for (const auto& e : r.build.lsm.elements) lanes += e.cls == CrowdClass::kLaneLine;
  CHECK(lanes > 10);
  CHECK(r.build.assembly.ground_instances < r.build.ranged_markings / 5);
}

TEST_CASE("lsm-build rejects bad inputs with clear errors and exit codes") {
  SECTION("missing calibration -> I/O error, exit 4") {
    const auto d = damagedCopy("lsm_bad_calib");
    fs::remove(d / "calibration.json");
    CHECK_THROWS_AS(io::readDriveFrames(d), IoError);
    CHECK(runApp(d, d.parent_path() / "out") == 4);
    CHECK(test::readText(d.parent_path() / "stderr.txt").find("calibration") != std::string::npos);
  }
  SECTION("malformed calibration -> parse error naming the field, exit 3") {
    const auto d = damagedCopy("lsm_bad_calib2");
    auto j = io::readDocument(d / "calibration.json");
    j["camera_height"] = -1.0;
    test::writeText(d / "calibration.json", j.dump());
    CHECK_THROWS_WITH(io::readDriveFrames(d), Catch::Contains("camera_height"));
    CHECK(runApp(d, d.parent_path() / "out") == 3);
  }
  SECTION("mismatched frame counts -> input error, exit 3") {
    const auto d = damagedCopy("lsm_bad_count");
    std::string obs = test::readText(d / "observations.jsonl");
    obs = obs.substr(0, obs.rfind('\n', obs.size() - 2) + 1);  // drop the last frame
    test::writeText(d / "observations.jsonl", obs);
    CHECK_THROWS_AS(io::readDriveFrames(d), InputError);
    CHECK(runApp(d, d.parent_path() / "out") == 3);
    CHECK(test::readText(d.parent_path() / "stderr.txt").find("frames") != std::string::npos);
  }
  SECTION("corrupt and empty mask PNGs -> parse error naming the file, exit 3") {
    const auto d = damagedCopy("lsm_bad_png", true);
    test::writeText(d / "masks/000003.png", "\x89PNG\r\n\x1a\n garbage");
    CHECK(runApp(d, d.parent_path() / "out", "--semantics masks") == 3);
    CHECK(test::readText(d.parent_path() / "stderr.txt").find("000003.png") != std::string::npos);
    test::writeText(d / "masks/000003.png", "");
    CHECK_THROWS_AS(io::readMask(d / "masks/000003.png", 1280, 720), ParseError);
    CHECK(runApp(d, d.parent_path() / "out", "--semantics masks") == 3);
  }
  SECTION("a mask without markings is valid and yields no ground observations") {
    cv::Mat empty(720, 1280, CV_8UC1, cv::Scalar(0));
    CHECK(vehicle::observationsFromMask(empty, 20).empty());
  }
  SECTION("not a drive folder -> exit 3; missing folder -> exit 4; poses count mismatch -> 3") {
    const auto d = test::tempDir("lsm_not_a_drive") / "drive";
    std::filesystem::create_directories(d);
    // The output beside the input: an output inside the drive folder is refused first (exit 2).
    CHECK(runApp(d, d.parent_path() / "out") == 3);
    CHECK(runApp(d / "missing", d.parent_path() / "out") == 4);
    const auto good = damagedCopy("lsm_poses");
    test::writeText(good.parent_path() / "poses.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n");
    CHECK(runApp(good, good.parent_path() / "out",
                 "--egomotion poses --poses " + (good.parent_path() / "poses.txt").string()) == 3);
    test::writeText(good.parent_path() / "poses.txt", "1 0 0 0 0 1 0 x 0 0 1 0\n");
    CHECK_THROWS_WITH(io::readKittiPoses(good.parent_path() / "poses.txt"),
                      Catch::Contains("line 1"));
  }
  SECTION("bad parameters -> exit 2, existing outputs untouched") {
    const auto d = damagedCopy("lsm_bad_param");
    const auto out = d.parent_path() / "out";
    REQUIRE(runApp(d, out) == 0);
    const std::string before = test::readText(out / (d.filename().string() + ".lsm.json"));
    CHECK(runApp(d, out, "--max-range 1") == 2);
    fs::remove(d / "calibration.json");
    CHECK(runApp(d, out) == 4);
    CHECK(test::readText(out / (d.filename().string() + ".lsm.json")) == before);
  }
}
