#pragma once
/// @file Independent work items on the OpenMP threads, with errors reported as a serial loop
/// would report them.
#include <omp.h>

#include <algorithm>
#include <cstddef>
#include <exception>
#include <vector>

namespace mapfuse {

/// @brief Calls body(i) for every i in [0, n) on the OpenMP threads (`threads` of them when
/// > 0, else OpenMP's default; never more than n), dynamically scheduled. An exception in one
/// item does not stop the others; once all have run, the exception of the lowest index is
/// rethrown with its type (the one a serial loop would have thrown first). One item runs on the
/// calling thread: a team for it left an idle worker spinning (georef reads its one LSM here: in
/// a per-drive job that spin was 40 % of the process's CPU samples).
template <class Body>
void parallelFor(std::size_t n, Body&& body, int threads = 0) {
  if (n == 0) return;
  if (n == 1) {
    body(std::size_t(0));
    return;
  }
  std::vector<std::exception_ptr> failed(n);
  const int team = int(std::min<std::size_t>(n, threads > 0 ? threads : omp_get_max_threads()));
#pragma omp parallel for schedule(dynamic) num_threads(team)
  for (std::ptrdiff_t k = 0; k < std::ptrdiff_t(n); ++k) {
    try {
      body(std::size_t(k));
    } catch (...) {
      failed[std::size_t(k)] = std::current_exception();
    }
  }
  for (const auto& e : failed)
    if (e) std::rethrow_exception(e);
}

}  // namespace mapfuse
