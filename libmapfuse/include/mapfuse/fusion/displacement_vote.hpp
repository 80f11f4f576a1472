#pragma once
/// @file Coarse registration by displacement voting (the coarsest level of align's semantic
/// pyramid, docs/fusion.md; also the first step of a map update's registration to the map,
/// docs/update.md). GPS-level initial errors (1-6 m) exceed half a lane width and half the dash
/// period, so GICP started at the georeferenced poses converges to the neighbouring lane line or
/// dash. Every same-label pair (a, b) within a radius votes for the shift a - b; the true shift
/// collects the votes of all lines and landmarks at once, an alias only those of a subset.
#include <Eigen/Core>
#include <vector>

#include "mapfuse/fusion/point_cloud.hpp"

namespace mapfuse::fusion {

/// The peak of a displacement vote.
struct DisplacementPeak {
  Eigen::Vector2d t = Eigen::Vector2d::Zero();  ///< m, shift that maps B onto A
  double score = 0;                             ///< votes at the peak
};

/// Displacement histogram a - b over [-half, half]^2 bins of `bin` m (row-major, y rows).
struct DisplacementVotes {
  int half = 0;
  double bin = 0.5;
  std::vector<double> votes;
  void add(const DisplacementVotes& o, double w) {
    for (std::size_t i = 0; i < votes.size() && i < o.votes.size(); ++i) votes[i] += w * o.votes[i];
  }
};

/// @brief Votes of every same-label pair (a, b) within `radius` (weights per label, bilinear).
DisplacementVotes voteDisplacements(const Cloud& A, const Cloud& B,
                                    const std::vector<double>& weights, double radius, double bin);

/// @brief Peak of a (summed) vote grid after [1 2 1]^2 smoothing and the Gaussian prior about
/// `prior_centre` (m).
DisplacementPeak votePeak(const DisplacementVotes& g, double prior_sigma,
                          const Eigen::Vector2d& prior_centre = Eigen::Vector2d::Zero());

}  // namespace mapfuse::fusion
