#include "mapfuse/vehicle/line_style.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>

namespace mapfuse::vehicle {
namespace {

/// left = a + b * forward, least squares over the points.
struct LineFit {
  double a = 0.0, b = 0.0;
  bool ok = false;
  double at(double forward) const { return a + b * forward; }
};

LineFit fitLine(const std::vector<const Eigen::Vector2d*>& pts) {
  LineFit f;
  if (pts.size() < 2) return f;
  double sf = 0, sl = 0, sff = 0, sfl = 0;
  for (const auto* p : pts) {
    sf += p->x(), sl += p->y(), sff += p->x() * p->x(), sfl += p->x() * p->y();
  }
  const double n = double(pts.size()), det = n * sff - sf * sf;
  if (det < 1e-9) return f;  // all at one forward distance: across the road, not a lane line
  f.b = (n * sfl - sf * sl) / det;
  f.a = (sl - f.b * sf) / n;
  f.ok = true;
  return f;
}

double meanOffset(const std::vector<Eigen::Vector2d>& pts, const LineFit& f) {
  double sum = 0;
  for (const auto& p : pts) sum += std::abs(p.y() - f.at(p.x())) / std::sqrt(1 + f.b * f.b);
  return pts.empty() ? 1e9 : sum / double(pts.size());
}

int findRoot(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

/// A stretch of the profile: rows [begin, end), marked or not, all rows seen or not.
struct Stretch {
  int begin, end;
  bool marked, all_seen;
};

}  // namespace

std::vector<PieceStyle> classifyLineStyles(const std::vector<std::vector<Eigen::Vector2d>>& pieces,
                                           const cv::Mat& markings, const cv::Mat& seen,
                                           const BevGrid& g, const LineStyleSettings& s) {
  std::vector<PieceStyle> out(pieces.size());
  if (!s.enabled || pieces.empty()) return out;
  CV_Assert(markings.type() == CV_8UC1 && seen.type() == CV_8UC1 && markings.size() == seen.size());
  // 1. Chain the pieces lying on one straight line (union of pieces within chain_lateral of
  // each other's fit).
  const std::size_t n = pieces.size();
  std::vector<LineFit> fits(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<const Eigen::Vector2d*> pts;
    for (const auto& p : pieces[i]) pts.push_back(&p);
    fits[i] = fitLine(pts);
  }
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      if (!fits[i].ok || !fits[j].ok) continue;
      // The longer piece's fit judges the shorter one (its direction is better known).
      const bool i_longer = pieces[i].size() >= pieces[j].size();
      const double off = i_longer ? meanOffset(pieces[j], fits[i]) : meanOffset(pieces[i], fits[j]);
      if (off < s.chain_lateral) parent[findRoot(parent, int(i))] = findRoot(parent, int(j));
    }
  std::vector<int> line_of(n), roots;
  for (std::size_t i = 0; i < n; ++i) {
    const int r = findRoot(parent, int(i));
    auto it = std::find(roots.begin(), roots.end(), r);
    line_of[i] = int(it - roots.begin());
    if (it == roots.end()) roots.push_back(r);
  }

  // 2. Per line: the marking profile along the fitted line, one sample per BEV row.
  const int rows = markings.rows, cols = markings.cols;
  const int probe = std::max(1, int(std::lround(s.probe_half_width / g.resolution)));
  const int max_hole = std::max(1, int(std::lround(0.5 / g.resolution)));  // bridged: 0.5 m
  auto length = [&](int r0, int r1) { return (r1 - r0) * g.resolution; };
  for (int line = 0; line < int(roots.size()); ++line) {
    std::vector<const Eigen::Vector2d*> pts;
    for (std::size_t i = 0; i < n; ++i)
      if (line_of[i] == line)
        for (const auto& p : pieces[i]) pts.push_back(&p);
    const LineFit fit = fitLine(pts);
    if (!fit.ok) continue;
    std::vector<uint8_t> marked(rows, 0), visible(rows, 0);
    for (int r = 0; r < rows; ++r) {
      const double forward = g.max_forward - r * g.resolution;
      const int c = int(std::lround((g.half_width - fit.at(forward)) / g.resolution));
      if (c < 0 || c >= cols) continue;
      visible[r] = seen.at<uint8_t>(r, c) > 0;
      const uint8_t* m = markings.ptr<uint8_t>(r);
      for (int k = std::max(0, c - probe); k <= std::min(cols - 1, c + probe); ++k)
        marked[r] = marked[r] || m[k] > 0;
    }
    // Short holes inside a marking (wear, a thin shadow) are not gaps.
    std::vector<Stretch> st;
    for (int r = 0; r < rows;) {
      int e = r;
      while (e < rows && marked[e] == marked[r]) ++e;
      bool all_seen = true;
      for (int k = r; k < e; ++k) all_seen = all_seen && visible[k];
      st.push_back({r, e, marked[r] != 0, all_seen});
      r = e;
    }
    for (std::size_t k = 1; k + 1 < st.size(); ++k)
      if (!st[k].marked && st[k - 1].marked && st[k + 1].marked &&
          st[k].end - st[k].begin <= max_hole) {
        st[k - 1].end = st[k + 1].end;
        st.erase(st.begin() + long(k), st.begin() + long(k) + 2);
        --k;
      }
    // Evidence per marked run: a seen gap between two dashes next to it, or its own length.
    auto isGap = [&](std::size_t k) {
      return k > 0 && k + 1 < st.size() && !st[k].marked && st[k].all_seen &&
             length(st[k].begin, st[k].end) >= s.min_gap;
    };
    std::vector<LineStyle> run_style(st.size(), LineStyle::kNone);
    double period_sum = 0;
    int periods = 0;
    for (std::size_t k = 0; k < st.size(); ++k) {
      if (!st[k].marked) continue;
      const double len = length(st[k].begin, st[k].end);
      if (len >= s.min_solid)
        run_style[k] = LineStyle::kSolid;
      else if (len <= s.max_dash && ((k > 0 && isGap(k - 1)) || isGap(k + 1)))
        run_style[k] = LineStyle::kDashed;
      if (isGap(k + 1) && len <= s.max_dash && k + 2 < st.size() &&
          length(st[k + 2].begin, st[k + 2].end) <= s.max_dash) {
        period_sum += len + length(st[k + 1].begin, st[k + 1].end);
        ++periods;
      }
    }
    // 3. Each piece takes the style of the run holding most of its points.
    for (std::size_t i = 0; i < n; ++i) {
      if (line_of[i] != line) continue;
      std::vector<int> votes(st.size(), 0);
      for (const auto& p : pieces[i]) {
        const int r = int(std::lround((g.max_forward - p.x()) / g.resolution));
        for (std::size_t k = 0; k < st.size(); ++k)
          if (st[k].marked && r >= st[k].begin - 1 && r <= st[k].end) ++votes[k];
      }
      const auto best = std::max_element(votes.begin(), votes.end()) - votes.begin();
      out[i].line = line;
      if (votes[best] == 0) continue;
      out[i].style = run_style[best];
      out[i].run = length(st[best].begin, st[best].end);
      out[i].period = out[i].style == LineStyle::kDashed && periods ? period_sum / periods : 0.0;
    }
  }
  return out;
}

}  // namespace mapfuse::vehicle
