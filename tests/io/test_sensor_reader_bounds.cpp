// Sensor-format readers (KITTI calibration, OXTS, timestamps, Velodyne, PLY, PCD, PNG semantics)
// refuse values outside docs/formats.md "Value bounds" before narrowing, multiplying or
// allocating (issue 19). Each case is an input that overflowed, wrapped or was undefined before.
#include <catch2/catch.hpp>
#include <cstring>
#include <limits>

#include "mapfuse/core/error.hpp"
#include "mapfuse/geo/oxts.hpp"
#include "mapfuse/io/oxts_line.hpp"
#include "mapfuse/io/kitti_calib.hpp"
#include "mapfuse/io/kitti_raw.hpp"
#include "mapfuse/io/pcd.hpp"
#include "mapfuse/io/ply.hpp"
#include "mapfuse/io/semantic_image.hpp"
#include "mapfuse/io/semantic_kitti.hpp"
#include "mapfuse/io/velodyne.hpp"

using namespace mapfuse;
using Catch::Contains;

namespace {

const char* const kCam =
    "S_rect_02: 1.242000e+03 3.750000e+02\n"
    "R_rect_00: 1 0 0 0 1 0 0 0 1\n"
    "P_rect_02: 7.215377e+02 0 6.095593e+02 4.485728e+01 0 7.215377e+02 1.728540e+02 "
    "2.163791e-01 0 0 1 2.745884e-03\n";
const char* const kVelo = "R: 1 0 0 0 1 0 0 0 1\nT: -4.069766e-03 -7.631618e-02 -2.717806e-01\n";

io::KittiCalibration calibrate(const std::string& cam, const std::string& velo = kVelo) {
  return io::kittiCalibrationFromFiles(io::KittiCalibFile::parse(cam, "cam.txt"),
                                       io::KittiCalibFile::parse(velo, "velo.txt"), nullptr);
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  return text.replace(text.find(from), from.size(), to);
}

const std::string kOxts =
    "49.011212804408 8.4228850417969 112.83492279053 0.022447 1e-05 -1.2219096732051 "
    "-3.3256321640686 1.1384311814592 3.5147680214713 0.037625160413037 -0.03878884255623 "
    "-0.29437452763793 0.037166856911681 9.9957015129717 -0.30581030960531 -0.19635662515203 "
    "9.9942128010936 -0.017332142869546 0.024792163815438 0.14511808479348 -0.017498934149631 "
    "0.021393359392165 0.14563031426063 0.49229361157748 0.068883960397178 4 10 4 4 0";

template <class T>
std::string bytesOf(const T& v) {
  return std::string(reinterpret_cast<const char*>(&v), sizeof v);
}

}  // namespace

TEST_CASE("KITTI calibration: image size and extrinsics within bounds", "[io][bounds][kitti]") {
  const io::KittiCalibration c = calibrate(kCam);
  CHECK(c.image_width == 1242);
  CHECK(c.image_height == 375);
  // A huge S_rect overflowed int: "image_02 is -727379968x-727379968".
  CHECK_THROWS_WITH(calibrate(replaced(kCam, "1.242000e+03 3.750000e+02", "5e9 5e9")),
                    Contains("cam.txt") && Contains("S_rect_02"));
  CHECK_THROWS_WITH(calibrate(replaced(kCam, "1.242000e+03 3.750000e+02", "60000 60000")),
                    Contains("S_rect_02") && Contains("pixels"));
  CHECK_THROWS_WITH(calibrate(kCam, replaced(kVelo, "T: -4.069766e-03", "T: 1e6")),
                    Contains("velo.txt") && Contains("field 'T'"));
  CHECK_THROWS_WITH(calibrate(replaced(kCam, "7.215377e+02 0 6.095593e+02", "1e300 0 1")),
                    Contains("P_rect_02"));
  CHECK_THROWS_WITH(calibrate(replaced(kCam, "R_rect_00: 1 0 0", "R_rect_00: 2 0 0")),
                    Contains("R_rect_00"));
}

