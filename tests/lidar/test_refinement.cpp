// K-nearest mean-distance filter: the sorted-key sweep against a brute-force reference (all
// pairs, exact K nearest) and against the cube-shell search over the hash index it replaced, on
// random sparse voxels with dense clusters and on edge cases.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <random>

#include "mapfuse/core/error.hpp"
#include "mapfuse/lidar/refinement.hpp"

using namespace mapfuse;
using lidar::KnnFilterSettings;
using lidar::SemanticVoxelMap;
using lidar::VoxelCoord;

namespace {

/// Exact reference: all pairs, the K nearest distances summed in ascending order, mean <= delta.
std::vector<uint8_t> bruteForce(const SemanticVoxelMap& map, const KnnFilterSettings& s) {
  const auto& vox = map.voxels();
  std::vector<uint8_t> keep(vox.size(), 0);
  std::vector<double> d;
  for (std::size_t i = 0; i < vox.size(); ++i) {
    const VoxelCoord a = lidar::unpackKey(vox[i].key);
    d.clear();
    for (std::size_t j = 0; j < vox.size(); ++j) {
      if (j == i) continue;
      const VoxelCoord b = lidar::unpackKey(vox[j].key);
      const int64_t dx = b.x - a.x, dy = b.y - a.y, dz = b.z - a.z;
      d.push_back(map.voxelSize() * std::sqrt(double(dx * dx + dy * dy + dz * dz)));
    }
    if (static_cast<int>(d.size()) < s.k) continue;
    std::partial_sort(d.begin(), d.begin() + s.k, d.end());
    double mean = 0;
    for (int j = 0; j < s.k; ++j) mean += d[j];
    keep[i] = mean / s.k <= s.max_mean_distance ? 1 : 0;
  }
  return keep;
}

/// The previous implementation: cube shells of 26, 98, ... hash lookups per voxel.
std::vector<uint8_t> previousShellSearch(const SemanticVoxelMap& map, const KnnFilterSettings& s) {
  const auto& vox = map.voxels();
  const double vs = map.voxelSize();
  const int K = s.k;
  const int max_shell = static_cast<int>(std::ceil(K * s.max_mean_distance / vs)) + 1;
  std::vector<uint8_t> keep(vox.size(), 0);
  for (std::size_t i = 0; i < vox.size(); ++i) {
    const VoxelCoord c = lidar::unpackKey(vox[i].key);
    std::vector<double> best;
    bool decided = false, ok = false;
    for (int r = 1; r <= max_shell && !decided; ++r) {
      for (int dx = -r; dx <= r; ++dx)
        for (int dy = -r; dy <= r; ++dy) {
          const bool edge = std::abs(dx) == r || std::abs(dy) == r;
          for (int dz = -r; dz <= r; dz += edge ? 1 : 2 * r)
            if (map.find(lidar::packKey({c.x + dx, c.y + dy, c.z + dz})) >= 0)
              best.push_back(vs * std::sqrt(double(dx * dx + dy * dy + dz * dz)));
        }
      std::sort(best.begin(), best.end());
      if (static_cast<int>(best.size()) > K) best.resize(K);
      const double beyond = (r + 1) * vs;
      double lower = 0;
      for (int j = 0; j < K; ++j)
        lower += j < static_cast<int>(best.size()) ? std::min(best[j], beyond) : beyond;
      lower /= K;
      if (lower > s.max_mean_distance) {
        decided = true;
      } else if (static_cast<int>(best.size()) == K && best[K - 1] <= beyond) {
        double mean = 0;
        for (int j = 0; j < K; ++j) mean += best[j];
        decided = true;
        ok = mean / K <= s.max_mean_distance;
      }
    }
    keep[i] = ok ? 1 : 0;
  }
  return keep;
}

/// Sparse random voxels in a box around the origin (negative coordinates included), dense
/// blobs, a plane with a hole-ridden edge and a few isolated voxels, in random insertion order.
SemanticVoxelMap randomMap(double voxel_size, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> box(-40, 40), off(-3, 3);
  std::vector<VoxelCoord> c;
  for (int i = 0; i < 1500; ++i) c.push_back({box(rng), box(rng), box(rng) / 4});
  for (int b = 0; b < 6; ++b) {  // dense blobs
    const VoxelCoord o{box(rng), box(rng), box(rng)};
    for (int i = 0; i < 150; ++i) c.push_back({o.x + off(rng), o.y + off(rng), o.z + off(rng)});
  }
  for (int x = -20; x < 10; ++x)  // a plane whose edge rows are half empty
    for (int y = -25; y < -5; ++y)
      if (y > -23 || rng() % 2) c.push_back({x, y, -17});
  for (int i = 0; i < 10; ++i) c.push_back({box(rng) * 10, box(rng) * 10, 300 + 10 * i});
  std::shuffle(c.begin(), c.end(), rng);
  SemanticVoxelMap map(voxel_size);
  for (const auto& v : c) map.findOrInsert(lidar::packKey(v));
  return map;
}

SemanticVoxelMap mapOf(const std::vector<VoxelCoord>& coords, double voxel_size) {
  SemanticVoxelMap map(voxel_size);
  for (const auto& v : coords) map.findOrInsert(lidar::packKey(v));
  return map;
}

KnnFilterSettings settings(int k, double delta) {
  KnnFilterSettings s;
  s.k = k;
  s.max_mean_distance = delta;
  return s;
}

}  // namespace

