// align's pair selection (detail::selectPairs) on hand-made submaps: two groups of traversals
// whose georeferenced copies of one road are offset (as when their GPS biases differ). Choosing
// the best-overlapping partners ties each group to itself; spread partners join the groups.
#include <catch2/catch.hpp>
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
    m.cloud = m.coarse;
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
