#include "mapfuse/sim/frames_writer.hpp"

#include <cmath>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <random>
#include <sstream>
#include <unordered_map>

#include "draw_order.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/json_geometry.hpp"
#include "mapfuse/io/png_frames.hpp"
#include "mapfuse/sim/point_cells.hpp"
#include "road_occlusion.hpp"

namespace mapfuse::sim {

namespace {
constexpr double kGroundStep = 0.5;      // m, ground polyline sampling
constexpr double kSampleCell = 10.0;     // m, grid of a line's samples (as the piece index's)
constexpr double kMinDepth = 1.0;        // m in front of the camera
constexpr double kLaneLineWidth = 0.15;  // m, painted width in masks
constexpr double kStopLineWidth = 0.30;  // m
constexpr double kPoleRadius = 0.1;      // m, for 2D boxes
constexpr double kLightHalfWidth = 0.2;  // m
constexpr int kShift = 4;                // sub-pixel bits of cv::fillPoly
constexpr double kPixelQuantum = 1e-3;   // px, rounding of written pixels

double roundPx(double v) {
  return std::round(v / kPixelQuantum) * kPixelQuantum;
}

std::string csvLine(std::initializer_list<double> values, int precision) {
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(precision);
  bool first = true;
  for (double v : values) {
    if (!first) os << ',';
    os << v;
    first = false;
  }
  os << '\n';
  return os.str();
}

/// calibration.json, frames.json (the manifest) and truth/sensor_errors.json.
void writeCalibrationAndManifest(const std::filesystem::path& dir, const World& world,
                                 const Drive& d, const SimCamera& camera, const DriveParams& DP,
                                 int frame_count) {
  const auto& C = camera.params();
  nlohmann::json calib;
  calib["format"] = "mapfuse.camera_calibration";
  calib["version"] = 1;
  const Eigen::Matrix3d& K = camera.K();
  calib["K"] = {K(0, 0), K(0, 1), K(0, 2), K(1, 0), K(1, 1), K(1, 2), K(2, 0), K(2, 1), K(2, 2)};
  calib["width"] = C.width;
  calib["height"] = C.height;
  calib["distortion"] = nlohmann::json::array();
  calib["T_body_cam"] = io::poseToJson(camera.T_body_cam());
  calib["camera_height"] = C.z;
  calib["ground_normal_cam"] = io::vec3ToJson(camera.groundNormalCam());
  io::writeDocument(dir / "calibration.json", calib, 2);
  nlohmann::json manifest = {{"format", "mapfuse.frames"},
                             {"version", 1},
                             {"drive_id", d.drive_id},
                             {"vehicle_id", d.vehicle_id},
                             {"origin", io::originToJson(world.truth.origin)},
                             {"calibration", "calibration.json"},
                             {"imu", "imu.csv"},
                             {"wheel", "wheel.csv"},
                             {"gps", "gps.csv"},
                             {"frames", "frames.csv"},
                             {"observations", "observations.jsonl"},
                             {"truth_poses", "truth/poses.csv"},
                             {"frame_count", frame_count},
                             {"camera_rate", DP.camera_rate},
                             {"imu_rate", DP.imu_rate},
                             {"wheel_rate", DP.wheel_rate},
                             {"gps_rate", DP.gps_rate},
                             {"mask_classes",
                              {{"0", "background"},
                               {"1", "lane_line"},
                               {"2", "stop_line"},
                               {"3", "ground_arrow"},
                               {"4", "crosswalk"}}}};
  io::writeDocument(dir / "frames.json", manifest, 2);
  nlohmann::json errors = {{"format", "mapfuse.sensor_errors"},
                           {"version", 1},
                           {"drive_id", d.drive_id},
                           {"wheel_scale_error", d.wheel_scale_error},
                           {"gyro_bias", {d.gyro_bias.x(), d.gyro_bias.y(), d.gyro_bias.z()}},
                           {"gps_initial_bias_enu", {d.gps_bias0.x(), d.gps_bias0.y()}}};
  io::writeDocument(dir / "truth" / "sensor_errors.json", errors, 2);
}

/// imu.csv, wheel.csv and gps.csv.
void writeSensorStreams(const std::filesystem::path& dir, const Drive& d) {
  std::string imu = "stamp,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z\n";
  for (const auto& s : d.imu)
    imu += csvLine(
        {s.stamp, s.gyro.x(), s.gyro.y(), s.gyro.z(), s.accel.x(), s.accel.y(), s.accel.z()}, 9);
  io::writeBytesAtomic(dir / "imu.csv", imu);
  std::string wheel = "stamp,speed\n";
  for (const auto& s : d.wheel) wheel += csvLine({s.stamp, s.speed}, 6);
  io::writeBytesAtomic(dir / "wheel.csv", wheel);
  std::string gps = "stamp,lat,lon,alt,sigma_h,sigma_v\n";
  for (const auto& g : d.gps)
    gps += csvLine({g.fix.stamp, g.fix.position.lat, g.fix.position.lon, g.fix.position.alt,
                    g.fix.sigma_h, g.fix.sigma_v},
                   9);
  io::writeBytesAtomic(dir / "gps.csv", gps);
}

/// What the camera sees in each frame: a mask of the painted ground classes and the
/// observations (ground pixels, aerial key points and boxes) with noisy pixels, drawn from one
/// stream in frame, piece, point order, and track ids that persist while a piece stays in view.
class FrameRenderer {
 public:
  FrameRenderer(const World& world, const PieceIndex& index, const Drive& d,
                const SimCamera& camera, const FramesParams& FP, std::size_t every, uint64_t seed)
      : world_(world),
        index_(index),
        d_(d),
        camera_(camera),
        C_(camera.params()),
        FP_(FP),
        every_(every),
        rng_(seed),
        occlusion_(d.truth, every) {}