TEST_CASE("OXTS: ranges checked, status fields integers before the int conversion",
          "[io][bounds][kitti]") {
  const geo::OxtsRecord r = io::parseOxtsLine(kOxts, "o.txt");
  CHECK(r.numsats == 10);
  // navstat 1e300 converted to int was undefined behaviour.
  CHECK_THROWS_WITH(io::parseOxtsLine(replaced(kOxts, " 4 10 4 4 0", " 1e300 10 4 4 0"), "o.txt"),
                    Contains("navstat"));
  CHECK_THROWS_WITH(io::parseOxtsLine(replaced(kOxts, " 4 10 4 4 0", " 4 10.5 4 4 0"), "o.txt"),
                    Contains("numsats") && Contains("integer"));
  // The devkit's Mercator pose is infinite at the poles.
  CHECK_THROWS_WITH(io::parseOxtsLine(replaced(kOxts, "49.011212804408", "-90"), "o.txt"),
                    Contains("field 'lat'"));
  CHECK_THROWS_WITH(io::parseOxtsLine(replaced(kOxts, "112.83492279053", "1e9"), "o.txt"),
                    Contains("field 'alt'"));
}

TEST_CASE("KITTI timestamps: strict digits, the same seconds as before", "[io][bounds][kitti]") {
  CHECK(io::parseKittiTimestamp("2011-09-26 13:04:32.335337762", "t", "l") ==
        13 * 3600.0 + 4 * 60.0 + 32.335337762);
  // "nan" seconds passed the range check (NaN compares false) before.
  CHECK_THROWS_AS(io::parseKittiTimestamp("2011-09-26 13:04:nan", "t", "l"), ParseError);
  CHECK_THROWS_AS(io::parseKittiTimestamp("2011-09-26 13:04:1e5", "t", "l"), ParseError);
  CHECK_THROWS_AS(io::parseKittiTimestamp("2011-09-26 99999999999:04:05", "t", "l"), ParseError);
  CHECK_THROWS_AS(io::parseKittiTimestamp("2011-09-26 13:04:05 tail", "t", "l"), ParseError);
  const auto stamps = io::parseKittiTimestamps("2011-09-26 13:04:32.3\n\n2011-09-26 13:04:32.4\r\n",
                                               "timestamps.txt");
  CHECK(stamps.size() == 2);
  CHECK_THROWS_WITH(io::parseKittiTimestamps("2011-09-26 13:04:32.3\n\nbad\n", "timestamps.txt"),
                    Contains("line 3"));
}

TEST_CASE("KITTI timestamps: a fraction of 30 digits does not overflow", "[io][bounds][kitti]") {
  // Fuzz finding (fuzz_kitti_timestamps, minimised): the fraction's digits were accumulated into a
  // long, which overflowed (undefined) past 18 digits; up to 30 digits are allowed.
  const double t =
      io::parseKittiTimestamp("2011-09-26 13:04:33.161788781556152220112345678901", "t", "l");
  CHECK(t == Approx(13 * 3600.0 + 4 * 60.0 + 33.161788781556152).margin(1e-9));
  CHECK_THROWS_AS(
      io::parseKittiTimestamp("2011-09-26 13:04:33.1617887815561522201123456789012", "t", "l"),
      ParseError);  // 31 digits
}

TEST_CASE("Velodyne: a return beyond the LiDAR range is refused", "[io][bounds][kitti]") {
  const float ok[4] = {10.f, -3.f, 1.f, 0.5f};
  CHECK(io::parseVelodyneBin(bytesOf(ok), "s.bin").size() == 1);
  const float far[4] = {1e30f, 0.f, 0.f, 0.5f};
  CHECK_THROWS_WITH(io::parseVelodyneBin(bytesOf(ok) + bytesOf(far), "s.bin"), Contains("point 1"));
  const float nan_reflectance[4] = {1.f, 0.f, 0.f, std::numeric_limits<float>::quiet_NaN()};
  CHECK_THROWS_WITH(io::parseVelodyneBin(bytesOf(nan_reflectance), "s.bin"),
                    Contains("reflectance"));
}

