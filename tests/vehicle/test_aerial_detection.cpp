// Issue 21: aerial detections from a segmentation (components, boxes, confidence), the road-user
// mask, the segmentation cache, and the chain components -> flow tracks -> eq. 2-3 on a
// synthetic drive whose sign, light and pole have known 3D positions.
#include <catch2/catch.hpp>
#include <fstream>
#include <opencv2/imgproc.hpp>

#include "mapfuse/core/error.hpp"
#include "mapfuse/vehicle/aerial_detection.hpp"
#include "mapfuse/vehicle/fallback_perception.hpp"
#include "mapfuse/vehicle/flow_association.hpp"
#include "support/test_support.hpp"
#include "vehicle/aerial_tracks.hpp"
#include "vehicle/segmentation_cache.hpp"

using namespace mapfuse;
using namespace mapfuse::vehicle;
namespace cs = mapfuse::vehicle::cityscapes;

namespace {
constexpr double kBoxTol = 1e-9;   // px: boxes are exact pixel extents
constexpr double kConfTol = 1e-3;  // confidence is a mean of 8-bit probabilities / 255

const AerialObservation* find(const std::vector<AerialObservation>& v, CrowdClass c) {
  for (const auto& a : v)
    if (a.cls == c) return &a;
  return nullptr;
}
}  // namespace

TEST_CASE("aerial components: boxes, mean class probability, clutter rejected",
          "[vehicle][aerial]") {
  cv::Mat cls(200, 300, CV_8UC1, cv::Scalar(cs::kRoad));
  cv::Mat conf(200, 300, CV_8UC1, cv::Scalar(255));
  // Sign 20x10 px at (40, 30); half its pixels at probability 0.6, half at 1.0 -> mean 0.8.
  cls(cv::Rect(40, 30, 20, 10)).setTo(cs::kTrafficSign);
  conf(cv::Rect(40, 30, 10, 10)).setTo(153);
  // Light 8x20 at (100, 20).
  cls(cv::Rect(100, 20, 8, 20)).setTo(cs::kTrafficLight);
  // Pole 4x80 at (200, 10): kept; stubby pole 12x20 at (250, 10): not elongated enough.
  cls(cv::Rect(200, 10, 4, 80)).setTo(cs::kPole);
  cls(cv::Rect(250, 10, 12, 20)).setTo(cs::kPole);
  // A sign of 9 px (noise), a low-confidence sign, and a sign touching the left border.
  cls(cv::Rect(150, 150, 3, 3)).setTo(cs::kTrafficSign);
  cls(cv::Rect(150, 100, 10, 10)).setTo(cs::kTrafficSign);
  conf(cv::Rect(150, 100, 10, 10)).setTo(60);
  cls(cv::Rect(0, 100, 10, 10)).setTo(cs::kTrafficSign);

  // A tail light: a light component inside a car.
  cls(cv::Rect(20, 150, 40, 30)).setTo(cs::kCar);
  cls(cv::Rect(30, 160, 12, 10)).setTo(cs::kTrafficLight);

  const auto det = detectAerial(cls, conf, AerialDetectSettings{});
  REQUIRE(det.size() == 3);
  const auto* sign = find(det, CrowdClass::kTrafficSign);
  REQUIRE(sign);
  CHECK((sign->box - Eigen::Vector4d(39.5, 29.5, 59.5, 39.5)).norm() < kBoxTol);
  CHECK(sign->confidence == Approx((153.0 + 255.0) / 2 / 255).margin(kConfTol));
  CHECK(sign->track_id == -1);
  const auto* light = find(det, CrowdClass::kTrafficLight);
  REQUIRE(light);
  CHECK((light->box - Eigen::Vector4d(99.5, 19.5, 107.5, 39.5)).norm() < kBoxTol);
  const auto* pole = find(det, CrowdClass::kPole);
  REQUIRE(pole);
  CHECK((pole->box - Eigen::Vector4d(199.5, 9.5, 203.5, 89.5)).norm() < kBoxTol);

  // A pole cut by a bridge: two pieces 20 px apart in the same columns are one pole.
  cv::Mat cut(200, 300, CV_8UC1, cv::Scalar(cs::kRoad));
  cut(cv::Rect(100, 0, 5, 60)).setTo(cs::kPole);
  cut(cv::Rect(101, 80, 5, 60)).setTo(cs::kPole);
  const auto merged = detectAerial(cut, conf, AerialDetectSettings{});
  REQUIRE(merged.size() == 1);
  CHECK((merged[0].box - Eigen::Vector4d(99.5, -0.5, 105.5, 139.5)).norm() < kBoxTol);
  AerialDetectSettings no_merge;
  no_merge.pole_merge_gap = 10;
  CHECK(detectAerial(cut, conf, no_merge).size() == 2);

  AerialDetectSettings off;
  off.enabled = false;
  CHECK(detectAerial(cls, conf, off).empty());
}

