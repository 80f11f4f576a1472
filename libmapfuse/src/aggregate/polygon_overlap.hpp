#pragma once
/// @file Exact intersection area of two planar polygon sets (polygons with holes), built for
/// the stage-1 similarity of lane instantiation: many queries between long thin buffer polygons
/// of a few dozen vertices each.
///
/// Method (Green's theorem): the boundary of A ∩ B is the part of ∂A inside B plus the part of
/// ∂B inside A, both with their own orientation, so area(A ∩ B) = ½ Σ p × q over those boundary
/// pieces. Edge crossings come from a sort-and-sweep along the longer axis of the overlap of
/// the two bounding boxes (edges are pre-sorted once per polygon), the inside state of each
/// ring's first vertex from a crossing-number test, and it toggles at every crossing. Cost
/// O((n + m) log + k) per pair (k candidate edge pairs) instead of a general overlay.
///
/// Edge pairs are classified with orientation signs: an end point farther than 1e-9 m from the
/// other edge's line has a reliable sign, and a crossing of two such edges lies more than 1e-9 m
/// from every end point. Degenerate configurations (a vertex of one polygon within 1e-9 m of the
/// other's boundary, collinear overlapping edges) are reported, not resolved: the caller then
/// uses a robust overlay (Boost.Geometry) for that pair. Two identical polygons (same vertices
/// in the same order) are handled: the area of one.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

namespace mapfuse::aggregate {

/// A polygon set prepared for repeated intersection-area queries. Coordinates are stored
/// relative to `origin` (pass the same origin for polygons that will be compared; a nearby
/// origin keeps the cross products small: errors ~1e-16 × (extent)², far below 1e-9 m).
class OverlapPolygon {
 public:
  OverlapPolygon() = default;
  /// @param rings outer boundaries and holes, each a vertex list (closed or not), non-crossing
  /// (a valid polygon set). Either orientation convention — clockwise outer rings with
  /// counter-clockwise holes (Boost.Geometry's default) or the reverse — as long as it is
  /// consistent. Consecutive duplicate vertices are dropped, rings of < 3 vertices ignored.
  /// @param origin subtracted from every vertex (m).
  OverlapPolygon(const std::vector<std::vector<Eigen::Vector2d>>& rings,
                 const Eigen::Vector2d& origin);

  double area() const { return area_; }  ///< m²
  bool empty() const { return vertices_.empty(); }
  std::size_t numVertices() const { return vertices_.size(); }
  const Eigen::Vector2d& origin() const { return origin_; }
  /// Rings in local coordinates (relative to the origin), counter-clockwise outer rings, open.
  std::vector<std::vector<Eigen::Vector2d>> localRings() const;

  /// @brief Area of a ∩ b (m²), or std::nullopt for a degenerate configuration (see the file
  /// comment). Thread-safe.
  /// @throws std::invalid_argument when a and b have different origins.
  friend std::optional<double> intersectionArea(const OverlapPolygon& a, const OverlapPolygon& b);

 private:
  std::vector<Eigen::Vector2d> vertices_;  ///< all rings, open, region on the left
  std::vector<int32_t> ring_start_;        ///< ring r: vertices [ring_start_[r], ring_start_[r+1])
  std::vector<int32_t> next_;              ///< edge k runs from vertex k to vertex next_[k]
  std::vector<Eigen::Vector2d> edge_lo_, edge_hi_;  ///< bounding box of edge k
  std::vector<int32_t> order_[2];                   ///< edges sorted by their lower x (0) or y (1)
  Eigen::Vector2d origin_{0, 0};
  Eigen::Vector2d lo_{0, 0}, hi_{0, 0};  ///< bounding box of all vertices
  double area_ = 0.0;
};

std::optional<double> intersectionArea(const OverlapPolygon& a, const OverlapPolygon& b);

}  // namespace mapfuse::aggregate
