#pragma once
/// @file Aerial elements of a drive (Song et al. 2023 §3.2.3): the boxes of one track id over
/// the frames are triangulated key point by key point (eq. 2-3); signs keep their corners,
/// lights and poles become a base point with a height. Private to vehicle/ (lsm_build.cpp).
#include <map>
#include <string>
#include <vector>

#include "mapfuse/vehicle/lsm_assembly.hpp"
#include "mapfuse/vehicle/lsm_build.hpp"
#include "mapfuse/vehicle/triangulation.hpp"

namespace mapfuse::vehicle {

/// The triangulated tracks of a drive and what became of the others.
struct AerialTracks {
  std::vector<AerialElement> elements;  ///< odom frame, in (class, track id) order
  int tracks = 0;                       ///< distinct (class, track id) pairs
  std::map<std::string, int> rejected;  ///< tracks per rejection reason
  int unassociated = 0;                 ///< observations without a track id (ignored)
};

/// @brief Groups the aerial observations of all frames by (class, track id) and triangulates
/// each track (track-parallel); the element's truth id is the majority of its observations'.
AerialTracks triangulateAerialTracks(const DriveData& drive, const TriangulationSettings& settings);

}  // namespace mapfuse::vehicle
