#pragma once
/// @file KITTI raw drives: `<date>/<date>_drive_<name>_sync/` with image_02/data/*.png,
/// velodyne_points/data/*.bin, oxts/data/*.txt (+ dataformat.txt) and timestamps.txt files,
/// and the date folder's three calibration files. Frames are indexed by the Velodyne files
/// present, so partial folders (a few frames, no OXTS, no timestamps) work. The same structure
/// also holds a KITTI odometry / SemanticKITTI sequence (io/kitti_sequence.hpp), which
/// openKittiRawDrive recognises and opens.
#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "mapfuse/core/param.hpp"
#include "mapfuse/geo/oxts.hpp"
#include "mapfuse/io/kitti_calib.hpp"

namespace mapfuse::io {

/// Which frames to use: indices first..last (inclusive, last < 0 = up to the end), every
/// `stride`-th frame present.
struct FrameRange {
  int first = 0;   ///< first frame index
  int last = -1;   ///< last frame index (inclusive), -1 = all
  int stride = 1;  ///< every stride-th frame present

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("first_frame", first, "", "first frame index", in(0, 1e9));
    v("last_frame", last, "", "last frame index, inclusive (-1 = all)", in(-1, 1e9));
    v.relation("last_frame", last, last < 0 || last >= first, "-1 or >= first_frame");
    v("stride", stride, "", "use every stride-th frame present", in(1, 1e6));
  }
};

/// One frame of a drive.
struct KittiRawFrame {
  int index = 0;                     ///< frame number (file name)
  std::string name;                  ///< file stem, e.g. "0000000000"
  std::filesystem::path velodyne;    ///< velodyne_points/data/<name>.bin (always exists)
  std::filesystem::path image;       ///< image_02/data/<name>.png, empty when absent
  std::filesystem::path oxts;        ///< oxts/data/<name>.txt, empty when absent
  double timestamp = std::nan("");   ///< velodyne timestamps.txt (s since the date's midnight)
  double scan_start = std::nan("");  ///< timestamps_start.txt (s), NaN when unknown
  double scan_end = std::nan("");    ///< timestamps_end.txt (s), NaN when unknown
};

/// An opened drive (files listed, nothing heavy loaded).
struct KittiRawDrive {
  std::filesystem::path dir;         ///< the drive folder
  std::filesystem::path date_dir;    ///< its parent, holding the calibration files (raw layout)
  std::string layout = "raw";        ///< "raw" or "sequence" (KITTI odometry / SemanticKITTI)
  std::filesystem::path poses_file;  ///< a sequence's own poses.txt (T_world_cam0), or empty
  KittiCalibration calib;
  std::vector<KittiRawFrame> frames;  ///< selected frames, ascending index
  bool has_oxts = false;              ///< every selected frame has an OXTS record
};

/// @brief Lists the drive's frames and reads the calibration of its date folder; a folder with
/// velodyne/ and calib.txt instead of velodyne_points/ is opened as a KITTI odometry sequence
/// (openKittiSequence).
/// @throws IoError when the folder or velodyne_points/data is missing; InputError when no frame
/// is selected or the range is invalid; ParseError for bad calibration or timestamp lines.
KittiRawDrive openKittiRawDrive(const std::filesystem::path& drive_dir, const FrameRange& range);

/// @brief Checks a frame range. @throws InputError naming the rule when it is invalid.
void checkFrameRange(const FrameRange& range);

/// @brief Frame number of a file stem made of digits only (at most 12), or -1.
long kittiFrameNumber(const std::string& stem);

/// @brief The Velodyne scans of `velo_dir` (files "<frame>.bin") that `range` selects (frames in
/// [first, last], every stride-th of those), as (frame, path) sorted by frame.
/// @throws IoError when the folder does not exist; InputError when it holds no scan at all.
std::vector<std::pair<long, std::filesystem::path>> listVelodyneScans(
    const std::filesystem::path& velo_dir, const FrameRange& range);

/// @brief Reads one frame's OXTS record. @throws IoError when absent, ParseError when malformed.
geo::OxtsRecord readOxts(const KittiRawFrame& frame);

/// @brief Parses a KITTI timestamp "YYYY-MM-DD HH:MM:SS.fffffffff" into seconds since the
/// midnight of its date. @throws ParseError(file, field) when malformed or out of range.
double parseKittiTimestamp(const std::string& text, const std::string& file,
                           const std::string& field);

/// @brief Every non-empty line of a timestamps file. @throws ParseError(file, "line N").
std::vector<double> parseKittiTimestamps(const std::string& text, const std::string& file);

}  // namespace mapfuse::io
