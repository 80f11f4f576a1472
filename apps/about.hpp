#pragma once
/// @file What each tool says at the top of its --help (and so in docs/cli-reference.md, which
/// scripts/gen-cli-docs.sh makes from --help): what it does, its outputs and its exit codes. One
/// table for all tools, so that their wording stays consistent and each main is only its
/// arguments and its library call.

namespace mapfuse::apps::about {

inline constexpr const char* kAggregate =
    "Fuse LSMs in ENU (georef or align output, one shared origin) into a light vector HD map:\n"
    "two-stage DBSCAN lane instantiation, Bezier vectorization, discrete element merging\n"
    "(--method grid_vote: the Qin et al. 2021 grid-vote baseline for the ground classes).\n"
    "Outputs below --out: map.cbor (compact), map.json, map.geojson (WGS84), map.osm\n"
    "(Lanelet2) with map.osm.mapfuse.json (its map ids, pole heights), map.png,\n"
    "aggregate.config.json, aggregate.summary.json.\n"
    "Exit codes: 0 ok, 2 usage/config, 3 bad input (malformed LSM, frame odom, origin\n"
    "mismatch), 4 I/O.";

inline constexpr const char* kAlign =
    "Align georeferenced LSMs (one shared ENU origin): registrations between overlapping\n"
    "submaps of different traversals (--method icp | sicp | sgicp | gba_sgicp), PCM, a\n"
    "multi-trajectory pose graph, then GBA. Outputs below --out: one LSM per input (same file\n"
    "name), align.config.json, align.summary.json.\n"
    "Exit codes: 0 ok, 2 usage/config, 3 bad input, 4 I/O.";

inline constexpr const char* kBalance =
    "Place the tiles of a tiled run consistently: each tile's align leaves every group of\n"
    "drive pieces it registered together at the mean GPS error of those pieces; balance\n"
    "carries every drive's GPS error across the tiles it runs through and moves each group to\n"
    "where one untiled run would put it. Reads tiles.json and, per tile, align's output in\n"
    "<tile>/align/; writes the moved LSMs to <out>/<tile>/ (same file names) for aggregate,\n"
    "plus balance.config.json and balance.summary.json.\n"
    "Exit codes: 0 ok, 2 usage/config, 3 bad input (missing align output), 4 I/O.";

inline constexpr const char* kEvaluate =
    "Evaluate mapfuse products against ground truth; choose one subcommand.\n"
    "Exit codes: 0 ok, 2 usage/config, 3 bad input, 4 I/O.";

inline constexpr const char* kGeoref =
    "Georeference LSMs: fuse keyframe odometry and GPS fixes in a Ceres pose graph (Cauchy\n"
    "loss, chi-square rejection of multipath fixes) and write each LSM in ENU of one shared\n"
    "origin (--origin, or the first GPS fix of the first LSM). Outputs below --out: one LSM per\n"
    "input (same file name), georef.config.json, georef.summary.json.\n"
    "Exit codes: 0 ok, 2 usage/config, 3 bad input, 4 I/O.";

inline constexpr const char* kInfo =
    "Describe mapfuse files (LSM, vector map, tiles, summary) as JSON lines on stdout; with "
    "--origin print the ENU origin \"lat,lon,alt\" of the first LSM (its origin, else its "
    "first GPS fix), the value per-drive georef jobs of one batch share.";

inline constexpr const char* kLidarSemanticMap =
    "Build a semantic voxel map from a KITTI raw drive or a KITTI odometry / SemanticKITTI\n"
    "sequence folder: poses (OXTS, poses file or LiDAR odometry), per-pixel semantics (ENet or\n"
    "precomputed semantics_02), projection onto image_02, cluster error minimisation, Bayesian\n"
    "voxel fusion, batch refinement. Outputs below --out: map.ply, map.pcd,\n"
    "labels/<frame>.label, topdown.png, poses.txt (KITTI T_world_cam0), poses_velo.txt\n"
    "(T_map_velo), lidar-semantic-map.{config,summary}.json. Untrusted odometry steps are\n"
    "listed on stderr and in the summary; more than --odom-max-untrusted stop the run (exit 3).\n"
    "A failed run leaves the previous outputs in the folder unchanged.\n"
    "Error minimisation is on by default with the forests the build generates from simulated\n"
    "drives (--classifier-dir auto = <bin>/../models/lidar-classifiers; none = off); the summary\n"
    "names them and their provenance. Retrain: scripts/train-classifiers.sh BIN_DIR DIR "
    "(simulated\n"
    "drives), or `train DRIVE... --validation DRIVE... -o DIR` on drives with\n"
    "labels/<frame>.label (validation drives choose each label's threshold), then\n"
    "--classifier-dir DIR.\n"
    "Exit codes: 0 ok, 2 usage/config, 3 bad input, 4 I/O.";

inline constexpr const char* kLocalize =
    "Localise georeferenced drives (LSMs, frame enu) on a vector map: per keyframe, observed\n"
    "lane / stop line points point-to-line, poles / lights / planar centres point-to-point,\n"
    "Cauchy loss, the georeferenced (GPS) pose as a weak prior; then (solve full_drive) all\n"
    "keyframes of a drive in one problem chained by its relative motion. Frames level\n"
    "(--frames DIR): every camera frame of the raw drives in DIR, from lsm-build's per-frame\n"
    "ranging; the LSMs are then lsm-build's of these drives, georeferenced. Outputs below --out:\n"
    "<drive>.trajectory.json; with --truth-trajectories <drive>.errors.csv and .errors.png;\n"
    "localize.config.json, localize.summary.json (mean lateral / longitudinal / heading; with\n"
    "--truth-map also in the map's own frame).\n"
    "Exit codes: 0 ok, 2 usage/config, 3 bad input or map lost (> max_lost_share), 4 I/O.";

inline constexpr const char* kLsmBuild =
    "Build a local semantic map (LSM) from one drive: camera semantics + ego-motion "
    "(docs/lsm-build.md).";

inline constexpr const char* kSimulate =
    "Simulate crowdsourced drives (LSMs, raw frames) with ground truth.\n"
    "Outputs below --out: truth/vector_map.json(.geojson), truth/<drive>.trajectory.json,\n"
    "lsm/<drive>.lsm.cbor|json (--level lsm), frames/<drive>/ (--level frames),\n"
    "simulate.config.json, simulate.summary.json. Exit codes: 0 ok, 2 usage/config,\n"
    "3 bad input (malformed map), 4 I/O (missing map, unwritable output).";

inline constexpr const char* kSimulateLidar =
    "Simulate a labelled KITTI raw drive (LiDAR + camera ground truth).";

inline constexpr const char* kStitch =
    "Merge per-tile vector maps (paths containing tile_<ix>_<iy>) into one map.";

inline constexpr const char* kUpdate =
    "Detect what changed between an existing vector map (aggregate's map.json/.cbor) and new\n"
    "drives' LSMs in the map's ENU frame (georef --origin of the map, then align): per map\n"
    "element and new traversal the expected observation area, then removed / moved /\n"
    "restriped / retyped by accumulated evidence, and added for clusters no element explains.\n"
    "Outputs below --out: changes.json (mapfuse.map_changes), changes.geojson (WGS84),\n"
    "update.config.json, update.summary.json (with the map elements no drive verified).\n"
    "Exit codes: 0 ok, 2 usage/config, 3 bad input (malformed file, frame odom, origin\n"
    "differs from the map's), 4 I/O.";

inline constexpr const char* kTile = "Cut georeferenced LSMs (frame enu) into per-tile LSM sets.";

}  // namespace mapfuse::apps::about
