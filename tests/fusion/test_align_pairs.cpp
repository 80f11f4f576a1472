// align's pair selection (detail::selectPairs) on hand-made submaps: two groups of traversals
// whose georeferenced copies of one road are offset (as when their GPS biases differ). Choosing
// the best-overlapping partners ties each group to itself; spread partners join the groups.
#include <algorithm>
#include <catch2/catch.hpp>
#include <map>
#include <set>

#include "fusion/align_internal.hpp"

using namespace mapfuse;
using namespace mapfuse::fusion;

namespace {
constexpr int kLsms = 8;          // 0-3: group A, 4-7: group B
constexpr double kShiftX = 25.0;  // m, group B's copy of the road starts this much later ...
constexpr double kShiftY = 3.0;   // ... and lies this much to the side (within overlap_radius)

std::vector<detail::Submap> twoGroups() {
  std::vector<detail::Submap> maps;
  for (int l = 0; l < kLsms; ++l) {
    detail::Submap m;
    m.lsm = l;
    const bool b = l >= kLsms / 2;
    for (int k = 0; k <= 60; ++k) {
      m.coarse.points.emplace_back(k + (b ? kShiftX : 0.0), b ? kShiftY : 0.0, 0.0);
      m.coarse.labels.push_back(0);
    }
    m.lo = Eigen::Vector2d(b ? kShiftX : 0.0, b ? kShiftY : 0.0);
    m.hi = m.lo + Eigen::Vector2d(60.0, 0.0);
    maps.push_back(m);
  }
  return maps;
}

int crossPairs(const std::vector<detail::SubmapPair>& pairs,
               const std::vector<detail::Submap>& maps) {
  int n = 0;
  for (const auto& p : pairs) n += (maps[p.a].lsm < kLsms / 2) != (maps[p.b].lsm < kLsms / 2);
  return n;
}
}  // namespace

TEST_CASE("align pairs: best overlap ties like to like, spread partners join the groups") {
  const auto maps = twoGroups();
  AlignSettings s;
  s.max_partners = 2;
  s.spread_partners = false;  // best overlap
  const auto best = detail::selectPairs(maps, s);
  // Within a group the copies overlap fully (1.0), across groups by (60 - 25) / 60 = 0.58.
  CHECK(crossPairs(best, maps) == 0);
  s.spread_partners = true;
  const auto spread = detail::selectPairs(maps, s);
  CHECK(crossPairs(spread, maps) > 0);
  // Every submap still registers with max_partners distinct LSMs; no pair is listed twice.
  std::set<std::pair<int, int>> unique;
  for (const auto& p : spread) {
    CHECK(maps[p.a].lsm < maps[p.b].lsm);
    CHECK(p.overlap >= s.min_overlap);
    unique.insert({p.a, p.b});
  }
  CHECK(unique.size() == spread.size());
  CHECK(spread.size() <= std::size_t(kLsms * s.max_partners));
  for (int l = 0; l < kLsms; ++l) {
    std::set<int> partners;
    for (const auto& p : spread)
      if (maps[p.a].lsm == l || maps[p.b].lsm == l)
        partners.insert(maps[p.a].lsm == l ? maps[p.b].lsm : maps[p.a].lsm);
    CHECK(int(partners.size()) >= s.max_partners);
  }
}

TEST_CASE("align pairs: registrations per submap do not grow with the traversals") {
  // n traversals of one 300 m road, submaps of 60 m (shifted by a few metres per traversal):
  // each submap has candidates in every other traversal, but picks max_partners of them, so the
  // registrations a submap takes part in and the overlaps computed for it stay bounded (the
  // overlap of every candidate, as before, costs O(traversals) per submap).
  AlignSettings s;
  s.max_partners = 2;
  std::map<int, std::pair<double, int>> per;  // n -> (mean, max) pairs per submap
  std::map<int, double> overlaps_per;         // n -> overlap computations per submap
  for (int n : {8, 32, 128}) {
    std::vector<detail::Submap> maps;
    for (int l = 0; l < n; ++l)
      for (int k = 0; k < 5; ++k) {
        detail::Submap m;
        m.lsm = l;
        const double x0 = 60.0 * k + 0.37 * (l % 7), y0 = 0.1 * (l % 5);
        for (int i = 0; i <= 60; ++i)
          for (double y : {-3.5, 0.0, 3.5}) {
            m.coarse.points.emplace_back(x0 + i, y0 + y, 0.0);
            m.coarse.labels.push_back(0);
          }
        m.lo = Eigen::Vector2d(x0, y0 - 3.5);
        m.hi = Eigen::Vector2d(x0 + 60.0, y0 + 3.5);
        maps.push_back(m);
      }
    long overlaps = 0;
    const auto pairs = detail::selectPairs(maps, s, &overlaps);
    overlaps_per[n] = double(overlaps) / maps.size();
    std::vector<int> count(maps.size(), 0);
    for (const auto& p : pairs) ++count[p.a], ++count[p.b];
    per[n] = {double(2 * pairs.size()) / maps.size(),
              *std::max_element(count.begin(), count.end())};
    WARN(n << " traversals: " << pairs.size() << " pairs for " << maps.size()
           << " submaps, at most " << per[n].second << " per submap, " << overlaps_per[n]
           << " overlaps computed per submap");
  }
  for (const auto& [n, c] : per) {
    CHECK(c.first <= 2 * s.max_partners);       // each submap chooses max_partners
    CHECK(c.second <= 4 * s.max_partners + 2);  // and is chosen by a few others
  }
  CHECK(per[128].first <= 1.2 * per[8].first);
  // a chosen LSM's candidates (the submaps its box meets: up to 3) per partner
  CHECK(overlaps_per[128] <= 3.0 * s.max_partners);
  CHECK(overlaps_per[128] <= 1.2 * overlaps_per[8]);
}
