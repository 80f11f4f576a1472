#pragma once
/// @file Top-down PNG of a vector map over the observations it was built from (OpenCV drawing):
/// observations thin and grey, map instances in their class colours (dashed lane lines drawn
/// dashed), north up, a 10 m scale bar in the lower-left corner.
#include <Eigen/Core>
#include <filesystem>
#include <vector>

#include "mapfuse/core/vector_map.hpp"

namespace mapfuse::io {

struct MapPngOptions {
  double resolution = 0.2;  ///< m per pixel (coarsened automatically to respect max_size)
  int max_size = 4000;      ///< px, largest image side
  double margin = 5.0;      ///< m around the drawn geometry
};

/// @brief Renders the map (and `background` polylines, single points drawn as dots) to a PNG.
/// @throws IoError when the file cannot be written.
void writeMapPng(const std::filesystem::path& path, const VectorMap& map,
                 const std::vector<std::vector<Eigen::Vector3d>>& background,
                 const MapPngOptions& options = {});

}  // namespace mapfuse::io
