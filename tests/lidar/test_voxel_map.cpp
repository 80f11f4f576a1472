// Semantic voxel map storage: paged voxel array (stable indices across pages, filter keeps the
// order, memory accounting within the 64 B/voxel target after shrinkToFit).
#include <catch2/catch.hpp>
#include <cstdint>

#include "mapfuse/lidar/paged_array.hpp"
#include "mapfuse/lidar/voxel_map.hpp"

using namespace mapfuse;

namespace {
lidar::VoxelCoord coordOfIndex(int i) {
  return {i % 97 - 48, (i / 97) % 89 - 44, i / (97 * 89)};
}
}  // namespace

TEST_CASE("paged array grows, truncates and reserves across pages", "[lidar][voxel_map]") {
  lidar::PagedArray<int, 4> a;  // 16 elements per page
  CHECK(a.empty());
  for (int i = 0; i < 100; ++i) a.push_back(i);
  REQUIRE(a.size() == 100);
  CHECK(a.capacity() == 112);  // 6 full pages + the 7th page allocated full
  const int* first = &a[0];
  for (int i = 100; i < 1000; ++i) a.push_back(i);
  CHECK(&a[0] == first);  // growing never moves stored elements
  int expect = 0;
  for (int v : a) CHECK(v == expect++);
  CHECK(expect == 1000);
  a.truncate(37);
  CHECK(a.size() == 37);
  CHECK(a[36] == 36);
  a.shrinkToFit();
  CHECK(a.capacity() == 37);
  a.push_back(-1);
  CHECK(a[37] == -1);
  lidar::PagedArray<int, 4> b;
  b.reserve(40);
  CHECK(b.capacity() == 40);
  for (int i = 0; i < 40; ++i) b.push_back(i);
  CHECK(b.capacity() == 40);
  b.truncate(0);
  CHECK(b.empty());
  CHECK(b.begin() == b.end());
}

TEST_CASE("voxel map indices stay valid across pages and filter keeps the order",
          "[lidar][voxel_map]") {
  const int n = 200000;  // > 3 pages of 65536 voxels
  lidar::SemanticVoxelMap map(0.05);
  for (int i = 0; i < n; ++i)
    REQUIRE(map.findOrInsert(lidar::packKey(coordOfIndex(i))) == static_cast<std::size_t>(i));
  REQUIRE(map.size() == static_cast<std::size_t>(n));
  for (int i = 0; i < n; i += 7) {
    REQUIRE(map.find(lidar::packKey(coordOfIndex(i))) == i);
    REQUIRE(map.findOrInsert(lidar::packKey(coordOfIndex(i))) == static_cast<std::size_t>(i));
  }
  map.fuse(n - 1, {0.01f, 0.9f, 0.01f, 0.02f, 0.02f, 0.02f, 0.01f, 0.01f});
  CHECK(map.voxels()[n - 1].label == 1);
  CHECK(map.voxels()[n - 1].observations == 1);
  map.shrinkToFit();
  CHECK(static_cast<double>(map.memoryBytes()) / n <= 64.0);

  std::vector<uint8_t> keep(n);
  for (int i = 0; i < n; ++i) keep[i] = i % 3 != 0;
  map.filter(keep);
  int j = 0;
  for (int i = 0; i < n; ++i) {
    const int64_t found = map.find(lidar::packKey(coordOfIndex(i)));
    if (i % 3 == 0) {
      REQUIRE(found == -1);
    } else {
      REQUIRE(found == j);
      REQUIRE(map.voxels()[j].key == lidar::packKey(coordOfIndex(i)));
      ++j;
    }
  }
  CHECK(map.size() == static_cast<std::size_t>(j));
  CHECK(map.voxels()[j - 1].label == 1);  // voxel n - 1 survived (n - 1 is not a multiple of 3)
}
