// Issue 21: solid / dashed typing of lane-line pieces from the marking profile in the BEV:
// a dashed line (3 m dash, 6 m gap: German urban "Leitlinie") gives its dash period, a solid
// line is solid, and a gap the camera did not see (a road user over it) is no evidence.
#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>

#include "mapfuse/vehicle/line_style.hpp"

using namespace mapfuse;
using namespace mapfuse::vehicle;

namespace {
constexpr double kPeriodTol = 0.2;  // m: 4 BEV rows of 0.05 m (run ends are pixel-quantised)

const BevGrid kGrid{30.0, 10.0, 0.05};  // 4-30 m forward, +-10 m: 520 x 400 px

int row(double forward) {
  return int(std::lround((kGrid.max_forward - forward) / 0.05));
}
int col(double left) {
  return int(std::lround((kGrid.half_width - left) / 0.05));
}

/// Paints a 0.15 m wide marking along left = `left` from forward f0 to f1 and returns the piece.
std::vector<Eigen::Vector2d> paint(cv::Mat& m, double left, double f0, double f1) {
  cv::rectangle(m, cv::Point(col(left) - 1, row(f1)), cv::Point(col(left) + 1, row(f0)), 255,
                cv::FILLED);
  std::vector<Eigen::Vector2d> piece;
  for (double f = f0; f <= f1 + 1e-9; f += 0.25) piece.emplace_back(f, left);
  return piece;
}
}  // namespace

TEST_CASE("line style: dashed with its period, solid, and unseen gaps untyped",
          "[vehicle][lane][style]") {
  cv::Mat markings(520, 400, CV_8UC1, cv::Scalar(0)), seen(520, 400, CV_8UC1, cv::Scalar(255));
  std::vector<std::vector<Eigen::Vector2d>> pieces;
  // Dashed at 1.75 m left: dashes 5-8, 14-17, 23-26 m (period 9 m).
  for (double f0 : {5.0, 14.0, 23.0}) pieces.push_back(paint(markings, 1.75, f0, f0 + 3.0));
  // Solid at -1.75 m, 6-28 m.
  pieces.push_back(paint(markings, -1.75, 6.0, 28.0));
  // A third line at 5.25 m: two dashes 8-11 and 17-20 m, the gap between hidden by a truck.
  pieces.push_back(paint(markings, 5.25, 8.0, 11.0));
  pieces.push_back(paint(markings, 5.25, 17.0, 20.0));
  cv::rectangle(seen, cv::Point(col(6.0), row(15.0)), cv::Point(col(4.5), row(12.0)), 0,
                cv::FILLED);

  const auto st = classifyLineStyles(pieces, markings, seen, kGrid, LineStyleSettings{});
  REQUIRE(st.size() == pieces.size());
  for (int i : {0, 1, 2}) {
    CHECK(st[i].style == LineStyle::kDashed);
    CHECK(st[i].period == Approx(9.0).margin(kPeriodTol));
    CHECK(st[i].line == st[0].line);
  }
  CHECK(st[3].style == LineStyle::kSolid);
  CHECK(st[3].run == Approx(22.0).margin(kPeriodTol));
  CHECK(st[3].line != st[0].line);
  CHECK(st[4].style == LineStyle::kNone);  // the only gap was not seen
  CHECK(st[5].style == LineStyle::kNone);
  CHECK(st[4].line == st[5].line);

  // Seen, the same gap makes the third line dashed; typing off leaves every piece untyped.
  seen.setTo(255);
  const auto seen_all = classifyLineStyles(pieces, markings, seen, kGrid, LineStyleSettings{});
  CHECK(seen_all[4].style == LineStyle::kDashed);
  LineStyleSettings off;
  off.enabled = false;
  for (const auto& s : classifyLineStyles(pieces, markings, seen, kGrid, off))
    CHECK(s.style == LineStyle::kNone);
}