TEST_CASE("pole key point: the axis at camera height (ground-parallel ray)", "[vehicle][aerial]") {
  constexpr double kPxTol = 1e-9;
  Eigen::Matrix3d K;
  K << 700, 0, 320, 0, 700, 360, 0, 0, 1;
  std::vector<AerialObservation> obs(2);
  obs[0].cls = CrowdClass::kPole;
  obs[0].box = Eigen::Vector4d(100, 20, 110, 200);
  obs[1].cls = CrowdClass::kTrafficSign;  // untouched
  // Level camera (ground normal = -y, camera y down): the horizon is the principal row.
  setPoleAxisKeyPoints(obs, K, Eigen::Vector3d(0, -1, 0));
  REQUIRE(obs[0].points.size() == 1);
  CHECK((obs[0].points[0] - Eigen::Vector2d(105, 360)).norm() < kPxTol);
  CHECK(obs[1].points.empty());
  // Camera pitched up by a (ground normal (0, -cos a, sin a)): the horizon moves down to
  // v = cy + f tan(a), and the key point's ray is parallel to the ground.
  const double a = 0.05;
  const Eigen::Vector3d n(0, -std::cos(a), std::sin(a));
  setPoleAxisKeyPoints(obs, K, n);
  CHECK(obs[0].points[0].y() == Approx(360 + 700 * std::tan(a)).margin(kPxTol));
  const Eigen::Vector3d ray = K.inverse() * obs[0].points[0].homogeneous();
  CHECK(std::abs(n.dot(ray)) < 1e-12);
}

TEST_CASE("road-user mask: vehicle and person classes, dilated", "[vehicle][aerial]") {
  cv::Mat cls(50, 50, CV_8UC1, cv::Scalar(cs::kRoad));
  cls(cv::Rect(10, 10, 5, 5)).setTo(cs::kCar);
  cls(cv::Rect(30, 30, 2, 2)).setTo(cs::kPerson);
  cls(cv::Rect(40, 5, 3, 3)).setTo(cs::kPole);  // not a road user
  const cv::Mat m0 = roadUserMask(cls, 0);
  CHECK(cv::countNonZero(m0) == 25 + 4);
  const cv::Mat m2 = roadUserMask(cls, 2);
  CHECK(m2.at<uint8_t>(9, 12) == 255);   // 1 px above the car
  CHECK(m2.at<uint8_t>(10, 17) == 0);    // 3 px right of the car
  CHECK(m2.at<uint8_t>(6, 41) == 0);     // the pole stays
  CHECK(m2.at<uint8_t>(31, 33) == 255);  // around the person
}

TEST_CASE("segmentation cache: round trip, and wrong files refused by name", "[vehicle][aerial]") {
  const auto dir = test::tempDir("seg_cache");
  Segmentation seg;
  seg.classes = cv::Mat(20, 30, CV_8UC1, cv::Scalar(cs::kRoad));
  seg.classes(cv::Rect(3, 4, 5, 6)).setTo(cs::kTrafficSign);
  seg.confidence = cv::Mat(20, 30, CV_8UC1, cv::Scalar(200));
  const auto file = segmentationCachePath(dir, "/x/y/0000000007.png");
  CHECK(file == dir / "0000000007.seg.png");
  CHECK_FALSE(readCachedSegmentation(file, {30, 20}));
  writeCachedSegmentation(file, seg);
  const auto back = readCachedSegmentation(file, {30, 20});
  REQUIRE(back);
  CHECK(cv::norm(back->classes, seg.classes, cv::NORM_INF) == 0);
  CHECK(cv::norm(back->confidence, seg.confidence, cv::NORM_INF) == 0);
  CHECK_THROWS_AS(readCachedSegmentation(file, {31, 20}), ParseError);  // stale size
  seg.classes.setTo(25);
  writeCachedSegmentation(file, seg);
  CHECK_THROWS_AS(readCachedSegmentation(file, {30, 20}), ParseError);  // not a class id
  std::ofstream(file) << "not a png";
  CHECK_THROWS_AS(readCachedSegmentation(file, {30, 20}), ParseError);
}

