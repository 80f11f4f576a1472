#pragma once
/// @file Independent work items on the OpenMP threads, with errors reported as a serial loop
/// would report them.
#include <omp.h>

#include <cstddef>
#include <exception>
#include <vector>

namespace mapfuse {

/// @brief Calls body(i) for every i in [0, n) on the OpenMP threads (`threads` of them when
/// > 0, else OpenMP's default), dynamically scheduled. An exception in one item does not stop
/// the others; once all have run, the exception of the lowest index is rethrown with its type
/// (the one a serial loop would have thrown first).
template <class Body>
void parallelFor(std::size_t n, Body&& body, int threads = 0) {
  std::vector<std::exception_ptr> failed(n);
  const int team = threads > 0 ? threads : omp_get_max_threads();
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
