// PLY / PCD / SemanticKITTI .label / KITTI poses round trips and malformed input.
#include <catch2/catch.hpp>
#include <cstring>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/kitti_poses.hpp"
#include "mapfuse/io/pcd.hpp"
#include "mapfuse/io/ply.hpp"
#include "mapfuse/io/semantic_kitti.hpp"
#include "support/error_matchers.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;

namespace {
LabeledCloud sampleCloud(std::size_t n) {
  LabeledCloud c;
  for (std::size_t i = 0; i < n; ++i) {
    c.points.emplace_back(0.05f * i, -0.1f * i, 1.0f + 0.01f * i);
    c.labels.push_back(static_cast<uint8_t>(i % 8));
    c.confidence.push_back(static_cast<float>(i % 100) / 100.0f);
  }
  return c;
}
void checkSame(const LabeledCloud& a, const LabeledCloud& b) {
  REQUIRE(a.size() == b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    CHECK(a.points[i] == b.points[i]);
    CHECK(a.labels[i] == b.labels[i]);
    CHECK(a.confidence[i] == b.confidence[i]);
  }
}
}  // namespace

TEST_CASE("PLY round-trip keeps points, labels, confidence and count", "[lidar][io]") {
  const auto dir = test::tempDir("ply");
  const auto cloud = sampleCloud(1234);
  io::writePly(dir / "m.ply", cloud);
  const std::string text = test::readText(dir / "m.ply");
  CHECK(text.rfind("ply\nformat binary_little_endian 1.0\n", 0) == 0);
  CHECK(text.find("element vertex 1234\n") != std::string::npos);
  // scalar_* (CloudCompare loads them as scalar fields), int32 / float (Open3D keeps them).
  CHECK(text.find("property uchar red\nproperty uchar green\nproperty uchar blue\n"
                  "property int scalar_label\nproperty float scalar_confidence\n"
                  "property int scalar_semantic_kitti\nend_header\n") != std::string::npos);
  CHECK(text.find("comment scalar_label: mapfuse LiDAR class id 0-7") != std::string::npos);
  checkSame(cloud, io::readPly(dir / "m.ply"));
  // The last vertex: label 1233 % 8 = 1 (road, SemanticKITTI 40); the one before: 0.
  int32_t label = -1, kitti = 0;
  std::memcpy(&label, text.data() + text.size() - 12, 4);
  std::memcpy(&kitti, text.data() + text.size() - 4, 4);
  CHECK(label == 1);
  CHECK(kitti == 40);
  // A file of the earlier layout (plain label / confidence names) still reads.
  std::string old =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n"
      "property float y\nproperty float z\nproperty uchar label\n"
      "property float confidence\nend_header\n";
  const float xyz_conf[4] = {1.0f, 2.0f, 3.0f, 0.25f};
  old.append(reinterpret_cast<const char*>(xyz_conf), 12).push_back('\x05');
  old.append(reinterpret_cast<const char*>(xyz_conf + 3), 4);
  test::writeText(dir / "old.ply", old);
  const auto back = io::readPly(dir / "old.ply");
  REQUIRE(back.size() == 1);
  CHECK(back.labels[0] == 5);
  CHECK(back.confidence[0] == 0.25f);
  // truncated body
  test::writeText(dir / "t.ply", text.substr(0, text.size() - 7));
  CHECK_THROWS_MATCHES(io::readPly(dir / "t.ply"), ParseError, test::ParseErrorAt("vertex"));
  test::writeText(dir / "a.ply", "ply\nformat ascii 1.0\nelement vertex 0\nend_header\n");
  CHECK_THROWS_AS(io::readPly(dir / "a.ply"), ParseError);
}

