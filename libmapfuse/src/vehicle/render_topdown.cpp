#include "mapfuse/vehicle/render_topdown.hpp"

#include <opencv2/imgproc.hpp>
#include <set>

namespace mapfuse::vehicle {
namespace {

const std::array<uint8_t, 3> kTrajectoryRgb{0, 160, 255};
const std::array<uint8_t, 3> kKeyframeRgb{0, 255, 255};

cv::Scalar bgr(const std::array<uint8_t, 3>& rgb) {
  return cv::Scalar(rgb[2], rgb[1], rgb[0]);
}

Eigen::Vector3d bevToCam(const GroundPlane& g, double f, double l) {
  const Eigen::Vector3d n = g.normal_cam.normalized();
  const Eigen::Vector3d fwd = (Eigen::Vector3d::UnitZ() - n.z() * n).normalized();
  return -g.height * n + f * fwd + l * n.cross(fwd);
}

}  // namespace

cv::Mat renderTopDown(const Lsm& lsm, const std::vector<Pose3>& trajectory, double res,
                      const std::vector<BevTile>& tiles) {
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  auto grow = [&](const Eigen::Vector3d& p) {
    lo = lo.cwiseMin(p.head<2>());
    hi = hi.cwiseMax(p.head<2>());
  };
  for (const auto& T : trajectory) grow(T.translation());
  for (const auto& e : lsm.elements)
    for (const auto& p : lsm.pointsInFrame(e)) grow(p);
  for (const auto& t : tiles)
    for (double f : {t.min_x, t.max_x})
      for (double l : {-t.half_width, t.half_width}) grow(t.T_odom_cam * bevToCam(t.plane, f, l));
  if (lo.x() > hi.x()) lo = hi = Eigen::Vector2d::Zero();
  lo -= Eigen::Vector2d(5, 5);
  hi += Eigen::Vector2d(5, 5);
  const int W = std::min(8000, int(std::ceil((hi.x() - lo.x()) / res)));
  const int H = std::min(8000, int(std::ceil((hi.y() - lo.y()) / res)));
  cv::Mat img(H, W, CV_8UC3, cv::Scalar(40, 40, 40));
  auto toPx = [&](const Eigen::Vector3d& p) {
    return cv::Point(int(std::round((p.x() - lo.x()) / res)),
                     int(std::round((hi.y() - p.y()) / res)));
  };
  // Background mosaic: every picture pixel takes the tile that saw it from closest.
  cv::Mat best_f(H, W, CV_32F, cv::Scalar(1e9f));
  for (const auto& t : tiles) {
    const Pose3 T_cam_odom = t.T_odom_cam.inverse();
    const Eigen::Vector3d n = t.plane.normal_cam.normalized();
    const Eigen::Vector3d fwd = (Eigen::Vector3d::UnitZ() - n.z() * n).normalized();
    const Eigen::Vector3d left = n.cross(fwd), foot = -t.plane.height * n;
    // Odom z of the tile's ground under the camera, used for the whole tile.
    const double z = (t.T_odom_cam * foot).z();
    for (int r = 0; r < H; ++r)
      for (int c = 0; c < W; ++c) {
        const Eigen::Vector3d p_odom(lo.x() + c * res, hi.y() - r * res, z);
        const Eigen::Vector3d q = T_cam_odom * p_odom - foot;
        const double f = q.dot(fwd), l = q.dot(left);
        if (f < t.min_x || f >= t.max_x || std::abs(l) >= t.half_width) continue;
        if (f >= best_f.at<float>(r, c)) continue;
        const int br = int((t.max_x - f) / t.resolution),
                  bc = int((t.half_width - l) / t.resolution);
        if (br < 0 || bc < 0 || br >= t.gray.rows || bc >= t.gray.cols) continue;
        const uint8_t v = t.gray.at<uint8_t>(br, bc);
        if (!v) continue;
        img.at<cv::Vec3b>(r, c) = cv::Vec3b(v, v, v);
        best_f.at<float>(r, c) = float(f);
      }
  }
  for (std::size_t i = 1; i < trajectory.size(); ++i)
    cv::line(img, toPx(trajectory[i - 1].translation()), toPx(trajectory[i].translation()),
             bgr(kTrajectoryRgb), 2);
  for (const auto& k : lsm.keyframes)
    cv::circle(img, toPx(k.T_frame_body.translation()), 4, bgr(kKeyframeRgb), -1);
  for (const auto& e : lsm.elements) {
    const auto rgb = crowdClassColor(e.cls);
    const cv::Scalar col(rgb[2], rgb[1], rgb[0]);
    const auto pts = lsm.pointsInFrame(e);
    std::vector<cv::Point> px;
    for (const auto& p : pts) px.push_back(toPx(p));
    const GeometryKind kind = geometryKind(e.cls);
    if (kind == GeometryKind::kPoint)
      cv::circle(img, px[0], 5, col, -1);
    else if (kind == GeometryKind::kPlanar)
      cv::polylines(img, px, true, col, 2);
    else
      cv::polylines(img, px, false, col, 2);
  }
  return img;
}

io::PictureKey topDownKey(const Lsm& lsm, double resolution) {
  std::set<CrowdClass> present;
  for (const auto& e : lsm.elements) present.insert(e.cls);
  io::PictureKey key;
  key.legend = io::crowdLegend(present);
  key.legend.push_back({"trajectory", kTrajectoryRgb, true});
  key.legend.push_back({"keyframe", kKeyframeRgb, false});
  key.metres_per_pixel = resolution;
  key.title = lsm.drive_id;
  // An LSM in its odometry frame (before georef) does not know where north is.
  key.north_up = lsm.frame == LsmFrame::kEnu;
  key.up_note = "no north arrow: odometry frame, +y up (north unknown)";
  return key;
}

}  // namespace mapfuse::vehicle
