// parallelFor (core/parallel_for.hpp): every item once, the lowest index's exception with its
// type, and no OpenMP team for a single item (a per-drive job must not spin an idle worker).
#include <omp.h>

#include <atomic>
#include <catch2/catch.hpp>
#include <stdexcept>
#include <vector>

#include "mapfuse/core/parallel_for.hpp"

using mapfuse::parallelFor;

TEST_CASE("parallelFor runs every item once", "[core][parallel_for]") {
  for (std::size_t n : {0, 1, 2, 3, 1000}) {
    std::vector<std::atomic<int>> runs(n);
    parallelFor(
        n, [&](std::size_t i) { ++runs[i]; }, 2);
    for (std::size_t i = 0; i < n; ++i) CHECK(runs[i] == 1);
  }
}

TEST_CASE("parallelFor rethrows the lowest index's exception with its type",
          "[core][parallel_for]") {
  auto body = [](std::size_t i) {
    if (i == 7) throw std::out_of_range("seven");
    if (i == 3) throw std::invalid_argument("three");
  };
  CHECK_THROWS_AS(parallelFor(10, body, 2), std::invalid_argument);
  CHECK_THROWS_WITH(parallelFor(10, body, 2), "three");
  CHECK_THROWS_AS(parallelFor(
                      1, [](std::size_t) { throw std::out_of_range("one"); }, 2),
                  std::out_of_range);
}

TEST_CASE("parallelFor runs one item on the calling thread, without a team",
          "[core][parallel_for]") {
  int team = -1;
  bool in_parallel = true;
  parallelFor(
      1,
      [&](std::size_t) {
        team = omp_get_num_threads();
        in_parallel = omp_in_parallel();
      },
      4);
  CHECK(team == 1);
  CHECK_FALSE(in_parallel);
  // Two items on at most two threads, whatever was asked for.
  std::atomic<int> widest{0};
  parallelFor(
      2,
      [&](std::size_t) {
        int t = omp_get_num_threads();
        for (int w = widest; t > w && !widest.compare_exchange_weak(w, t);) {
        }
      },
      8);
  CHECK(widest <= 2);
}