  /// Renders frame f into `mask` (zeroed here); its observations into ground / aerial.
  void render(int f, cv::Mat& mask, nlohmann::json& ground, nlohmann::json& aerial) {
    f_ = f;
    k_ = static_cast<std::size_t>(f) * every_;
    T_enu_cam_ = d_.truth[k_] * camera_.T_body_cam();
    T_cam_enu_ = T_enu_cam_.inverse();
    mask = cv::Mat::zeros(C_.height, C_.width, CV_8UC1);
    ground = nlohmann::json::array(), aerial = nlohmann::json::array();
    centre_ = d_.truth[k_] * Eigen::Vector3d(C_.max_range / 2, 0, 0);
    radius_ = C_.max_range / 2 + 15.0;
    for (int pi : index_.near(centre_, radius_)) {
      const auto& piece = index_.pieces()[pi];
      const MapInstance& m = world_.truth.instances[piece.instance];
      const GeometryKind kind = geometryKind(m.cls);
      const bool is_ground = m.cls == CrowdClass::kLaneLine || m.cls == CrowdClass::kStopLine ||
                             m.cls == CrowdClass::kGroundArrow || m.cls == CrowdClass::kCrosswalk;
      if (is_ground && kind == GeometryKind::kLine)
        groundLine(pi, m, piece.points, mask, ground);
      else if (is_ground)
        groundPolygon(pi, m, piece.points, mask, ground);
      else
        aerialElement(pi, m, kind, piece.points, aerial);
    }
  }

 private:
  int trackOf(int piece) {
    auto it = tracks_.find(piece);
    if (it == tracks_.end() || it->second.second != f_ - 1)
      it = tracks_.insert_or_assign(piece, std::make_pair(next_track_++, f_)).first;
    it->second.second = f_;
    return it->second.first;
  }
  std::optional<Eigen::Vector2d> pixel(const Eigen::Vector3d& p_enu) const {
    return camera_.project(T_cam_enu_ * p_enu, kMinDepth);
  }
  bool hidden(const Eigen::Vector3d& p_enu) const {  // beyond a crest
    return occlusion_.hidden(k_, T_enu_cam_.translation(), p_enu, C_.max_range + 5.0);
  }
  bool inImage(const Eigen::Vector2d& uv) const {
    return uv.x() >= -0.5 && uv.y() >= -0.5 && uv.x() <= C_.width - 0.5 &&
           uv.y() <= C_.height - 0.5;
  }
  nlohmann::json noisyPx(const Eigen::Vector2d& uv) {
    const Eigen::Vector2d n = FP_.pixel_sigma > 0
                                  ? Eigen::Vector2d(FP_.pixel_sigma * drawVector2(N01_, rng_))
                                  : Eigen::Vector2d::Zero();
    return nlohmann::json::array({roundPx(uv.x() + n.x()), roundPx(uv.y() + n.y())});
  }
  static cv::Point toCv(const Eigen::Vector2d& uv) {
    return cv::Point(static_cast<int>(std::lround((uv.x()) * (1 << kShift))),
                     static_cast<int>(std::lround((uv.y()) * (1 << kShift))));
  }
  void addGround(int pi, const MapInstance& m, nlohmann::json px, nlohmann::json& ground) {
    nlohmann::json o = {{"instance", ground.size()}, {"track_id", trackOf(pi)}, {"truth_id", m.id}};
    io::writeClassAndAttributes(o, m.cls, m.attributes);
    o["pixels"] = std::move(px);
    ground.push_back(o);
  }

