// Camera overlay pictures (Jeong et al. 2018, Fig. 4): a labelled 3D point lands at the pixel the
// pinhole equations give, in its class colour; nearer points cover farther ones; the legend lists
// exactly the classes painted; the map / scan point selections.
#include <catch2/catch.hpp>
#include <cmath>

#include "mapfuse/core/error.hpp"
#include "mapfuse/lidar/camera_overlay.hpp"

using namespace mapfuse;

namespace {
constexpr double kPixelTol = 1.0;  // px, projected position against the hand computation
constexpr int kWidth = 400, kHeight = 200;
constexpr double kFu = 500.0, kCu = 200.0, kCv = 100.0;  // px

/// Velodyne -> camera: camera z = velo x (ahead), camera x = -velo y (right), camera y = -velo z
/// (down); the camera 0.3 m ahead of and 0.1 m below the Velodyne.
const Eigen::Matrix3d kR = (Eigen::Matrix3d() << 0, -1, 0, 0, 0, -1, 1, 0, 0).finished();
const Eigen::Vector3d kT(0.0, -0.1, -0.3);

Eigen::Matrix<double, 3, 4> testP() {
  Eigen::Matrix3d K;
  K << kFu, 0, kCu, 0, kFu, kCv, 0, 0, 1;
  Eigen::Matrix<double, 3, 4> Rt;
  Rt << kR, kT;
  return K * Rt;
}

/// The pixel of a Velodyne point, by hand: camera coordinates, then u = f x / z + c_u.
Eigen::Vector2d handPixel(const Eigen::Vector3d& p_velo) {
  const Eigen::Vector3d c = kR * p_velo + kT;
  return {kFu * c.x() / c.z() + kCu, kFu * c.y() / c.z() + kCv};
}

cv::Vec3b bgrOf(LidarClass c) {
  const auto rgb = lidarClassColor(c);
  return {rgb[2], rgb[1], rgb[0]};
}

lidar::OverlayPoints points(std::initializer_list<std::pair<Eigen::Vector3f, LidarClass>> list) {
  lidar::OverlayPoints out;
  for (const auto& [p, c] : list) {
    out.points_velo.push_back(p);
    out.labels.push_back(static_cast<uint8_t>(c));
  }
  return out;
}
}  // namespace

TEST_CASE("camera overlay: a labelled point lands at its pinhole pixel in its class colour",
          "[lidar][overlay]") {
  const cv::Mat photo(kHeight, kWidth, CV_8UC3, cv::Scalar(90, 90, 90));
  const Eigen::Vector3f p(12.0f, 1.5f, 0.4f);
  lidar::OverlayStyle style;
  style.alpha = 1.0;
  style.max_splat_px = 1;  // one pixel per point: the test reads exactly that pixel
  const auto o =
      lidar::renderCameraOverlay(photo, points({{p, LidarClass::kVehicle}}), testP(), style);
  const Eigen::Vector2d px = handPixel(p.cast<double>());
  REQUIRE(o.drawn == 1);
  cv::Point found(-1, -1);
  for (int r = 0; r < kHeight; ++r)
    for (int c = 0; c < kWidth; ++c)
      if (o.labels.at<uint8_t>(r, c) != 255) found = {c, r};
  CHECK(std::abs(found.x - px.x()) <= kPixelTol);
  CHECK(std::abs(found.y - px.y()) <= kPixelTol);
  CHECK(o.labels.at<uint8_t>(found) == static_cast<uint8_t>(LidarClass::kVehicle));
  CHECK(o.image.at<cv::Vec3b>(found) == bgrOf(LidarClass::kVehicle));
  // The photo around it is untouched; the key panel (200 px) is on the right.
  CHECK(o.image.at<cv::Vec3b>(found.y, found.x + 3) == cv::Vec3b(90, 90, 90));
  CHECK(o.image.cols == kWidth + 200);
  CHECK(o.legend == std::vector<std::string>{"vehicle"});

  // Half transparent: the blend of the class colour and the photo (rounding: 1 unit).
  style.alpha = 0.5;
  const auto half =
      lidar::renderCameraOverlay(photo, points({{p, LidarClass::kVehicle}}), testP(), style);
  const cv::Vec3b got = half.image.at<cv::Vec3b>(found), col = bgrOf(LidarClass::kVehicle);
  for (int k = 0; k < 3; ++k) CHECK(std::abs(got[k] - (0.5 * col[k] + 0.5 * 90)) <= 1.0);
}

