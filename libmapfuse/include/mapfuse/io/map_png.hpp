#pragma once
/// @file Top-down PNG of a vector map over a grey background (the observations it was built
/// from, or the truth it is scored against), OpenCV drawing, north up: map instances in their
/// colours on white (core/classes.hpp crowdClassPaperColor; yellow lane lines yellow, dashed lane
/// lines dashed); signs (squares) and lights (discs) outlined, poles as smaller dots over them,
/// so each class keeps pixels of its colour; the picture key on the right (io/picture_key.hpp): title,
/// one legend line per class drawn and the background, scale bar, north arrow.
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "mapfuse/core/vector_map.hpp"

namespace mapfuse::io {

struct MapPngOptions {
  double resolution = 0.2;           ///< m per pixel (coarsened automatically to respect max_size)
  int max_size = 4000;               ///< px, largest image side
  double margin = 5.0;               ///< m around the drawn geometry
  std::string title = "vector map";  ///< the key's title
  std::string background_label = "observations";  ///< the grey lines' legend entry
};

/// @brief Renders the map (and `background` polylines, single points drawn as dots) to a PNG.
/// @throws IoError when the file cannot be written.
void writeMapPng(const std::filesystem::path& path, const VectorMap& map,
                 const std::vector<std::vector<Eigen::Vector3d>>& background,
                 const MapPngOptions& options = {});

}  // namespace mapfuse::io