  /// A line's samples (kGroundStep apart) and their cells, made on its first frame.
  struct Samples {
    Polyline pts;
    PointCells cells;
  };
  const Samples& samplesOf(int pi, const Polyline& points) {
    auto it = samples_.find(pi);
    if (it == samples_.end()) {
      Polyline pts = resample(points, kGroundStep);
      PointCells cells(pts, kSampleCell);
      it = samples_.emplace(pi, Samples{std::move(pts), std::move(cells)}).first;
    }
    return it->second;
  }

  /// A painted line: its seen samples' pixels, its strip painted into the mask. Only the samples
  /// in the cells of this frame's query: the others are out of the view and paint nothing (a
  /// solid lane line is one piece however long).
  void groundLine(int pi, const MapInstance& m, const Polyline& points, cv::Mat& mask,
                  nlohmann::json& ground) {
    const Samples& samples = samplesOf(pi, points);
    const Polyline& pts = samples.pts;
    const double half = (m.cls == CrowdClass::kStopLine ? kStopLineWidth : kLaneLineWidth) / 2;
    nlohmann::json px = nlohmann::json::array();
    for (const uint32_t i : samples.cells.near(centre_, radius_)) {
      const Eigen::Vector3d pc = T_cam_enu_ * pts[i];
      const auto uv = camera_.project(pc, kMinDepth);
      const bool seen = uv && inImage(*uv) && pc.norm() <= C_.max_range && !hidden(pts[i]);
      if (seen) px.push_back(noisyPx(*uv));
      if (i + 1 < pts.size() && !hidden(pts[i])) {  // painted strip segment
        const Eigen::Vector3d dir = (pts[i + 1] - pts[i]).normalized();
        const Eigen::Vector3d n(-dir.y() * half, dir.x() * half, 0.0);
        const auto a = pixel(pts[i] + n), b = pixel(pts[i + 1] + n), c = pixel(pts[i + 1] - n),
                   e = pixel(pts[i] - n);
        if (a && b && c && e && (T_cam_enu_ * pts[i]).norm() <= C_.max_range + 5.0) {
          const cv::Point quad[4] = {toCv(*a), toCv(*b), toCv(*c), toCv(*e)};
          cv::fillConvexPoly(mask, quad, 4, cv::Scalar(static_cast<int>(m.cls) + 1), cv::LINE_8,
                             kShift);
        }
      }
    }
    if (px.size() >= 2) addGround(pi, m, std::move(px), ground);
  }

  /// A painted polygon: every corner in front of the camera (their pixels drawn as they come),
  /// at least one in the image.
  void groundPolygon(int pi, const MapInstance& m, const Polyline& points, cv::Mat& mask,
                     nlohmann::json& ground) {
    std::vector<cv::Point> poly;
    nlohmann::json px = nlohmann::json::array();
    bool any_inside = false;
    for (const auto& p : points) {
      const Eigen::Vector3d pc = T_cam_enu_ * p;
      const auto uv = camera_.project(pc, kMinDepth);
      if (!uv || pc.norm() > C_.max_range || hidden(p)) return;
      any_inside = any_inside || inImage(*uv);
      poly.push_back(toCv(*uv));
      px.push_back(noisyPx(*uv));
    }
    if (!any_inside) return;
    cv::fillPoly(mask, std::vector<std::vector<cv::Point>>{poly},
                 cv::Scalar(static_cast<int>(m.cls) + 1), cv::LINE_8, kShift);
    addGround(pi, m, std::move(px), ground);
  }