TEST_CASE("PCD round-trip keeps points, labels, confidence and count", "[lidar][io]") {
  const auto dir = test::tempDir("pcd");
  const auto cloud = sampleCloud(777);
  io::writePcd(dir / "m.pcd", cloud);
  const std::string text = test::readText(dir / "m.pcd");
  CHECK(text.find("FIELDS x y z rgb label confidence semantic_kitti\n") != std::string::npos);
  CHECK(text.find("POINTS 777\nDATA binary\n") != std::string::npos);
  CHECK(text.find("SIZE 4 4 4 4 4 4 4\nTYPE F F F F U F U\n") != std::string::npos);
  checkSame(cloud, io::readPcd(dir / "m.pcd"));
  // The last point: label 776 % 8 = 0 (unlabeled, SemanticKITTI 0); the one before: 7, vehicle:
  // rgb 0x6496F5 (SemanticKITTI's car colour, its BGR [245, 150, 100] as RGB) in the bits of
  // a float field (PCL's PointXYZRGB convention), id 10.
  uint32_t rgb = 0, label = 0, kitti = 0;
  const std::size_t prev = text.size() - 2 * 28;
  std::memcpy(&rgb, text.data() + prev + 12, 4);
  std::memcpy(&label, text.data() + prev + 16, 4);
  std::memcpy(&kitti, text.data() + prev + 24, 4);
  CHECK(label == 7);
  CHECK(rgb == 0x6496F5u);
  CHECK(kitti == 10);
  test::writeText(dir / "t.pcd", text.substr(0, text.size() - 1));
  CHECK_THROWS_AS(io::readPcd(dir / "t.pcd"), ParseError);
  std::string ascii = text;
  ascii.replace(ascii.find("DATA binary"), 11, "DATA ascii");
  test::writeText(dir / "a.pcd", ascii);
  CHECK_THROWS_MATCHES(io::readPcd(dir / "a.pcd"), ParseError, test::ParseErrorAt("DATA"));
}

TEST_CASE("PLY and PCD writers refuse a cloud whose arrays differ in size, writing nothing",
          "[lidar][io]") {
  const auto dir = test::tempDir("cloud-sizes");
  LabeledCloud fewer_labels = sampleCloud(10), fewer_scores = sampleCloud(10);
  fewer_labels.labels.pop_back();
  fewer_scores.confidence.pop_back();
  for (const auto* cloud : {&fewer_labels, &fewer_scores}) {
    for (const char* name : {"m.ply", "m.pcd"}) {
      const auto path = dir / name;
      const auto write = [&] {
        if (path.extension() == ".ply")
          io::writePly(path, *cloud);
        else
          io::writePcd(path, *cloud);
      };
      CHECK_THROWS_WITH(write(), Catch::Contains(path.string()) &&
                                     Catch::Contains("labels and confidence differ in size"));
      CHECK_FALSE(std::filesystem::exists(path));
    }
  }
}

TEST_CASE("SemanticKITTI .label round-trip and truncation", "[lidar][io]") {
  const auto dir = test::tempDir("label");
  std::vector<uint32_t> labels = {0, 40, 48, (7u << 16) | 10u, 70, 80};
  io::writeSemanticKittiLabels(dir / "000000.label", labels);
  const auto back = io::readSemanticKittiLabels(dir / "000000.label");
  CHECK(back == labels);
  CHECK(io::semanticIdOf(back[3]) == 10);
  test::writeText(dir / "bad.label", std::string(10, '\0'));
  CHECK_THROWS_AS(io::readSemanticKittiLabels(dir / "bad.label"), ParseError);
}

TEST_CASE("KITTI poses file reads the odometry ground truth", "[lidar][io]") {
  const auto poses =
      io::readKittiOdometryPoses(test::requireShared("data/kitti_odometry/poses/00.txt"));
  REQUIRE(poses.size() == 6);
  CHECK(poses[0].translation().norm() < 1e-6);
  // "frames 0->1 move ~0.859 m forward" (data README)
  CHECK((poses[1].translation() - poses[0].translation()).norm() == Approx(0.859).margin(0.01));
  const auto dir = test::tempDir("poses");
  io::writeKittiOdometryPoses(dir / "p.txt", poses);
  const auto back = io::readKittiOdometryPoses(dir / "p.txt");
  REQUIRE(back.size() == 6);
  CHECK((back[5].matrix() - poses[5].matrix()).cwiseAbs().maxCoeff() < 1e-8);
  test::writeText(dir / "bad.txt", "1 0 0 0 0 1 0 0 0 0 1\n");
  CHECK_THROWS_MATCHES(io::readKittiOdometryPoses(dir / "bad.txt"), ParseError,
                       test::ParseErrorAt("line 1"));
}