namespace {

/// An axis-aligned upright rectangle facing the camera (the plane x = x0 of the odom frame).
struct Board {
  CrowdClass cls;
  int cityscapes_id;
  double x0, y_min, y_max, z_min, z_max;  ///< m, odom
};

constexpr int kW = 640, kH = 720;
Eigen::Matrix3d kK() {
  Eigen::Matrix3d K;
  K << 700, 0, 320, 0, 700, 360, 0, 0, 1;
  return K;
}

/// Texture anchored to the world: a hash of the 10 cm cell of the hit point.
uint8_t texture(double a, double b) {
  const auto ia = int64_t(std::floor(a * 10)), ib = int64_t(std::floor(b * 10));
  uint64_t h = uint64_t(ia * 73856093) ^ uint64_t(ib * 19349663);
  h ^= h >> 13;
  h *= 0x5bd1e995;
  return uint8_t(40 + (h >> 7) % 180);
}

/// Class map and grey image of the boards (and a far textured wall) seen from T_odom_cam.
void render(const std::vector<Board>& boards, const Pose3& T_odom_cam, cv::Mat& cls,
            cv::Mat& gray) {
  cls = cv::Mat(kH, kW, CV_8UC1, cv::Scalar(cs::kRoad));
  gray = cv::Mat(kH, kW, CV_8UC1, cv::Scalar(0));
  const Eigen::Matrix3d K_inv = kK().inverse();
  const Eigen::Vector3d c = T_odom_cam.translation();
  for (int v = 0; v < kH; ++v)
    for (int u = 0; u < kW; ++u) {
      const Eigen::Vector3d d = T_odom_cam.linear() * (K_inv * Eigen::Vector3d(u, v, 1));
      double best = 1e9;
      // Far wall at x = 200 m.
      const double tw = (200 - c.x()) / d.x();
      const Eigen::Vector3d pw = c + tw * d;
      gray.at<uint8_t>(v, u) = texture(pw.y() / 4, pw.z() / 4);
      for (const auto& b : boards) {
        const double t = (b.x0 - c.x()) / d.x();
        const Eigen::Vector3d p = c + t * d;
        if (t <= 0 || t >= best || p.y() < b.y_min || p.y() > b.y_max || p.z() < b.z_min ||
            p.z() > b.z_max)
          continue;
        best = t;
        cls.at<uint8_t>(v, u) = uint8_t(b.cityscapes_id);
        gray.at<uint8_t>(v, u) = texture(p.y(), p.z());
      }
    }
}

}  // namespace

TEST_CASE("aerial chain on a synthetic drive: components, flow tracks, eq. 2-3 positions",
          "[vehicle][aerial]") {
  constexpr double kPosTol = 0.25;     // m, element position (about 0.5 px over a 4.5 m baseline)
  constexpr double kHeightTol = 0.25;  // m, light / pole height
  const std::vector<Board> boards = {
      {CrowdClass::kTrafficSign, cs::kTrafficSign, 20.0, 4.7, 5.3, 2.2, 2.8},
      {CrowdClass::kTrafficLight, cs::kTrafficLight, 18.0, -3.15, -2.85, 3.5, 4.4},
      {CrowdClass::kPole, cs::kPole, 22.0, 6.9, 7.1, 0.0, 6.0}};
  DriveData d;
  d.calib.K = kK();
  // Camera 1.65 m above the body origin, looking along the body x axis (x right, y down).
  Eigen::Matrix3d R_body_cam;
  R_body_cam << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  d.calib.T_body_cam = Pose3::Identity();
  d.calib.T_body_cam.linear() = R_body_cam;
  d.calib.T_body_cam.translation() = Eigen::Vector3d(0, 0, 1.65);
  const int frames = 10;
  std::vector<cv::Mat> grays(frames);
  FlowSettings flow;
  flow.min_box_side = PerceptionSettings{}.track_min_box_side;
  int64_t next_id = 0;
  for (int i = 0; i < frames; ++i) {
    Pose3 T = Pose3::Identity();
    T.translation() = Eigen::Vector3d(0.5 * i, 0, 0);
    d.T_odom_body.push_back(T);
    d.stamps.push_back(0.1 * i);
    cv::Mat cls;
    render(boards, T * d.calib.T_body_cam, cls, grays[i]);
    FrameObservations f;
    f.index = i;
    f.aerial =
        detectAerial(cls, cv::Mat(cls.size(), CV_8UC1, cv::Scalar(230)), AerialDetectSettings{});
    REQUIRE(f.aerial.size() == 3);
    if (i == 0)
      for (auto& a : f.aerial) a.track_id = next_id++;
    else
      associateByFlow(grays[i - 1], grays[i], d.frames.back().aerial, f.aerial, next_id, flow);
    d.frames.push_back(std::move(f));
  }
  CHECK(next_id == 3);  // every box continued its track
  const AerialTracks tracks = triangulateAerialTracks(d, TriangulationSettings{});
  REQUIRE(tracks.elements.size() == 3);
  for (const auto& b : boards) {
    const AerialElement* el = nullptr;
    for (const auto& e : tracks.elements)
      if (e.cls == b.cls) el = &e;
    REQUIRE(el);
    CHECK(el->observations == frames);
    const double yc = 0.5 * (b.y_min + b.y_max);
    if (b.cls == CrowdClass::kTrafficSign) {  // the box centre: the board's centre
      const Eigen::Vector3d truth(b.x0, yc, 0.5 * (b.z_min + b.z_max));
      CHECK((el->points[0] - truth).norm() < kPosTol);
    } else {  // bottom centre and height
      CHECK((el->points[0] - Eigen::Vector3d(b.x0, yc, b.z_min)).norm() < kPosTol);
      CHECK(std::abs(el->height - (b.z_max - b.z_min)) < kHeightTol);
    }
  }
}