  /// A sign, light or pole: its key points (a point element's base and top) and a 2D box.
  void aerialElement(int pi, const MapInstance& m, GeometryKind kind, const Polyline& points,
                     nlohmann::json& aerial) {
    Polyline keys = points;
    double half_width = 0.0;
    if (kind == GeometryKind::kPoint) {
      keys.push_back(keys[0] + Eigen::Vector3d(0, 0, m.height));
      half_width = m.cls == CrowdClass::kPole ? kPoleRadius : kLightHalfWidth;
    }
    std::vector<Eigen::Vector2d> uvs;
    double umin = 1e300, vmin = 1e300, umax = -1e300, vmax = -1e300;
    for (const auto& p : keys) {
      const Eigen::Vector3d pc = T_cam_enu_ * p;
      const auto uv = camera_.project(pc, kMinDepth);
      if (!uv || pc.norm() > C_.max_range) return;
      const double du = C_.fx * half_width / pc.z();
      umin = std::min(umin, uv->x() - du), umax = std::max(umax, uv->x() + du);
      vmin = std::min(vmin, uv->y()), vmax = std::max(vmax, uv->y());
      uvs.push_back(*uv);
    }
    umin = std::max(umin, -0.5), vmin = std::max(vmin, -0.5);
    umax = std::min(umax, C_.width - 0.5), vmax = std::min(vmax, C_.height - 0.5);
    if (umax - umin < 1.0 || vmax - vmin < 1.0) return;
    nlohmann::json o = {
        {"track_id", trackOf(pi)}, {"truth_id", m.id}, {"class", crowdClassName(m.cls)}};
    o["box"] = {roundPx(umin), roundPx(vmin), roundPx(umax), roundPx(vmax)};
    nlohmann::json px = nlohmann::json::array();
    for (const auto& uv : uvs) px.push_back(noisyPx(uv));
    o["points"] = px;
    aerial.push_back(o);
  }

  const World& world_;
  const PieceIndex& index_;
  const Drive& d_;
  const SimCamera& camera_;
  const CameraParams& C_;
  const FramesParams& FP_;
  const std::size_t every_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> N01_{0.0, 1.0};
  const RoadOcclusion occlusion_;              // markings beyond a crest are not seen
  std::map<int, std::pair<int, int>> tracks_;  // piece -> (track id, last frame)
  int next_track_ = 0;
  int f_ = 0;
  std::size_t k_ = 0;
  Pose3 T_enu_cam_, T_cam_enu_;
  Eigen::Vector3d centre_ = Eigen::Vector3d::Zero();  // ENU, this frame's query of the pieces
  double radius_ = 0.0;                               // m
  std::unordered_map<int, Samples> samples_;          // piece -> its line's samples
};

}  // namespace

FramesStats writeFramesDrive(const std::filesystem::path& dir, const World& world,
                             const PieceIndex& index, const Drive& d, const SimCamera& camera,
                             const DriveParams& DP, const FramesParams& FP, uint64_t seed) {
  FramesStats stats;
  const std::size_t every = cameraStride(DP);
  const int frame_count = static_cast<int>((d.stamps.size() + every - 1) / every);
  writeCalibrationAndManifest(dir, world, d, camera, DP, frame_count);
  writeSensorStreams(dir, d);
  std::string frames_csv = "index,stamp,mask\n", poses_csv = "index,stamp,tx,ty,tz,qw,qx,qy,qz\n";
  std::string jsonl;
  FrameRenderer renderer(world, index, d, camera, FP, every, seed);
  for (int f = 0; f < frame_count; ++f) {
    const std::size_t k = static_cast<std::size_t>(f) * every;
    char name[32];
    std::snprintf(name, sizeof name, "masks/%06d.png", f);
    frames_csv += std::to_string(f) + "," + csvLine({d.stamps[k]}, 4);
    if (!FP.masks)
      frames_csv.replace(frames_csv.size() - 1, 1, ",\n");
    else
      frames_csv.insert(frames_csv.size() - 1, std::string(",") + name);
    const Eigen::Quaterniond q(d.truth[k].linear());
    const Eigen::Vector3d t = d.truth[k].translation();
    poses_csv += std::to_string(f) + "," +
                 csvLine({d.stamps[k], t.x(), t.y(), t.z(), q.w(), q.x(), q.y(), q.z()}, 9);
    cv::Mat mask;
    nlohmann::json ground, aerial;
    renderer.render(f, mask, ground, aerial);
    stats.ground_observations += static_cast<int>(ground.size());
    stats.aerial_observations += static_cast<int>(aerial.size());
    jsonl += nlohmann::json(
                 {{"frame", f}, {"stamp", d.stamps[k]}, {"ground", ground}, {"aerial", aerial}})
                 .dump() +
             "\n";
    if (FP.masks) io::writePngFrame(dir / name, mask);
    ++stats.frames;
  }
  io::writeBytesAtomic(dir / "frames.csv", frames_csv);
  io::writeBytesAtomic(dir / "truth" / "poses.csv", poses_csv);
  io::writeBytesAtomic(dir / "observations.jsonl", jsonl);
  return stats;
}

}  // namespace mapfuse::sim
