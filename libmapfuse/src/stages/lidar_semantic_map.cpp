#include "mapfuse/stages/lidar_semantic_map.hpp"

#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/core/stopwatch.hpp"
#include "mapfuse/io/kitti_poses.hpp"
#include "mapfuse/io/output_transaction.hpp"
#include "mapfuse/io/pcd.hpp"
#include "mapfuse/io/ply.hpp"
#include "mapfuse/io/png_frames.hpp"
#include "mapfuse/io/semantic_kitti.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/io/velodyne.hpp"

namespace mapfuse::stages {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {
constexpr const char* kLidarSemanticMap = "lidar-semantic-map";
/// labels/<frame>.label for every scan; the summary's share of labelled points.
json writeScanLabels(const io::KittiRawDrive& drive, const lidar::SemanticMapResult& r,
                     const fs::path& output) {
  std::size_t files = 0, labelled = 0, points = 0;
  for (std::size_t i = 0; i < drive.frames.size(); ++i) {
    const auto& f = drive.frames[i];
    const auto scan = io::readVelodyneBin(f.velodyne);
    const auto labels =
        lidar::scanLabels(r.map, r.poses.T_map_velo[i], scan.points, &r.refinement.removed);
    for (uint32_t l : labels) labelled += l != 0;
    points += labels.size();
    io::writeSemanticKittiLabels(output / "labels" / (f.name + ".label"), labels);
    ++files;
  }
  return {{"scan_label_files", files},
          {"scan_points_labelled_fraction",
           points ? static_cast<double>(labelled) / static_cast<double>(points) : 0.0}};
}

json toJson(const lidar::CameraOverlayReport& o, const lidar::CameraOverlaySettings& s) {
  json classes = json::object();
  for (int c = 1; c < kNumLidarClasses; ++c)
    classes[lidarClassName(LidarClass(c))] = o.pictures_with_class[c];
  return {{"every", s.every},
          {"source", s.source},
          {"files", o.files},
          {"frames_without_image", o.frames_without_image},
          {"points_drawn", o.points_drawn},
          {"pictures_with_class", classes}};
}
}  // namespace

lidar::SemanticMapResult runLidarSemanticMap(const fs::path& drive_dir, const fs::path& output,
                                             const LidarSemanticMapParams& p) {
  validateParams(p);
  io::OutputTransaction outputs(output);  // locked and writable before the work (exit 4)
  const Stopwatch total;
  const io::KittiRawDrive drive = io::openKittiRawDrive(drive_dir, p.frames);
  const double t_open = total.seconds();
  MAPFUSE_INFO(kLidarSemanticMap << ": " << drive.frames.size() << " frames of " << drive.dir);
  lidar::SemanticMapResult r = lidar::buildSemanticMap(drive, p.map, output / "semantics_02");

  const Stopwatch t;
  const LabeledCloud cloud = lidar::toLabeledCloud(r.map);
  io::writePly(output / "map.ply", cloud);
  io::writePcd(output / "map.pcd", cloud);
  const double res = p.exports.topdown_resolution;
  const bool north_up = r.poses.source == "oxts" || r.poses.source == "oxts_enu";  // else frame 0
  const lidar::TopDownPicture top =
      lidar::renderTopDownPicture(r.map, r.poses.T_map_velo, res, north_up);
  io::writePngFrame(output / "topdown.png", top.image);
  io::writeKittiOdometryPoses(
      output / "poses.txt",
      lidar::cameraPosesForFile(r.poses.T_map_velo, drive.calib.T_rect0_velo()));
  io::writeKittiOdometryPoses(output / "poses_velo.txt", r.poses.T_map_velo);
  const lidar::CameraOverlayReport overlays =
      lidar::writeCameraOverlays(drive, r.map, r.poses.T_map_velo, p.exports.overlay,
                                 p.map.fusion.projection.max_range, output / "overlay");
  json summary = toJson(r, p.map.poses.odometry);
  summary.update(p.exports.write_scan_labels
                     ? writeScanLabels(drive, r, output)
                     : json{{"scan_label_files", 0}, {"scan_points_labelled_fraction", 0.0}});
  summary["overlay"] = toJson(overlays, p.exports.overlay);
  summary["timings_s"]["open"] = t_open + r.timings.open;
  summary["timings_s"]["outputs"] = t.seconds();
  summary["timings_s"]["total"] = total.seconds();

  json hist = json::object();
  std::array<std::size_t, kNumLidarClasses> counts{};
  for (uint8_t l : cloud.labels) ++counts[l];
  for (int c = 0; c < kNumLidarClasses; ++c) hist[lidarClassName(LidarClass(c))] = counts[c];
  summary["label_histogram"] = hist;
  summary["drive"] = drive.dir.string();
  summary["frames"] = drive.frames.size();
  summary["first_frame"] = drive.frames.front().index;
  summary["last_frame"] = drive.frames.back().index;
  summary["topdown"] = {{"resolution_m", res},
                        {"origin_xy", {top.origin_xy.x(), top.origin_xy.y()}},
                        {"width", top.width},
                        {"height", top.height}};
  io::writeResolvedConfig(output, kLidarSemanticMap, paramsToJson(p));
  io::writeSummary(output, kLidarSemanticMap, summary);
  outputs.commit();  // every output replaced as a set: a failed run above left the previous ones
  return r;
}

}  // namespace mapfuse::stages
