#pragma once
/// @file The input of aggregation: every element of every LSM, transformed into the shared ENU
/// frame (the anchor keyframe's T_enu_body applied, §4.2 "P' = R P + t").
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/lsm.hpp"
#include "mapfuse/geo/origin.hpp"

namespace mapfuse::aggregate {

/// One LSM element in ENU.
struct Observation {
  int drive = 0;           ///< index of the source LSM in the input list
  int64_t element_id = 0;  ///< Element::id within its LSM
  CrowdClass cls = CrowdClass::kLaneLine;
  Attributes attributes;
  std::vector<Eigen::Vector3d> points;  ///< ENU, m
  double confidence = 1.0;              ///< [0, 1]
  int observations = 1;                 ///< frames that observed it
  double height = 0.0;                  ///< m (poles, lights)
  int64_t truth_id = -1;                ///< simulator provenance, -1 unknown
};

/// All observations of a set of LSMs sharing one ENU origin.
struct ObservationSet {
  geo::GeoOrigin origin;
  int num_drives = 0;
  std::vector<Observation> items;
};

/// @brief Transforms the elements of georeferenced (or aligned) LSMs into ENU observations.
/// @param lsms LSMs in frame enu, all with the same origin.
/// @param sources one name per LSM (file path) for error messages.
/// @throws InputError when there is no LSM, an LSM is not in frame enu, or the origins differ
/// (the message names both files).
ObservationSet collectObservations(const std::vector<Lsm>& lsms,
                                   const std::vector<std::string>& sources);

/// @brief Indices of the observations of one class.
std::vector<std::size_t> indicesOfClass(const ObservationSet& set, CrowdClass cls);

}  // namespace mapfuse::aggregate
