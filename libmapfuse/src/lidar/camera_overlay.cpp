#include "mapfuse/lidar/camera_overlay.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/io/picture_key.hpp"
#include "mapfuse/io/png_frames.hpp"
#include "mapfuse/io/velodyne.hpp"
#include "mapfuse/lidar/projection.hpp"

namespace mapfuse::lidar {
namespace fs = std::filesystem;

namespace {
constexpr uint8_t kNone = 255;  // labels image: nothing painted

struct Splat {
  float depth;  // m along the optical axis
  int u, v;     // px, nearest pixel
  int side;     // px
  uint8_t label;
};
}  // namespace

CameraOverlay renderCameraOverlay(const cv::Mat& bgr, const OverlayPoints& pts,
                                  const Eigen::Matrix<double, 3, 4>& P, const OverlayStyle& style) {
  if (bgr.empty() || bgr.type() != CV_8UC3)
    throw InputError("camera overlay: the photo must be a non-empty 8-bit BGR image");
  if (pts.points_velo.size() != pts.labels.size())
    throw InputError("camera overlay: " + std::to_string(pts.points_velo.size()) + " points but " +
                     std::to_string(pts.labels.size()) + " labels");
  CameraOverlay out;
  // Focal length in px: the left 3x3 of P is K R (R a rotation), whose rows 0 and 2 are
  // f_u r0 + c_u r2 and r2, so |row0 x row2| / |row2|^2 = f_u (any overall scale cancels).
  const Eigen::Vector3d m0 = P.row(0).head<3>().transpose(), m2 = P.row(2).head<3>().transpose();
  const double fu = m0.cross(m2).norm() / std::max(m2.squaredNorm(), 1e-12);
  const double r2max = style.max_range * style.max_range;
  std::vector<Splat> splats;
  splats.reserve(pts.points_velo.size() / 2);
  for (std::size_t i = 0; i < pts.points_velo.size(); ++i) {
    const Eigen::Vector3d p = pts.points_velo[i].cast<double>();
    double u = 0, v = 0;
    if (p.squaredNorm() > r2max || !projectPoint(P, p, &u, &v)) {  // eq. (2)-(3)
      ++out.behind;
      continue;
    }
    const int iu = static_cast<int>(std::floor(u + 0.5)),
              iv = static_cast<int>(std::floor(v + 0.5));
    if (iu < 0 || iv < 0 || iu >= bgr.cols || iv >= bgr.rows) {
      ++out.outside;
      continue;
    }
    const double depth = (m2.dot(p) + P(2, 3)) / m2.norm();  // m along the optical axis
    const int side =
        std::clamp(static_cast<int>(std::lround(style.splat_size * fu / depth)), style.min_splat_px,
                   std::max(style.min_splat_px, style.max_splat_px));
    splats.push_back({static_cast<float>(depth), iu, iv, side, pts.labels[i]});
  }
  // Painter's order: farthest first, so the nearest point owns each pixel.
  std::sort(splats.begin(), splats.end(),
            [](const Splat& a, const Splat& b) { return a.depth > b.depth; });
  out.labels = cv::Mat(bgr.rows, bgr.cols, CV_8UC1, cv::Scalar(kNone));
  for (const Splat& s : splats) {
    const int u0 = std::max(0, s.u - (s.side - 1) / 2), v0 = std::max(0, s.v - (s.side - 1) / 2);
    const int u1 = std::min(bgr.cols - 1, s.u + s.side / 2);
    const int v1 = std::min(bgr.rows - 1, s.v + s.side / 2);
    for (int r = v0; r <= v1; ++r) {
      uint8_t* row = out.labels.ptr<uint8_t>(r);
      for (int c = u0; c <= u1; ++c) row[c] = s.label;
    }
  }
  out.drawn = splats.size();
  // Blend the painted pixels: alpha * class colour + (1 - alpha) * photo.
  cv::Mat photo = bgr.clone();
  const double a = std::clamp(style.alpha, 0.0, 1.0);
  for (int r = 0; r < photo.rows; ++r) {
    const uint8_t* lab = out.labels.ptr<uint8_t>(r);
    cv::Vec3b* px = photo.ptr<cv::Vec3b>(r);
    for (int c = 0; c < photo.cols; ++c) {
      if (lab[c] == kNone) continue;
      const auto cls = static_cast<LidarClass>(lab[c]);
      out.classes.insert(cls);
      const auto rgb = lidarClassColor(cls);
      for (int k = 0; k < 3; ++k)
        px[c][k] = cv::saturate_cast<uint8_t>(a * rgb[2 - k] + (1.0 - a) * px[c][k]);
    }
  }
  io::PictureKey key{io::lidarLegend(out.classes), 0.0, false, style.title, ""};
  for (const auto& e : key.legend) out.legend.push_back(e.label);
  out.image = io::withPictureKey(photo, key);
  return out;
}

OverlayPoints mapOverlayPoints(const SemanticVoxelMap& map, const Pose3& T_map_velo,
                               double max_range) {
  OverlayPoints out;
  const Pose3 T_velo_map = T_map_velo.inverse();
  const Eigen::Vector3d origin = T_map_velo.translation();
  const double r2max = max_range * max_range;
  for (const Voxel& v : map.voxels()) {
    if (v.label == static_cast<uint8_t>(LidarClass::kUnlabeled)) continue;
    const Eigen::Vector3d c = map.center(v.key);
    if ((c - origin).squaredNorm() > r2max) continue;
    out.points_velo.push_back((T_velo_map * c).cast<float>());
    out.labels.push_back(v.label);
  }
  return out;
}

OverlayPoints scanOverlayPoints(const SemanticVoxelMap& map, const Pose3& T_map_velo,
                                const std::vector<Eigen::Vector3f>& points_velo) {
  OverlayPoints out;
  constexpr int32_t kLim = (1 << 20) - 1;  // packKey's range
  for (const Eigen::Vector3f& p : points_velo) {
    const VoxelCoord c = map.coordOf(T_map_velo * p.cast<double>());
    if (std::abs(c.x) > kLim || std::abs(c.y) > kLim || std::abs(c.z) > kLim) continue;
    const int64_t j = map.find(packKey(c));
    if (j < 0) continue;
    const uint8_t label = map.voxels()[j].label;
    if (label == static_cast<uint8_t>(LidarClass::kUnlabeled)) continue;
    out.points_velo.push_back(p);
    out.labels.push_back(label);
  }
  return out;
}

CameraOverlayReport writeCameraOverlays(const io::KittiRawDrive& drive, const SemanticVoxelMap& map,
                                        const std::vector<Pose3>& T_map_velo,
                                        const CameraOverlaySettings& settings, double max_range,
                                        const fs::path& dir) {
  CameraOverlayReport report;
  if (settings.every <= 0) return report;
  const Eigen::Matrix<double, 3, 4> P = drive.calib.veloToImage2();
  OverlayStyle style;
  style.max_range = max_range;
  style.alpha = settings.alpha;
  // Map voxels are drawn at their edge; a scan's points at two voxels so the rings read as lines.
  style.splat_size = settings.source == "scan" ? 2 * map.voxelSize() : map.voxelSize();
  style.min_splat_px = settings.source == "scan" ? 2 : 1;
  for (std::size_t i = 0; i < drive.frames.size() && i < T_map_velo.size();
       i += static_cast<std::size_t>(settings.every)) {
    const io::KittiRawFrame& f = drive.frames[i];
    if (f.image.empty()) {
      report.frames_without_image.push_back(f.name);
      continue;
    }
    const cv::Mat bgr = cv::imread(f.image.string(), cv::IMREAD_COLOR);
    if (bgr.empty()) throw IoError(f.image.string(), "cannot decode image for the overlay");
    const OverlayPoints pts =
        settings.source == "scan"
            ? scanOverlayPoints(map, T_map_velo[i], io::readVelodyneBin(f.velodyne).points)
            : mapOverlayPoints(map, T_map_velo[i], max_range);
    style.title = f.name + " (" + settings.source + ")";  // fits the 200 px key panel
    const CameraOverlay o = renderCameraOverlay(bgr, pts, P, style);
    io::writePngFrame(dir / (f.name + ".png"), o.image);
    report.files.push_back(f.name + ".png");
    report.points_drawn += o.drawn;
    for (LidarClass c : o.classes) ++report.pictures_with_class[static_cast<int>(c)];
  }
  if (!report.frames_without_image.empty())
    MAPFUSE_WARN("camera overlay: " << report.frames_without_image.size()
                                    << " selected frame(s) have no image_02 and got no picture "
                                       "(first: "
                                    << report.frames_without_image.front() << ")");
  return report;
}

}  // namespace mapfuse::lidar
