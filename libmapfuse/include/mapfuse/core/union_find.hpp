#pragma once
/// @file Disjoint sets over indices 0..n-1 kept as a parent array (parent[i] == i at a root).
#include <vector>

namespace mapfuse {

/// @brief Root of `i`'s set, halving the path on the way (parent[i] = parent[parent[i]]).
inline int findRoot(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace mapfuse
