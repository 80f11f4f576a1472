#pragma once
/// @file Changed worlds (docs/simulate.md "Changed worlds"): true changes drawn with their own
/// seed and applied to a world's truth before any drive is simulated over it, so that a run
/// without changes ("before") and one with ("after") over the same world share every unchanged
/// element, id and geometry byte for byte. Kinds: removed (sign, light, pole, stop line, arrow,
/// crosswalk), added (a sign or pole beside the road, an arrow in a lane, a stop line across a
/// lane end), moved (pole or sign, along the road), restriped (a lane line shifted sideways over
/// its length or a stretch), retyped (dashed <-> solid lane line, an arrow turned round).
#include <cstdint>

#include "mapfuse/core/map_changes.hpp"
#include "mapfuse/core/param.hpp"
#include "mapfuse/sim/world.hpp"

namespace mapfuse::sim {

struct ChangeSettings {
  int removed = 0;         ///< elements removed
  int added = 0;           ///< elements added
  int moved = 0;           ///< poles and signs moved
  int restriped = 0;       ///< lane lines shifted sideways
  int retyped = 0;         ///< lane lines dashed <-> solid, arrows turned round
  uint64_t seed = 1;       ///< the changes' own seed (independent of the crowd's)
  double move_min = 0.5;   ///< m, displacement of a moved element
  double move_max = 5.0;   ///< m
  double shift_min = 0.3;  ///< m, sideways shift of a restriped lane line
  double shift_max = 3.5;  ///< m
  /// m: only elements this near a planned route change (a lane line: half of it), additions too;
  /// 0: anywhere in the world. Changes no drive passes cannot be detected by any update.
  double route_distance = 12.0;

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("change_removed", removed, "",
      "true changes: signs, lights, poles, stop lines, arrows, crosswalks removed", in(0, 100000));
    v("change_added", added, "",
      "true changes: signs / poles beside the road, arrows in lanes, stop lines at lane ends "
      "added",
      in(0, 100000));
    v("change_moved", moved, "", "true changes: poles and signs moved along the road",
      in(0, 100000));
    v("change_restriped", restriped, "",
      "true changes: lane lines shifted sideways (whole length or a stretch)", in(0, 100000));
    v("change_retyped", retyped, "",
      "true changes: lane lines dashed <-> solid, ground arrows turned round", in(0, 100000));
    v("change_seed", seed, "", "random seed of the true changes", in(0, 4294967295.0));
    v("change_move_min", move_min, "m", "displacement of a moved element, min", in(0.01, 100));
    v("change_move_max", move_max, "m", "displacement of a moved element, max", in(0.01, 100));
    v.relation("change_move_max", move_max, move_max >= move_min, ">= change_move_min");
    v("change_shift_min", shift_min, "m", "sideways shift of a restriped lane line, min",
      in(0.01, 20));
    v("change_shift_max", shift_max, "m", "sideways shift of a restriped lane line, max",
      in(0.01, 20));
    v.relation("change_shift_max", shift_max, shift_max >= shift_min, ">= change_shift_min");
    v("change_route_distance", route_distance, "m",
      "only elements this near a planned route change (a lane line: half its length; 0: anywhere "
      "in the world)",
      in(0, 10000));
  }

  int total() const { return removed + added + moved + restriped + retyped; }
};

/// Distance (m) an added element keeps from every element of its class, so that each addition
/// is one unambiguous change (`evaluate changes` matches additions within a smaller distance).
constexpr double kAddedClearance = 10.0;

/// @brief Draws settings.total() changes (exactly the requested count of each kind, each element
/// changed at most once) and applies them to world.truth: removed elements leave it, changed
/// ones keep their id and place in it, added ones are appended with fresh ids (above the
/// largest). Drives simulated afterwards see the changed world. With `routes` and
/// settings.route_distance > 0 only elements (and places of additions) within route_distance of
/// a route are drawn.
/// @return the change truth, ids of the world before (after_id == before_id for changed ones).
/// @throws ConfigError when the world has too few candidates for a kind, naming the key.
MapChanges applyWorldChanges(World& world, const ChangeSettings& settings,
                             const std::vector<Polyline>& routes = {});

}  // namespace mapfuse::sim
