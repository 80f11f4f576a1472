#pragma once
/// @file Stage 2 of lane instantiation (§4.3.1, Song et al. 2023): fragment ends are linked with
/// the modified core-object rule MinPts <= |N_eps| <= MaxPts, then the chains of linked
/// fragments are walked into lane instances (lane_instantiation.cpp).
#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <vector>

#include "lane_fragments.hpp"
#include "lane_instantiation.hpp"

namespace mapfuse::aggregate {

/// The ends of stage-1 fragments and the tests that link them. End e = 2 f + w is the front
/// (w = 0) or the back (w = 1) of fragment f.
class FragmentEnds {
 public:
  FragmentEnds(const std::vector<Fragment>& frags, const LaneInstantiationParams& p);
  ~FragmentEnds();

  std::size_t size() const { return ends_.size(); }

  /// @brief The ends that end e could link to, sorted: ends within reach that follow e on a
  /// straight line or on one arc (curves too tight for the straight test: roundabouts), without
  /// those lying beyond a nearer candidate (dropShadowed). |N_eps| of e is 1 + their number.
  std::vector<std::size_t> candidates(std::size_t e) const;

  /// @brief Points filling the gap of a link from end `from` to end `to`: none for a straight
  /// link, else along the arc (arc_link.hpp), which a chord would cut short.
  std::vector<Eigen::Vector3d> bridge(std::size_t from, std::size_t to) const;

 private:
  struct End {
    Eigen::Vector3d pos;
    Eigen::Vector2d dir;  ///< outward unit direction
  };
  struct Index;  // the ends in an R-tree

  bool follows(const End& a, const End& b) const;
  bool straight(std::size_t e, std::size_t f) const;
  bool onArc(std::size_t e, std::size_t f) const;
  void dropShadowed(std::size_t e, std::vector<std::size_t>& cand) const;

  const LaneInstantiationParams& p_;
  double cos_max_ = 1.0;  ///< cosine of link_angle_deg
  std::vector<End> ends_;
  /// each end's last kArcTail metres: from_end_[e] starts at the end and runs inward, to_end_[e]
  /// the reverse
  std::vector<std::vector<Eigen::Vector3d>> from_end_, to_end_;
  std::unique_ptr<Index> index_;
};

/// @brief Links every core end (MinPts <= |N_eps| <= MaxPts) to its first candidate that is a
/// core end too, both still free. @return per end the end it is linked to, or -1. Counts links
/// and branch ends (more candidates than MaxPts allows) into `stats`.
std::vector<long> linkEnds(const std::vector<std::vector<std::size_t>>& candidates,
                           const LaneInstantiationParams& p, LaneInstantiationStats& stats);

/// @brief Walks the chains of linked fragments (open chains from their free end, then closed
/// loops) into lane instances; instances shorter than min_instance_length are dropped (counted
/// in `stats`).
std::vector<LaneInstance> chainFragments(const std::vector<Fragment>& frags,
                                         const FragmentEnds& ends, const std::vector<long>& link,
                                         const LaneInstantiationParams& p,
                                         LaneInstantiationStats& stats);

}  // namespace mapfuse::aggregate
