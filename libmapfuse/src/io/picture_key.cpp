#include "mapfuse/io/picture_key.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

namespace mapfuse::io {
namespace {

constexpr int kPanelWidth = 200;  // px
constexpr int kMargin = 10;       // px
constexpr int kRow = 18;          // px per legend line
constexpr int kMaxBar = 170;      // px, longest scale bar
constexpr double kFont = 0.42;
const cv::Scalar kInk(0, 0, 0);
const cv::Scalar kPaper(255, 255, 255);

cv::Scalar bgrOf(const std::array<uint8_t, 3>& rgb) {
  return cv::Scalar(rgb[2], rgb[1], rgb[0]);
}

std::string metres(double m) {
  char buf[32];
  if (m >= 1000.0)
    std::snprintf(buf, sizeof buf, "%g km", m / 1000.0);
  else if (m >= 1.0)
    std::snprintf(buf, sizeof buf, "%g m", m);
  else
    std::snprintf(buf, sizeof buf, "%g cm", m * 100.0);
  return buf;
}

int textWidth(const std::string& text, double font_scale) {
  int baseline = 0;
  return cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, font_scale, 1, &baseline).width;
}

// Draws `lines` from row y (top) in the panel; returns the row below them.
int drawLines(cv::Mat& out, const std::vector<std::string>& lines, int x0, int y, double font) {
  for (const auto& l : lines) {
    cv::putText(out, l, {x0, y + 12}, cv::FONT_HERSHEY_SIMPLEX, font, kInk, 1, cv::LINE_AA);
    y += kRow;
  }
  return y;
}

constexpr double kTitleFont = 0.48;
constexpr int kTextWidth = kPanelWidth - 2 * kMargin;  // px

}  // namespace

std::vector<std::string> wrapText(const std::string& text, double font_scale, int max_width) {
  std::vector<std::string> lines;
  std::string line;
  std::size_t i = 0;
  while (i < text.size()) {
    // The next piece: up to and including a break character, or to the end.
    std::size_t j = i;
    while (j < text.size() && text[j] != ' ' && text[j] != '_' && text[j] != '/') ++j;
    std::string piece = text.substr(i, std::min(text.size(), j + 1) - i);
    i = std::min(text.size(), j + 1);
    if (line.empty() && piece == " ") continue;
    if (textWidth(line + piece, font_scale) <= max_width) {
      line += piece;
      continue;
    }
    if (!line.empty()) lines.push_back(line);
    line.clear();
    if (piece == " ") continue;
    for (char c : piece) {  // a piece wider than a line is cut anywhere
      if (!line.empty() && textWidth(line + c, font_scale) > max_width) {
        lines.push_back(line);
        line.clear();
      }
      line += c;
    }
  }
  while (!line.empty() && line.back() == ' ') line.pop_back();
  if (!line.empty()) lines.push_back(line);
  return lines;
}

std::vector<LegendEntry> crowdLegend(const std::set<CrowdClass>& present) {
  std::vector<LegendEntry> out;
  for (CrowdClass c : present) out.push_back({crowdClassName(c), crowdClassColor(c), false});
  return out;
}

std::vector<LegendEntry> lidarLegend(const std::set<LidarClass>& present) {
  std::vector<LegendEntry> out;
  for (LidarClass c : present) out.push_back({lidarClassName(c), lidarClassColor(c), false});
  return out;
}

int drawPath(cv::Mat& bgr, const std::vector<Eigen::Vector3d>& path,
             const Eigen::Vector2d& top_left, double metres_per_pixel,
             const std::array<uint8_t, 3>& rgb) {
  std::vector<cv::Point> px;
  int inside = 0;
  for (const auto& p : path) {
    px.emplace_back(static_cast<int>(std::floor((p.x() - top_left.x()) / metres_per_pixel)),
                    static_cast<int>(std::floor((top_left.y() - p.y()) / metres_per_pixel)));
    inside +=
        px.back().x >= 0 && px.back().y >= 0 && px.back().x < bgr.cols && px.back().y < bgr.rows;
  }
  if (px.size() >= 2) cv::polylines(bgr, px, false, bgrOf(rgb), 2, cv::LINE_AA);
  return inside;
}

