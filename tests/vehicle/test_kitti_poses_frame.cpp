// lsm-build on KITTI raw: a LiDAR poses file (T_world_velo, as lidar-semantic-map writes it,
// poses_frame = velo) gives the same body trajectory as the equivalent camera-0 poses file.
#include <catch2/catch.hpp>
#include <fstream>
#include <iomanip>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/kitti_calib.hpp"
#include "mapfuse/stages/lsm_build.hpp"
#include "sim_fixture.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;
namespace fs = std::filesystem;

namespace {
constexpr double kPoseTol = 1e-6;  // m / rad: the same poses written with 12 digits
const char* const kDate = "data/kitti_raw/2011_09_26";
const char* const kDrive = "data/kitti_raw/2011_09_26/2011_09_26_drive_sfnd_sync";

void writePoses(const fs::path& path, const std::vector<Pose3>& poses) {
  std::ofstream f(path);
  f << std::setprecision(12);
  for (const auto& T : poses) {
    const Eigen::Matrix4d M = T.matrix();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) f << M(r, c) << (r == 2 && c == 3 ? "\n" : " ");
  }
}
}  // namespace

TEST_CASE("lsm-build: a T_world_velo poses file (poses_frame velo) equals its T_world_cam0 twin",
          "[vehicle][kitti]") {
  const fs::path drive = test::requireShared(kDrive);
  const fs::path model = test::requireShared("models/enet-cityscapes/enet-model.net");
  // Independent conversion from the calibration files: T_world_velo = T_world_cam0 T_rect0_velo.
  const Pose3 T_rect0_velo = io::readKittiCalibration(test::requireShared(kDate)).T_rect0_velo();
  const std::vector<Pose3> cam0 = {Pose3::Identity(),
                                   poseFromXyzRpy(0.02, -0.01, 0.9, 0.0, 0.03, 0.0)};
  std::vector<Pose3> velo;
  for (const auto& T : cam0) velo.push_back(T * T_rect0_velo);
  const fs::path dir = test::tempDir("kitti_poses_frame");
  writePoses(dir / "cam0.txt", cam0);
  writePoses(dir / "velo.txt", velo);

  stages::LsmBuildParams p;
  p.perception.model = model.string();
  p.kitti_last_frame = 1;
  p.egomotion = "poses";
  stages::LsmBuildInputs in;
  in.drive = drive;
  in.poses = dir / "cam0.txt";
  const auto a = stages::loadDrive(in, p);
  p.poses_frame = "velo";
  in.poses = dir / "velo.txt";
  const auto b = stages::loadDrive(in, p);
  REQUIRE(a.T_odom_body.size() == 2);
  REQUIRE(b.T_odom_body.size() == 2);
  for (std::size_t i = 0; i < 2; ++i) {
    CHECK((a.T_odom_body[i].translation() - b.T_odom_body[i].translation()).norm() < kPoseTol);
    CHECK((a.T_odom_body[i].linear() - b.T_odom_body[i].linear()).norm() < kPoseTol);
  }
  // The camera moved 0.9 m forward (camera z), so the body moved ~0.9 m.
  CHECK(a.T_odom_body[1].translation().norm() == Approx(0.9).margin(0.05));
}

TEST_CASE("lsm-build: poses_frame velo needs a KITTI raw drive", "[vehicle][kitti]") {
  const fs::path dir = test::tempDir("velo_on_frames");
  writePoses(dir / "poses.txt", {Pose3::Identity()});
  stages::LsmBuildParams p;
  p.egomotion = "poses";
  p.poses_frame = "velo";
  stages::LsmBuildInputs in;
  in.drive = test::simulatedDrive(false, false);
  in.poses = dir / "poses.txt";
  CHECK_THROWS_AS(stages::loadDrive(in, p), ConfigError);
}

TEST_CASE("lsm-build: a singular poses row is refused before any image or network work",
          "[vehicle][kitti]") {
  const fs::path drive = test::requireShared(kDrive);
  const fs::path dir = test::tempDir("kitti_poses_singular");
  test::writeText(dir / "poses.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n0 0 0 0 0 0 0 0 0 0 0 0\n");
  stages::LsmBuildParams p;
  p.perception.model = (dir / "no-such-model.net").string();  // loading it would fail with an IoError
  p.kitti_last_frame = 1;
  p.egomotion = "poses";
  stages::LsmBuildInputs in;
  in.drive = drive;
  in.poses = dir / "poses.txt";
  CHECK_THROWS_WITH(stages::loadDrive(in, p),
                    Catch::Contains("poses.txt") && Catch::Contains("line 2"));
  // A row count that does not match the frames is refused before the network too.
  writePoses(dir / "three.txt", {Pose3::Identity(), Pose3::Identity(), Pose3::Identity()});
  in.poses = dir / "three.txt";
  CHECK_THROWS_WITH(stages::loadDrive(in, p), Catch::Contains("has 3 poses"));
}