TEST_CASE("PLY and PCD: counts multiplied in 64 bits, labels and coordinates checked",
          "[io][bounds][clouds]") {
  const std::string ply_header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty double x\n"
      "property double y\nproperty double z\nproperty int label\nend_header\n";
  struct {
    double x, y, z;
    int32_t label;
  } __attribute__((packed)) v{1.0, 2.0, 3.0, 2};
  CHECK(io::parsePly(ply_header + bytesOf(v), "m.ply").labels[0] == 2);
  // n * stride wrapped around 2^64 and passed the truncation check.
  CHECK_THROWS_WITH(
      io::parsePly(replaced(ply_header, "vertex 1", "vertex 922337203685477580") + bytesOf(v),
                   "m.ply"),
      Contains("truncated"));
  v.label = 300;  // was cast to uint8_t: 44
  CHECK_THROWS_WITH(io::parsePly(ply_header + bytesOf(v), "m.ply"), Contains("vertex 0 label"));
  v.label = 2;
  v.x = 1e300;  // a double beyond float: undefined when converted
  CHECK_THROWS_WITH(io::parsePly(ply_header + bytesOf(v), "m.ply"), Contains("vertex 0 x"));

  const std::string pcd_header =
      "VERSION 0.7\nFIELDS x y z label\nSIZE 4 4 4 4\nTYPE F F F U\nCOUNT 1 1 1 1\nWIDTH 1\n"
      "HEIGHT 1\nPOINTS 1\nDATA binary\n";
  struct {
    float x, y, z;
    uint32_t label;
  } p{1.f, 2.f, 3.f, 1};
  CHECK(io::parsePcd(pcd_header + bytesOf(p), "m.pcd").labels[0] == 1);
  CHECK_THROWS_WITH(
      io::parsePcd(replaced(pcd_header, "SIZE 4 4 4 4", "SIZE 4 4 4 -4") + bytesOf(p), "m.pcd"),
      Contains("SIZE"));
  CHECK_THROWS_WITH(
      io::parsePcd(replaced(pcd_header, "COUNT 1 1 1 1", "COUNT 1 1 1 2147483647") + bytesOf(p),
                   "m.pcd"),
      Contains("COUNT"));
  CHECK_THROWS_WITH(
      io::parsePcd(replaced(pcd_header, "POINTS 1", "POINTS 4611686018427387904") + bytesOf(p),
                   "m.pcd"),
      Contains("truncated"));
  p.label = 256;  // was truncated to 0
  CHECK_THROWS_WITH(io::parsePcd(pcd_header + bytesOf(p), "m.pcd"), Contains("point 0 label"));
}

TEST_CASE("PNG semantics: the declared size is checked before decoding", "[io][bounds]") {
  // A 33-byte PNG whose header declares 65535 x 65535 pixels (4 GB once decoded).
  std::string png("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR\0\0\xff\xff\0\0\xff\xff\x08\0\0\0\0\0\0\0\0",
                  33);
  CHECK_THROWS_WITH(io::parseSemanticImage(png, "f.png"),
                    Contains("f.png") && Contains("65535x65535"));
  CHECK_THROWS_WITH(io::parseSemanticImage("not a png at all, not at all", "f.png"),
                    Contains("not a PNG"));
  CHECK_THROWS_WITH(io::parseSemanticImage("mapfuse-prob 1 65535 65535 8\n", "f.prob"),
                    Contains("pixels"));
}

TEST_CASE("an empty SemanticKITTI label file is an empty scan", "[io][bounds][kitti]") {
  // Fuzz finding (fuzz_semantic_labels, empty input): memcpy from a null vector.data() is
  // undefined even for 0 bytes.
  CHECK(io::parseSemanticKittiLabels("", "empty.label").empty());
  const std::string two("\x01\x00\x02\x00\x28\x00\x00\x00", 8);
  CHECK(io::parseSemanticKittiLabels(two, "two.label") == std::vector<uint32_t>{0x20001, 40});
}