TEST_CASE("camera overlay: nearer points cover farther ones, the legend lists what shows",
          "[lidar][overlay]") {
  const cv::Mat photo(kHeight, kWidth, CV_8UC3, cv::Scalar(0, 0, 0));
  lidar::OverlayStyle style;
  style.splat_size = 0.05;  // m: 5 px at 5 m, 1.25 px at 20 m
  // A building point 20 m straight ahead hidden behind a road point 5 m ahead on the same ray
  // (the camera centre is at velo (0.3, 0, -0.1)), given far-last and near-last.
  const Eigen::Vector3f near(5.3f, 0.0f, -0.1f), far(20.3f, 0.0f, -0.1f);
  for (bool near_first : {true, false}) {
    const auto pts = near_first ? points({{near, LidarClass::kRoad}, {far, LidarClass::kBuilding}})
                                : points({{far, LidarClass::kBuilding}, {near, LidarClass::kRoad}});
    const auto o = lidar::renderCameraOverlay(photo, pts, testP(), style);
    CHECK(o.drawn == 2);
    CHECK(o.labels.at<uint8_t>(static_cast<int>(kCv), static_cast<int>(kCu)) ==
          static_cast<uint8_t>(LidarClass::kRoad));
    CHECK(o.classes == std::set<LidarClass>{LidarClass::kRoad});
    CHECK(o.legend == std::vector<std::string>{"road"});
  }
  // Three classes apart, plus points behind the camera, beyond max_range and outside the photo.
  const auto o =
      lidar::renderCameraOverlay(photo,
                                 points({{{10, 2, 0}, LidarClass::kVegetation},
                                         {{10, -2, 0}, LidarClass::kPole},
                                         {{8, 0, -1.5f}, LidarClass::kRoad},
                                         {{-10, 0, 0}, LidarClass::kVehicle},  // behind
                                         {{60, 0, 0}, LidarClass::kBuilding},  // beyond 50 m
                                         {{5, 30, 0}, LidarClass::kFence}}),   // left of the photo
                                 testP(), style);
  CHECK(o.drawn == 3);
  CHECK(o.behind == 2);
  CHECK(o.outside == 1);
  CHECK(o.legend == std::vector<std::string>{"road", "pole", "vegetation"});  // class order
  int painted = 0;
  for (int r = 0; r < kHeight; ++r)
    for (int c = 0; c < kWidth; ++c) painted += o.labels.at<uint8_t>(r, c) != 255;
  CHECK(painted == 3 * 9);  // 0.05 m * 500 px / (7.7 to 9.7 m) -> 3 x 3 px squares

  CHECK_THROWS_AS(lidar::renderCameraOverlay(cv::Mat(), {}, testP(), style), InputError);
  lidar::OverlayPoints bad = points({{near, LidarClass::kRoad}});
  bad.labels.push_back(1);
  CHECK_THROWS_AS(lidar::renderCameraOverlay(photo, bad, testP(), style), InputError);
}

TEST_CASE("camera overlay: map voxels near the frame and scan points take the map's labels",
          "[lidar][overlay]") {
  lidar::SemanticVoxelMap map(0.5);
  auto put = [&](const Eigen::Vector3d& p, LidarClass c) {
    const std::size_t i = map.findOrInsert(lidar::packKey(map.coordOf(p)));
    lidar::ClassDistribution m{};
    m.fill(0.01f);
    m[static_cast<int>(c)] = 0.93f;
    for (int k = 0; k < 3; ++k) map.fuse(i, m);
  };
  put({110.2, 20.2, 0.2}, LidarClass::kBuilding);  // centre (110.25, 20.25, 0.25)
  put({101.2, 20.2, 0.2}, LidarClass::kUnlabeled);
  put({300.2, 20.2, 0.2}, LidarClass::kRoad);  // 200 m away
  Pose3 T_map_velo = Pose3::Identity();
  T_map_velo.translation() = Eigen::Vector3d(100, 20, 0);
  const auto m = lidar::mapOverlayPoints(map, T_map_velo, 50.0);
  REQUIRE(m.points_velo.size() == 1);
  CHECK((m.points_velo[0] - Eigen::Vector3f(10.25f, 0.25f, 0.25f)).norm() < 1e-4f);
  CHECK(m.labels[0] == static_cast<uint8_t>(LidarClass::kBuilding));

  const std::vector<Eigen::Vector3f> scan = {{10.1f, 0.1f, 0.1f},   // in the building voxel
                                             {1.1f, 0.1f, 0.1f},    // in the unlabeled voxel
                                             {30.0f, 5.0f, 1.0f}};  // in no voxel
  const auto s = lidar::scanOverlayPoints(map, T_map_velo, scan);
  REQUIRE(s.points_velo.size() == 1);
  CHECK(s.points_velo[0] == scan[0]);
  CHECK(s.labels[0] == static_cast<uint8_t>(LidarClass::kBuilding));
}