double scaleBarLength(double metres_per_pixel, int max_pixels) {
  const double max_m = metres_per_pixel * std::max(1, max_pixels);
  double best = 0.0;
  for (int k = -3; k <= 6; ++k)
    for (double f : {1.0, 2.0, 5.0}) {
      const double L = f * std::pow(10.0, k);
      if (L <= max_m * (1 + 1e-12) && L >= metres_per_pixel) best = std::max(best, L);
    }
  return best;
}

cv::Mat withPictureKey(const cv::Mat& bgr, const PictureKey& key) {
  const auto title = wrapText(key.title, kTitleFont, kTextWidth);
  const auto note =
      key.north_up ? std::vector<std::string>{} : wrapText(key.up_note, kFont, kTextWidth);
  const int rows_needed = 2 * kMargin + (title.empty() ? 0 : kRow * int(title.size()) + 4) +
                          kRow * static_cast<int>(key.legend.size()) +
                          (key.metres_per_pixel > 0 ? 50 : 0) +
                          (key.north_up ? 60 : 8 + kRow * int(note.size()));
  const int H = std::max(bgr.rows, rows_needed);
  cv::Mat out(H, bgr.cols + kPanelWidth, CV_8UC3, kPaper);
  bgr.copyTo(out(cv::Rect(0, 0, bgr.cols, bgr.rows)));
  const int x0 = bgr.cols + kMargin;
  cv::line(out, {bgr.cols, 0}, {bgr.cols, H - 1}, kInk, 1);
  int y = kMargin;
  if (!title.empty()) y = drawLines(out, title, x0, y, kTitleFont) + 4;
  // Legend: a swatch with a black border (white classes stay visible) and the label.
  for (const auto& e : key.legend) {
    if (e.line) {
      cv::line(out, {x0, y + 7}, {x0 + 14, y + 7}, bgrOf(e.rgb), 3);
    } else {
      cv::rectangle(out, cv::Rect(x0, y, 14, 14), bgrOf(e.rgb), cv::FILLED);
      cv::rectangle(out, cv::Rect(x0, y, 14, 14), kInk, 1);
    }
    // a label too long for the panel is shortened (the legend stays one row per entry)
    std::string label = e.label;
    while (label.size() > 1 && textWidth(label, kFont) > kTextWidth - 22) label.pop_back();
    cv::putText(out, label, {x0 + 22, y + 12}, cv::FONT_HERSHEY_SIMPLEX, kFont, kInk, 1,
                cv::LINE_AA);
    y += kRow;
  }
  // Scale bar: alternating black and white halves with end ticks, its length above.
  if (key.metres_per_pixel > 0) {
    y += 12;
    const double L = scaleBarLength(key.metres_per_pixel, kMaxBar);
    const int px = std::max(1, static_cast<int>(std::lround(L / key.metres_per_pixel)));
    cv::putText(out, metres(L), {x0, y + 10}, cv::FONT_HERSHEY_SIMPLEX, kFont, kInk, 1,
                cv::LINE_AA);
    const int yb = y + 18;
    cv::rectangle(out, cv::Rect(x0, yb, px / 2, 6), kInk, cv::FILLED);
    cv::rectangle(out, cv::Rect(x0, yb, px, 6), kInk, 1);
    cv::line(out, {x0, yb - 4}, {x0, yb + 9}, kInk, 1);
    cv::line(out, {x0 + px, yb - 4}, {x0 + px, yb + 9}, kInk, 1);
    y += 38;
  }
  // North arrow: an arrow pointing up with an N above it.
  if (key.north_up) {
    y += 8;
    const int cx = x0 + 12;
    cv::putText(out, "N", {cx - 6, y + 10}, cv::FONT_HERSHEY_SIMPLEX, 0.5, kInk, 1, cv::LINE_AA);
    std::vector<cv::Point> head = {{cx, y + 16}, {cx - 7, y + 30}, {cx + 7, y + 30}};
    cv::fillConvexPoly(out, head, kInk, cv::LINE_AA);
    cv::line(out, {cx, y + 30}, {cx, y + 50}, kInk, 2);
  } else {
    drawLines(out, note, x0, y + 8, kFont);
  }
  return out;
}

}  // namespace mapfuse::io
