#include "mapfuse/io/drive_frames.hpp"

#include <Eigen/SVD>
#include <cmath>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "csv_table.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/bounds.hpp"
#include "mapfuse/io/camera_calib.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/json_geometry.hpp"
#include "mapfuse/io/kitti_poses.hpp"
#include "mapfuse/io/png_decode.hpp"
#include "relative_path.hpp"

namespace mapfuse::io {
namespace fs = std::filesystem;
namespace {
using detail::Csv;
using detail::forEachLine;
using detail::readCsv;
using detail::requireSorted;

std::vector<Eigen::Vector2d> readPixels(const JsonView& v) {
  std::vector<Eigen::Vector2d> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const JsonView px = v.at(i);
    px.vector(2);  // checks the count
    out.emplace_back(px.at(std::size_t(0)).number(-bounds::kMaxPixel, bounds::kMaxPixel),
                     px.at(std::size_t(1)).number(-bounds::kMaxPixel, bounds::kMaxPixel));
  }
  return out;
}

FrameObservations parseObservation(const JsonView& v) {
  v.onlyKeys({"frame", "stamp", "ground", "aerial"});
  FrameObservations f;
  f.index = v.at("frame").integerInt(0);
  f.stamp = v.at("stamp").number(-bounds::kMaxStamp, bounds::kMaxStamp);
  if (auto g = v.find("ground"))
    for (std::size_t i = 0; i < g->size(); ++i) {
      const JsonView e = g->at(i);
      e.onlyKeys({"instance", "track_id", "truth_id", "class", "style", "color", "pixels"});
      GroundObservation o;
      readClassAndAttributes(e, o.cls, o.attributes);
      if (geometryKind(o.cls) == GeometryKind::kPoint || o.cls == CrowdClass::kTrafficSign)
        e.at("class").fail("is not a ground marking class");
      if (auto t = e.find("track_id")) o.track_id = t->integer();
      if (auto t = e.find("truth_id")) o.truth_id = t->integer();
      o.pixels = readPixels(e.at("pixels"));
      f.ground.push_back(std::move(o));
    }
  if (auto a = v.find("aerial"))
    for (std::size_t i = 0; i < a->size(); ++i) {
      const JsonView e = a->at(i);
      e.onlyKeys({"track_id", "truth_id", "class", "box", "points"});
      AerialObservation o;
      Attributes unused;
      readClassAndAttributes(e, o.cls, unused);
      if (o.cls != CrowdClass::kTrafficSign && o.cls != CrowdClass::kTrafficLight &&
          o.cls != CrowdClass::kPole)
        e.at("class").fail("is not an aerial class (traffic_sign, traffic_light, pole)");
      if (auto t = e.find("track_id")) o.track_id = t->integer();
      if (auto t = e.find("truth_id")) o.truth_id = t->integer();
      o.box = e.at("box").vector(4);
      if (o.box.cwiseAbs().maxCoeff() > bounds::kMaxPixel)
        e.at("box").fail("outside " + bounds::rangeText(-bounds::kMaxPixel, bounds::kMaxPixel) +
                         " px");
      if (o.box(2) < o.box(0) || o.box(3) < o.box(1)) e.at("box").fail("max is below min");
      if (auto p = e.find("points")) o.points = readPixels(*p);
      f.aerial.push_back(std::move(o));
    }
  return f;
}

std::vector<FrameObservations> readObservations(const fs::path& path) {
  std::vector<FrameObservations> out;
  forEachLine(path, [&](const std::string& line, int n) {
    Json j;
    try {
      j = parseDocument(line, Encoding::kJson, path.string());
    } catch (const ParseError& e) {
      throw ParseError(path.string(), "line " + std::to_string(n), e.problem());
    }
    out.push_back(parseObservation(JsonView(j, path.string(), "line " + std::to_string(n))));
  });
  return out;
}

}  // namespace