TEST_CASE("KNN filter matches brute force and the previous shell search on random voxels",
          "[lidar][refinement]") {
  struct Case {
    double voxel_size;
    int k;
    double delta;
  };
  const Case cases[] = {{0.05, 6, 0.20}, {0.05, 1, 0.05}, {0.05, 2, 0.06}, {0.05, 32, 0.25},
                        {0.2, 6, 0.3},   {0.1, 12, 0.2},  {0.05, 4, 0.1}};
  for (unsigned seed = 1; seed <= 2; ++seed)
    for (const Case& c : cases) {
      const SemanticVoxelMap map = randomMap(c.voxel_size, seed);
      const auto s = settings(c.k, c.delta);
      CAPTURE(seed, c.voxel_size, c.k, c.delta, map.size());
      const auto keep = lidar::knnMeanDistanceFilter(map, s);
      const auto kept = std::count(keep.begin(), keep.end(), 1);
      CHECK(kept > 0);
      CHECK(kept < static_cast<long>(keep.size()));
      CHECK(keep == bruteForce(map, s));
      CHECK(keep == previousShellSearch(map, s));
      CHECK(keep == lidar::knnMeanDistanceFilter(map, settings(c.k, c.delta), 3));
    }
}

TEST_CASE("KNN filter edge cases", "[lidar][refinement]") {
  SECTION("empty map") {
    CHECK(lidar::knnMeanDistanceFilter(SemanticVoxelMap(0.05), settings(6, 0.2)).empty());
  }
  SECTION("invalid settings") {
    const auto map = mapOf({{0, 0, 0}}, 0.05);
    CHECK_THROWS_AS(lidar::knnMeanDistanceFilter(map, settings(0, 0.2)), InputError);
    CHECK_THROWS_AS(lidar::knnMeanDistanceFilter(map, settings(33, 0.2)), InputError);
    CHECK_THROWS_AS(lidar::knnMeanDistanceFilter(map, settings(6, 0.0)), InputError);
  }
  SECTION("isolated voxels are dropped, fewer than K voxels drop all") {
    const auto map = mapOf({{0, 0, 0}, {100, 0, 0}, {-100, -7, 3}}, 0.05);
    CHECK(lidar::knnMeanDistanceFilter(map, settings(1, 0.2)) == std::vector<uint8_t>{0, 0, 0});
    const auto pair = mapOf({{-3, -3, -3}, {-3, -3, -2}}, 0.05);
    CHECK(lidar::knnMeanDistanceFilter(pair, settings(1, 0.05)) == std::vector<uint8_t>{1, 1});
    CHECK(lidar::knnMeanDistanceFilter(pair, settings(2, 1.0)) == std::vector<uint8_t>{0, 0});
  }
  SECTION("exactly K neighbours at the threshold are kept, just above it dropped") {
    // 0.25 m voxels: the 4 neighbours 2 voxels away are exactly 0.5 m from the centre, and
    // sqrt(8) * 0.25 or 1.0 m from one another.
    const std::vector<VoxelCoord> c = {
        {-5, -5, -5}, {-7, -5, -5}, {-3, -5, -5}, {-5, -7, -5}, {-5, -3, -5}};
    const auto map = mapOf(c, 0.25);
    CHECK(lidar::knnMeanDistanceFilter(map, settings(4, 0.5)) ==
          std::vector<uint8_t>{1, 0, 0, 0, 0});
    CHECK(lidar::knnMeanDistanceFilter(map, settings(4, std::nextafter(0.5, 0.0))) ==
          std::vector<uint8_t>{0, 0, 0, 0, 0});
    CHECK(lidar::knnMeanDistanceFilter(map, settings(4, 0.5)) ==
          previousShellSearch(map, settings(4, 0.5)));
  }
  SECTION("K = 32 in a dense cube, K = 1 on a line") {
    std::vector<VoxelCoord> cube, line;
    for (int x = -4; x < 4; ++x)
      for (int y = -4; y < 4; ++y)
        for (int z = -4; z < 4; ++z) cube.push_back({x, y, z});
    for (int x = -50; x < 50; x += 2) line.push_back({x, -1, -1});
    const auto cm = mapOf(cube, 0.05), lm = mapOf(line, 0.05);
    for (const auto& s : {settings(32, 0.1), settings(32, 0.08)}) {
      CHECK(lidar::knnMeanDistanceFilter(cm, s) == bruteForce(cm, s));
      CHECK(lidar::knnMeanDistanceFilter(cm, s) == previousShellSearch(cm, s));
    }
    CHECK(lidar::knnMeanDistanceFilter(lm, settings(1, 0.1)) ==
          std::vector<uint8_t>(line.size(), 1));
    CHECK(lidar::knnMeanDistanceFilter(lm, settings(1, 0.099)) ==
          std::vector<uint8_t>(line.size(), 0));
  }
  SECTION("voxels at the edge of the key range (where the hash search threw)") {
    constexpr int kMax = (1 << 20) - 1, kMin = -(1 << 20);
    std::vector<VoxelCoord> c;
    for (int i = 0; i < 4; ++i) {
      c.push_back({kMax - i, kMax, kMin});
      c.push_back({kMin + i, kMin, kMax});
    }
    const auto map = mapOf(c, 0.05);
    CHECK(lidar::knnMeanDistanceFilter(map, settings(2, 0.1)) == bruteForce(map, settings(2, 0.1)));
  }
}
