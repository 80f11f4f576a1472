#include "mapfuse/eval/map_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <set>
#include <sstream>

#include "mapfuse/io/png_writer.hpp"

namespace mapfuse::eval {
namespace {

std::string num(double v, int decimals = 3) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string orDash(const ErrorStats& s, double v, int decimals = 3) {
  return s.count ? num(v, decimals) : "–";
}

cv::Scalar bgr(CrowdClass c) {
  const auto rgb = crowdClassPaperColor(c);  // the map colours are for dark backgrounds
  return cv::Scalar(rgb[2], rgb[1], rgb[0]);
}

struct Axes {  // plot area and value mapping
  cv::Mat img{480, 720, CV_8UC3, cv::Scalar(255, 255, 255)};
  cv::Rect area{70, 40, 610, 360};
  double ymax = 1.0;
  int y(double v) const { return area.y + area.height - int(v / ymax * area.height); }
  void frame(const std::string& title, const std::string& ylabel) {
    cv::rectangle(img, area, cv::Scalar(0, 0, 0), 1);
    for (int k = 0; k <= 4; ++k) {
      const double v = ymax * k / 4;
      cv::line(img, {area.x - 4, y(v)}, {area.x, y(v)}, cv::Scalar(0, 0, 0));
      cv::putText(img, num(v, 2), {5, y(v) + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.4,
                  cv::Scalar(0, 0, 0));
    }
    cv::putText(img, title, {area.x, 25}, cv::FONT_HERSHEY_SIMPLEX, 0.55, cv::Scalar(0, 0, 0));
    cv::putText(img, ylabel, {5, 25}, cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(60, 60, 60));
  }
};

}  // namespace

std::string markdownReport(const std::vector<MapReportEntry>& maps,
                           const std::vector<TrajectoryMetrics>& trajectories) {
  std::ostringstream md;
  md << "# Map evaluation\n\n";
  for (const auto& e : maps) {
    md << "## " << e.name;
    if (e.traversals > 0) md << " (" << e.traversals << " traversals)";
    md << "\n\n| Element | Relative precision (m) | Abs. error mean (m) | Abs. RMS (m) | "
          "Abs. 3σ (m) | Completeness | Redundancy | Truth | Map | Measure |\n"
          "|---|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& c : e.metrics.classes)
      md << "| " << crowdClassName(c.cls) << " | " << orDash(c.relative, c.relative.mean) << " | "
         << orDash(c.absolute, c.absolute.mean) << " | " << orDash(c.absolute, c.absolute.rms)
         << " | " << orDash(c.absolute, c.absolute.p3sigma) << " | " << num(c.completeness) << " | "
         << num(c.redundancy) << " | " << c.truth_count << " | " << c.map_count << " | "
         << (c.by_length ? "length" : "count") << " |\n";
    md << "\n";
  }
  if (maps.size() > 1) {
    std::set<CrowdClass> classes;
    for (const auto& e : maps)
      for (const auto& c : e.metrics.classes) classes.insert(c.cls);
    for (const bool completeness : {false, true}) {
      md << (completeness ? "## Completeness versus traversals"
                          : "## Relative precision (m) versus traversals")
         << "\n\n| Traversals |";
      for (auto c : classes) md << " " << crowdClassName(c) << " |";
      md << "\n|---|";
      for (std::size_t i = 0; i < classes.size(); ++i) md << "---|";
      md << "\n";
      for (const auto& e : maps) {
        md << "| " << (e.traversals > 0 ? std::to_string(e.traversals) : e.name) << " |";
        for (auto cls : classes) {
          std::string cell = " – |";
          for (const auto& c : e.metrics.classes)
            if (c.cls == cls)
              cell = " " +
                     (completeness ? (c.truth_count ? num(c.completeness) : std::string("–"))
                                   : orDash(c.relative, c.relative.mean)) +
                     " |";
          md << cell;
        }
        md << "\n";
      }
      md << "\n";
    }
  }
  if (!trajectories.empty()) {
    md << "## Trajectories\n\n| Drive | Keyframes | ATE mean (m) | ATE RMS (m) | ATE rot. RMS "
          "(deg) | RPE mean (m) | RPE rot. mean (deg) |\n|---|---|---|---|---|---|---|\n";
    for (const auto& t : trajectories)
      md << "| " << t.drive_id << " | " << t.matched << " | "
         << orDash(t.ate_translation, t.ate_translation.mean) << " | "
         << orDash(t.ate_translation, t.ate_translation.rms) << " | "
         << orDash(t.ate_rotation, t.ate_rotation.rms) << " | "
         << orDash(t.rpe_translation, t.rpe_translation.mean) << " | "
         << orDash(t.rpe_rotation, t.rpe_rotation.mean) << " |\n";
    md << "\n";
  }
  return md.str();
}

void writeErrorPerClassPng(const std::filesystem::path& path, const MapReportEntry& entry) {
  Axes ax;
  double vmax = 0.05;
  for (const auto& c : entry.metrics.classes)
    vmax = std::max(
        {vmax, c.relative.count ? c.relative.mean : 0.0, c.absolute.count ? c.absolute.mean : 0.0});
  ax.ymax = vmax * 1.15;
  ax.frame("Error per class: relative precision (filled), abs. mean (outline)", "m");
  const std::size_t n = std::max<std::size_t>(1, entry.metrics.classes.size());
  const int slot = ax.area.width / int(n);
  for (std::size_t i = 0; i < entry.metrics.classes.size(); ++i) {
    const auto& c = entry.metrics.classes[i];
    const int x = ax.area.x + int(i) * slot + slot / 6;
    const int w = slot / 3;
    if (c.relative.count) {
      cv::rectangle(ax.img, {x, ax.y(c.relative.mean)}, {x + w, ax.y(0)}, bgr(c.cls), cv::FILLED);
      cv::rectangle(ax.img, {x, ax.y(c.relative.mean)}, {x + w, ax.y(0)}, cv::Scalar(0, 0, 0), 1);
    }
    if (c.absolute.count)
      cv::rectangle(ax.img, {x + w, ax.y(c.absolute.mean)}, {x + 2 * w, ax.y(0)}, bgr(c.cls), 2);
    cv::putText(ax.img, crowdClassName(c.cls), {x - slot / 8, ax.area.y + ax.area.height + 18},
                cv::FONT_HERSHEY_SIMPLEX, 0.38, cv::Scalar(0, 0, 0));
  }
  io::writePng(path, ax.img);
}

void writeErrorVsTraversalsPng(const std::filesystem::path& path,
                               const std::vector<MapReportEntry>& maps) {
  // Fig. 9 of Song et al. 2023: relative precision (top) and completeness (bottom) per class
  std::vector<MapReportEntry> sorted = maps;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const auto& a, const auto& b) { return a.traversals < b.traversals; });
  double vmax = 0.05;
  int tmax = 1;
  for (const auto& e : sorted) {
    tmax = std::max(tmax, e.traversals);
    for (const auto& c : e.metrics.classes)
      if (c.relative.count) vmax = std::max(vmax, c.relative.mean);
  }
  Axes rel, comp;
  rel.ymax = vmax * 1.15;
  rel.frame("Relative precision vs traversals", "m");
  comp.ymax = 1.0;
  comp.frame("Completeness vs traversals", "share");
  auto xOf = [&](const Axes& ax, int t) {
    return ax.area.x + int(double(t) / tmax * (ax.area.width - 10));
  };
  for (Axes* ax : {&rel, &comp}) {
    for (int k = 0; k <= 5; ++k) {
      const int t = int(std::lround(tmax * k / 5.0));
      cv::putText(ax->img, std::to_string(t), {xOf(*ax, t) - 6, ax->area.y + ax->area.height + 18},
                  cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(0, 0, 0));
    }
    cv::putText(ax->img, "traversals", {ax->area.x + ax->area.width - 80, ax->img.rows - 30},
                cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(60, 60, 60));
  }
  int legend_y = rel.area.y + 15;
  for (int c = 0; c < kNumCrowdClasses; ++c) {
    std::vector<cv::Point> pr, pc;
    for (const auto& e : sorted)
      for (const auto& m : e.metrics.classes)
        if (int(m.cls) == c) {
          if (m.relative.count) pr.push_back({xOf(rel, e.traversals), rel.y(m.relative.mean)});
          if (m.truth_count > 0) pc.push_back({xOf(comp, e.traversals), comp.y(m.completeness)});
        }
    if (pr.empty() && pc.empty()) continue;
    const cv::Scalar col = bgr(CrowdClass(c));
    for (auto [ax, pts] : {std::pair{&rel, &pr}, std::pair{&comp, &pc}})
      for (std::size_t i = 0; i < pts->size(); ++i) {
        cv::circle(ax->img, (*pts)[i], 3, col, cv::FILLED);
        if (i) cv::line(ax->img, (*pts)[i - 1], (*pts)[i], col, 2, cv::LINE_AA);
      }
    cv::putText(rel.img, crowdClassName(CrowdClass(c)),
                {rel.area.x + rel.area.width - 120, legend_y}, cv::FONT_HERSHEY_SIMPLEX, 0.4, col);
    legend_y += 15;
  }
  cv::Mat both;
  cv::vconcat(rel.img, comp.img, both);
  io::writePng(path, both);
}

}  // namespace mapfuse::eval
