#include "mapfuse/io/map_png.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <set>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/picture_key.hpp"
#include "mapfuse/io/png_writer.hpp"

namespace mapfuse::io {
namespace {

const std::array<uint8_t, 3> kBackgroundRgb{190, 190, 190};
const std::array<uint8_t, 3> kYellowLineRgb{230, 160, 0};
const cv::Scalar kOutline(40, 40, 40);

cv::Scalar bgr(const std::array<uint8_t, 3>& rgb) {
  return cv::Scalar(rgb[2], rgb[1], rgb[0]);
}

/// The picture's frame: map (x, y) to pixels, north up.
struct Canvas {
  double x0 = 0, y1 = 0, res = 1;
  cv::Mat img;
  cv::Point px(const Eigen::Vector3d& p) const {
    return cv::Point(int(std::lround((p.x() - x0) / res)), int(std::lround((y1 - p.y()) / res)));
  }
};

Canvas makeCanvas(const VectorMap& map, const std::vector<std::vector<Eigen::Vector3d>>& background,
                  const MapPngOptions& opt) {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  auto grow = [&](const Eigen::Vector3d& p) {
    x0 = std::min(x0, p.x()), y0 = std::min(y0, p.y());
    x1 = std::max(x1, p.x()), y1 = std::max(y1, p.y());
  };
  for (const auto& inst : map.instances)
    for (const auto& p : inst.points) grow(p);
  for (const auto& line : background)
    for (const auto& p : line) grow(p);
  if (x0 > x1) x0 = y0 = 0, x1 = y1 = 1;
  x0 -= opt.margin, y0 -= opt.margin, x1 += opt.margin, y1 += opt.margin;
  Canvas c;
  c.res = std::max(opt.resolution, std::max(x1 - x0, y1 - y0) / std::max(opt.max_size, 16));
  const int w = std::max(16, int(std::ceil((x1 - x0) / c.res)));
  const int h = std::max(16, int(std::ceil((y1 - y0) / c.res)));
  c.x0 = x0, c.y1 = y1;
  c.img = cv::Mat(h, w, CV_8UC3, cv::Scalar(255, 255, 255));
  return c;
}

/// Paper colour of an instance: the class's colour on white (core/classes.hpp), yellow lane
/// lines in yellow.
std::array<uint8_t, 3> instanceRgb(const MapInstance& inst) {
  if (inst.cls == CrowdClass::kLaneLine && inst.attributes.color == LineColor::kYellow)
    return kYellowLineRgb;
  return crowdClassPaperColor(inst.cls);
}

void drawBackground(Canvas& c, const std::vector<std::vector<Eigen::Vector3d>>& background) {
  const cv::Scalar grey = bgr(kBackgroundRgb);
  for (const auto& line : background) {
    if (line.size() == 1) cv::circle(c.img, c.px(line[0]), 1, grey, cv::FILLED, cv::LINE_AA);
    for (std::size_t i = 1; i < line.size(); ++i)
      cv::line(c.img, c.px(line[i - 1]), c.px(line[i]), grey, 1, cv::LINE_AA);
  }
}

/// Lines and ground shapes: dashed lane lines 3 m on, 3 m off.
void drawGround(Canvas& c, const MapInstance& inst) {
  const cv::Scalar color = bgr(instanceRgb(inst));
  const auto& pts = inst.points;
  if (geometryKind(inst.cls) == GeometryKind::kPlanar) {
    std::vector<cv::Point> ring;
    for (const auto& p : pts) ring.push_back(c.px(p));
    cv::polylines(c.img, ring, true, color, 2, cv::LINE_AA);
    return;
  }
  const bool dashed = inst.attributes.style == LineStyle::kDashed;
  double run = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    run += (pts[i] - pts[i - 1]).norm();
    if (dashed && std::fmod(run, 6.0) > 3.0) continue;
    cv::line(c.img, c.px(pts[i - 1]), c.px(pts[i]), color, 2, cv::LINE_AA);
  }
}

/// Signs, lights and poles stand at nearly the same place (a sign on its pole): signs are drawn
/// as outlined 11 px squares and lights as outlined discs of radius 6 px, then poles on top as
/// dots of radius 3 px, so that each keeps pixels of its own colour (a pole dot inside its
/// sign's square).
void drawUpright(Canvas& c, const MapInstance& inst) {
  const cv::Scalar color = bgr(instanceRgb(inst));
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& p : inst.points) centre += p;
  const cv::Point at = c.px(centre / double(std::max<std::size_t>(1, inst.points.size())));
  if (inst.cls == CrowdClass::kPole) {
    cv::circle(c.img, at, 3, color, cv::FILLED, cv::LINE_AA);
  } else if (inst.cls == CrowdClass::kTrafficSign) {
    const cv::Rect box(at.x - 5, at.y - 5, 11, 11);
    cv::rectangle(c.img, box, color, cv::FILLED);
    cv::rectangle(c.img, box, kOutline, 1);
  } else {
    cv::circle(c.img, at, 6, color, cv::FILLED, cv::LINE_AA);
    cv::circle(c.img, at, 6, kOutline, 1, cv::LINE_AA);
  }
}

bool upright(CrowdClass k) {
  return k == CrowdClass::kPole || k == CrowdClass::kTrafficSign || k == CrowdClass::kTrafficLight;
}

PictureKey mapKey(const VectorMap& map, bool has_background, const MapPngOptions& opt, double res) {
  std::set<CrowdClass> present;
  bool yellow = false;
  for (const auto& inst : map.instances) {
    present.insert(inst.cls);
    yellow = yellow || instanceRgb(inst) == kYellowLineRgb;
  }
  PictureKey key;
  for (CrowdClass k : present) key.legend.push_back({crowdClassName(k), crowdClassPaperColor(k)});
  if (yellow) key.legend.push_back({"yellow lane_line", kYellowLineRgb});
  if (has_background) key.legend.push_back({opt.background_label, kBackgroundRgb, true});
  key.metres_per_pixel = res;
  key.title = opt.title;
  return key;
}

}  // namespace

void writeMapPng(const std::filesystem::path& path, const VectorMap& map,
                 const std::vector<std::vector<Eigen::Vector3d>>& background,
                 const MapPngOptions& opt) {
  Canvas c = makeCanvas(map, background, opt);
  drawBackground(c, background);
  for (const auto& inst : map.instances)
    if (!upright(inst.cls) && !inst.points.empty()) drawGround(c, inst);
  for (CrowdClass k : {CrowdClass::kTrafficSign, CrowdClass::kTrafficLight, CrowdClass::kPole})
    for (const auto& inst : map.instances)
      if (inst.cls == k && !inst.points.empty()) drawUpright(c, inst);
  writePng(path, withPictureKey(c.img, mapKey(map, !background.empty(), opt, c.res)));
}

}  // namespace mapfuse::io
