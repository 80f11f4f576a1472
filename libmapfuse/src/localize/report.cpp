#include "mapfuse/localize/report.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "mapfuse/io/json_geometry.hpp"
#include "mapfuse/io/png_writer.hpp"

namespace mapfuse::localize {
namespace {

std::string num(double v, int decimals) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(decimals) << v;
  return s.str();
}

const cv::Scalar kBlack(0, 0, 0), kGrey(120, 120, 120), kRed(40, 40, 220);
const cv::Scalar kBlue(200, 90, 30), kOrange(30, 140, 240), kGreen(60, 160, 60);

/// One panel: x = distance (m), y = value in [0, ymax].
struct Panel {
  cv::Rect area;
  double xmax = 1.0, ymax = 1.0;
  int x(double v) const { return area.x + int(v / xmax * area.width); }
  int y(double v) const {
    return area.y + area.height - int(std::min(v, ymax) / ymax * area.height);
  }
  void frame(cv::Mat& img, const std::string& ylabel) const {
    cv::rectangle(img, area, kBlack, 1);
    for (int k = 0; k <= 4; ++k) {
      const double v = ymax * k / 4;
      cv::line(img, {area.x - 4, y(v)}, {area.x, y(v)}, kBlack);
      cv::putText(img, num(v, 2), {area.x - 48, y(v) + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.38, kBlack);
      const double d = xmax * k / 4;
      cv::line(img, {x(d), area.y + area.height}, {x(d), area.y + area.height + 4}, kBlack);
      cv::putText(img, num(d, 0), {x(d) - 12, area.y + area.height + 17}, cv::FONT_HERSHEY_SIMPLEX,
                  0.38, kBlack);
    }
    cv::putText(img, ylabel, {area.x + 4, area.y - 6}, cv::FONT_HERSHEY_SIMPLEX, 0.42, kGrey);
  }
  void curve(cv::Mat& img, const LocalizeErrors& e, double (*value)(const KeyframeError&),
             const cv::Scalar& colour) const {
    const cv::Point* prev = nullptr;
    cv::Point last;
    for (const auto& k : e.keyframes) {
      if (k.lost) {
        prev = nullptr;
        continue;
      }
      const cv::Point p(x(k.distance), y(std::abs(value(k))));
      if (prev) cv::line(img, *prev, p, colour, 2, cv::LINE_AA);
      last = p;
      prev = &last;
    }
  }
};

void legend(cv::Mat& img, cv::Point at, const std::string& text, const cv::Scalar& colour) {
  cv::line(img, at, {at.x + 24, at.y}, colour, 2, cv::LINE_AA);
  cv::putText(img, text, {at.x + 30, at.y + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.4, kBlack);
}

}  // namespace

nlohmann::json trajectoryJson(const LocalizeResult& result, const std::string& drive_id,
                              const std::string& vehicle_id, const geo::GeoOrigin& origin) {
  nlohmann::json j;
  j["format"] = "mapfuse.trajectory";
  j["version"] = 1;
  j["drive_id"] = drive_id;
  j["vehicle_id"] = vehicle_id;
  j["frame"] = "enu";
  j["origin"] = io::originToJson(origin);
  j["source"] = "localize";
  nlohmann::json poses = nlohmann::json::array();
  for (const auto& k : result.keyframes)
    poses.push_back({{"id", k.id},
                     {"stamp", k.stamp},
                     {"pose", io::poseToJson(k.T_enu_body)},
                     {"status", statusName(k.status)},
                     {"matches", k.matches}});
  j["poses"] = poses;
  return j;
}

std::string errorsCsv(const LocalizeErrors& errors) {
  std::ostringstream s;
  s << "id,distance_m,status,lateral_m,longitudinal_m,heading_deg,prior_lateral_m,"
       "prior_longitudinal_m,prior_heading_deg\n";
  for (const auto& k : errors.keyframes)
    s << k.id << ',' << num(k.distance, 2) << ',' << (k.lost ? "lost" : "ok") << ','
      << num(k.localized.lateral, 4) << ',' << num(k.localized.longitudinal, 4) << ','
      << num(k.localized.heading_deg, 4) << ',' << num(k.prior.lateral, 4) << ','
      << num(k.prior.longitudinal, 4) << ',' << num(k.prior.heading_deg, 4) << '\n';
  return s.str();
}

void writeErrorPlot(const std::filesystem::path& path, const LocalizeErrors& errors,
                    const std::string& title) {
  cv::Mat img(560, 760, CV_8UC3, cv::Scalar(255, 255, 255));
  Panel top{cv::Rect(70, 50, 660, 250)}, bottom{cv::Rect(70, 340, 660, 160)};
  double xmax = 1.0, pmax = 0.05, hmax = 0.05;
  for (const auto& k : errors.keyframes) {
    xmax = std::max(xmax, k.distance);
    if (k.lost) continue;
    pmax = std::max({pmax, std::abs(k.localized.lateral), std::abs(k.localized.longitudinal)});
    hmax = std::max(hmax, std::abs(k.localized.heading_deg));
  }
  top.xmax = bottom.xmax = xmax;
  top.ymax = pmax * 1.1;
  bottom.ymax = hmax * 1.1;
  cv::putText(img, title, {70, 22}, cv::FONT_HERSHEY_SIMPLEX, 0.55, kBlack);
  top.frame(img, "|error| m");
  bottom.frame(img, "|heading error| deg");
  top.curve(
      img, errors, [](const KeyframeError& k) { return k.localized.lateral; }, kBlue);
  top.curve(
      img, errors, [](const KeyframeError& k) { return k.localized.longitudinal; }, kOrange);
  bottom.curve(
      img, errors, [](const KeyframeError& k) { return k.localized.heading_deg; }, kGreen);
  for (const auto& k : errors.keyframes)  // lost keyframes: red ticks under both panels
    if (k.lost)
      for (const Panel* p : {&top, &bottom})
        cv::line(img, {p->x(k.distance), p->area.y + p->area.height - 8},
                 {p->x(k.distance), p->area.y + p->area.height}, kRed, 2);
  legend(img, {480, 40}, "lateral", kBlue);
  legend(img, {580, 40}, "longitudinal", kOrange);
  legend(img, {480, 330}, "heading", kGreen);
  legend(img, {580, 330}, "lost keyframe", kRed);
  cv::putText(img, "distance travelled (m)", {320, 540}, cv::FONT_HERSHEY_SIMPLEX, 0.45, kBlack);
  io::writePng(path, img);
}

nlohmann::json toJson(const MeanAbsError& m) {
  return {{"keyframes", m.count},
          {"mean_abs_lateral_m", m.lateral},
          {"mean_abs_longitudinal_m", m.longitudinal},
          {"mean_abs_heading_deg", m.heading_deg}};
}

nlohmann::json toJson(const LocalizeResult& r) {
  const double n = static_cast<double>(r.keyframes.size());
  return {{"keyframes", r.keyframes.size()},
          {"lost", r.lost},
          {"lost_share", r.lostShare()},
          {"acquisitions", r.acquisitions},
          {"solver_iterations", r.solver_iterations},
          {"seconds", r.seconds},
          {"localisations_per_second", r.seconds > 0 ? n / r.seconds : 0.0}};
}

}  // namespace mapfuse::localize
