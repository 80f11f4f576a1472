#include "mapfuse/io/map_png.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/png_writer.hpp"

namespace mapfuse::io {

void writeMapPng(const std::filesystem::path& path, const VectorMap& map,
                 const std::vector<std::vector<Eigen::Vector3d>>& background,
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
  const double res =
      std::max(opt.resolution, std::max(x1 - x0, y1 - y0) / std::max(opt.max_size, 16));
  const int w = std::max(16, int(std::ceil((x1 - x0) / res)));
  const int h = std::max(16, int(std::ceil((y1 - y0) / res)));
  cv::Mat img(h, w, CV_8UC3, cv::Scalar(255, 255, 255));
  auto px = [&](const Eigen::Vector3d& p) {
    return cv::Point(int(std::lround((p.x() - x0) / res)), int(std::lround((y1 - p.y()) / res)));
  };
  const cv::Scalar grey(190, 190, 190);
  for (const auto& line : background) {
    if (line.size() == 1) cv::circle(img, px(line[0]), 1, grey, cv::FILLED, cv::LINE_AA);
    for (std::size_t i = 1; i < line.size(); ++i)
      cv::line(img, px(line[i - 1]), px(line[i]), grey, 1, cv::LINE_AA);
  }
  for (const auto& inst : map.instances) {
    const auto c = crowdClassColor(inst.cls);
    cv::Scalar color(c[2], c[1], c[0]);     // BGR
    if (inst.cls == CrowdClass::kLaneLine)  // white paint would vanish on the white canvas
      color = inst.attributes.color == LineColor::kYellow ? cv::Scalar(0, 160, 230)
                                                          : cv::Scalar(40, 40, 40);
    const auto& pts = inst.points;
    switch (geometryKind(inst.cls)) {
      case GeometryKind::kPoint:
        cv::circle(img, px(pts[0]), 4, color, cv::FILLED, cv::LINE_AA);
        break;
      case GeometryKind::kPlanar: {
        std::vector<cv::Point> ring;
        for (const auto& p : pts) ring.push_back(px(p));
        cv::polylines(img, ring, true, color, 2, cv::LINE_AA);
        break;
      }
      case GeometryKind::kLine: {
        const bool dashed = inst.attributes.style == LineStyle::kDashed;
        double run = 0.0;
        for (std::size_t i = 1; i < pts.size(); ++i) {
          run += (pts[i] - pts[i - 1]).norm();
          if (dashed && std::fmod(run, 6.0) > 3.0) continue;  // 3 m on, 3 m off
          cv::line(img, px(pts[i - 1]), px(pts[i]), color, 2, cv::LINE_AA);
        }
        break;
      }
    }
  }
  const int bar = int(std::lround(10.0 / res));  // 10 m scale bar
  cv::line(img, {10, h - 10}, {10 + bar, h - 10}, cv::Scalar(0, 0, 0), 2);
  cv::putText(img, "10 m", {10, h - 16}, cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(0, 0, 0), 1);
  writePng(path, img);
}

}  // namespace mapfuse::io