DriveFrames readDriveFrames(const fs::path& dir) {
  const fs::path manifest = dir / "frames.json";
  if (!fileExists(manifest)) throw IoError(manifest.string(), "no such file (not a drive folder)");
  const Json doc = readDocument(manifest);
  const JsonView v(doc, manifest.string());
  v.checkFormat(kFramesFormat, 1);
  DriveFrames d;
  d.dir = dir;
  d.drive_id = v.at("drive_id").string();
  if (auto s = v.find("vehicle_id")) d.vehicle_id = s->string();
  if (auto o = v.find("origin")) d.origin = readOrigin(*o);
  auto file = [&](const char* key) -> fs::path {
    const auto f = v.find(key);
    if (!f) v.at(key);  // throws "missing"
    const std::string name = f->string();
    if (const std::string why = relativeNameProblem(name); !why.empty()) f->fail(why);
    return dir / name;
  };

  const fs::path calib_path = file("calibration");
  if (!fileExists(calib_path)) throw IoError(calib_path.string(), "camera calibration missing");
  d.calib = readCameraCalib(calib_path);

  {
    const Csv c = readCsv(file("imu"),
                          {"stamp", "gyro_x", "gyro_y", "gyro_z", "accel_x", "accel_y", "accel_z"});
    std::vector<double> stamps;
    for (std::size_t r = 0; r < c.rows.size(); ++r) {
      ImuSample s;
      s.stamp = c.stamp(r, 0);
      for (int k = 0; k < 3; ++k) {
        s.gyro[k] = c.number(r, 1 + k, -bounds::kMaxAngularRate, bounds::kMaxAngularRate);
        s.accel[k] = c.number(r, 4 + k, -bounds::kMaxAcceleration, bounds::kMaxAcceleration);
      }
      d.imu.push_back(s);
      stamps.push_back(s.stamp);
    }
    requireSorted(c, stamps);
  }
  {
    const Csv c = readCsv(file("wheel"), {"stamp", "speed"});
    std::vector<double> stamps;
    for (std::size_t r = 0; r < c.rows.size(); ++r) {
      d.wheel.push_back({c.stamp(r, 0), c.number(r, 1, -bounds::kMaxSpeed, bounds::kMaxSpeed)});
      stamps.push_back(c.number(r, 0));
    }
    requireSorted(c, stamps);
  }
  if (v.has("gps")) {
    const Csv c = readCsv(file("gps"), {"stamp", "lat", "lon", "alt", "sigma_h", "sigma_v"});
    for (std::size_t r = 0; r < c.rows.size(); ++r) {
      GpsFix g;
      g.stamp = c.stamp(r, 0);
      g.position = {c.number(r, 1, -90.0, 90.0), c.number(r, 2, -180.0, 180.0),
                    c.number(r, 3, bounds::kMinAltitude, bounds::kMaxAltitude)};
      g.sigma_h = c.number(r, 4, 0.0, bounds::kMaxSigma);
      g.sigma_v = c.number(r, 5, 0.0, bounds::kMaxSigma);
      if (g.sigma_h <= 0.0 || g.sigma_v <= 0.0)
        throw ParseError(c.file, "line " + std::to_string(c.line_numbers[r]),
                         "invalid fix (sigma not positive)");
      d.gps.push_back(g);
    }
  }
  {
    const Csv c = readCsv(file("frames"), {"index", "stamp", "mask"});
    for (std::size_t r = 0; r < c.rows.size(); ++r) {
      FrameEntry f;
      const double index = c.number(r, 0);
      f.stamp = c.stamp(r, 1);
      if (index != double(r))
        throw ParseError(c.file, "line " + std::to_string(c.line_numbers[r]) + " index",
                         "expected frame " + std::to_string(r));
      f.index = int(r);
      if (const std::string& name = c.rows[r][2]; !name.empty()) {
        if (const std::string why = relativeNameProblem(name); !why.empty())
          throw ParseError(c.file, "line " + std::to_string(c.line_numbers[r]) + " mask", why);
        f.mask = dir / name;
      }
      d.frames.push_back(f);
    }
  }
  if (d.frames.empty()) throw InputError(manifest.string() + ": the drive has no frames");
  if (auto fc = v.find("frame_count"))
    if (fc->integer() != int64_t(d.frames.size()))
      throw InputError(manifest.string() + ": frame_count is " + std::to_string(fc->integer()) +
                       " but " + file("frames").string() + " lists " +
                       std::to_string(d.frames.size()) + " frames");
  if (v.has("observations") && fileExists(file("observations"))) {
    d.observations = readObservations(file("observations"));
    if (d.observations.size() != d.frames.size())
      throw InputError(file("observations").string() + " has " +
                       std::to_string(d.observations.size()) + " frames but frames.csv lists " +
                       std::to_string(d.frames.size()));
    for (std::size_t i = 0; i < d.frames.size(); ++i)
      if (d.observations[i].index != d.frames[i].index)
        throw ParseError(file("observations").string(), "line " + std::to_string(i + 1) + " frame",
                         "expected frame " + std::to_string(d.frames[i].index));
  }
  if (v.has("truth_poses") && fileExists(file("truth_poses"))) {
    const Csv c =
        readCsv(file("truth_poses"), {"index", "stamp", "tx", "ty", "tz", "qw", "qx", "qy", "qz"});
    for (std::size_t r = 0; r < c.rows.size(); ++r) {
      Pose3 T = Pose3::Identity();
      for (int k = 0; k < 3; ++k)
        T.translation()[k] = c.number(r, 2 + k, -bounds::kMaxCoordinate, bounds::kMaxCoordinate);
      const Eigen::Quaterniond q(c.number(r, 5), c.number(r, 6), c.number(r, 7), c.number(r, 8));
      if (std::abs(q.norm() - 1.0) > 1e-3)
        throw ParseError(c.file, "line " + std::to_string(c.line_numbers[r]) + " qw",
                         "quaternion norm is " + std::to_string(q.norm()) + ", expected 1");
      T.linear() = q.normalized().toRotationMatrix();
      d.truth_T_enu_body.push_back(T);
    }
  }
  return d;
}

cv::Mat readMask(const fs::path& path, int width, int height) {
  if (!fileExists(path)) throw IoError(path.string(), "mask image missing");
  const cv::Mat img = decodePng(readBytes(path), path.string(), cv::IMREAD_UNCHANGED);
  if (img.type() != CV_8UC1)
    throw ParseError(path.string(), "", "mask must be an 8-bit single-channel image");
  if (img.cols != width || img.rows != height)
    throw ParseError(path.string(), "",
                     "mask is " + std::to_string(img.cols) + "x" + std::to_string(img.rows) +
                         ", calibration says " + std::to_string(width) + "x" +
                         std::to_string(height));
  return img;
}

std::vector<Pose3> readKittiPoses(const fs::path& path) {
  return readKittiOdometryPoses(path);  // one reader for every poses file (io/kitti_poses.hpp)
}

std::vector<Pose3> parseKittiPoses(const std::string& text, const std::string& file) {
  return parseKittiOdometryPoses(text, file);
}

}  // namespace mapfuse::io
