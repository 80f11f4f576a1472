#include "kitti_sequence.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/bounds.hpp"

namespace mapfuse::io {
namespace fs = std::filesystem;
namespace {

/// Width and height from a PNG's IHDR chunk (bytes 16-23, big-endian), or false.
bool pngSize(const fs::path& path, int* w, int* h) {
  std::ifstream f(path, std::ios::binary);
  unsigned char b[24];
  if (!f.read(reinterpret_cast<char*>(b), sizeof b)) return false;
  if (b[0] != 0x89 || b[1] != 'P' || b[2] != 'N' || b[3] != 'G') return false;
  auto be = [&](int o) {
    return int(uint32_t(b[o]) << 24 | uint32_t(b[o + 1]) << 16 | uint32_t(b[o + 2]) << 8 |
               uint32_t(b[o + 3]));
  };
  *w = be(16);
  *h = be(20);
  return *w > 0 && *h > 0;
}

/// times.txt: one time in seconds per line, within ±bounds::kMaxStamp, never going back; empty
/// when absent.
std::vector<double> readTimes(const fs::path& path) {
  std::vector<double> out;
  if (!fs::exists(path)) return out;
  std::istringstream in(readBytes(path));
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    try {
      std::size_t used = 0;
      out.push_back(std::stod(line, &used));
      if (line.find_first_not_of(" \t\r", used) != std::string::npos || !std::isfinite(out.back()))
        throw std::invalid_argument(line);
    } catch (const std::exception&) {
      throw ParseError(path.string(), "line " + std::to_string(n),
                       "not a time in seconds: '" + line + "'");
    }
    if (std::abs(out.back()) > bounds::kMaxStamp)  // the stamps of every other input (bounds.hpp)
      throw ParseError(path.string(), "line " + std::to_string(n),
                       "time " + bounds::numberText(out.back()) + " s is outside +-" +
                           bounds::numberText(bounds::kMaxStamp) + " s");
    if (out.size() > 1 && out.back() < out[out.size() - 2])
      throw ParseError(path.string(), "line " + std::to_string(n),
                       "time goes back (" + std::to_string(out.back()) + " s after " +
                           std::to_string(out[out.size() - 2]) + " s)");
  }
  return out;
}

}  // namespace

bool isKittiSequence(const fs::path& dir) {
  const bool sequence =
      fs::is_directory(dir / "velodyne") && !fs::is_directory(dir / "velodyne_points");
  // A sequence without calib.txt would otherwise be taken for a raw drive ("velodyne_points/data:
  // folder not found"): name the file that is missing.
  if (sequence && !fs::exists(dir / "calib.txt"))
    throw IoError((dir / "calib.txt").string(),
                  "missing: a KITTI odometry sequence (velodyne/) needs its calib.txt");
  return sequence;
}

KittiCalibration readKittiSequenceCalibration(const fs::path& dir) {
  const KittiCalibFile calib = KittiCalibFile::read(dir / "calib.txt");
  KittiCalibration c;
  c.P_rect_02 = calib.matrix("P2", 3, 4);
  c.R_rect_00 = Eigen::Matrix3d::Identity();
  c.T_cam0_velo = calib.rigid34("Tr");
  c.T_velo_imu = Pose3::Identity();
  c.has_imu = false;
  const fs::path images = dir / "image_2";
  if (fs::is_directory(images)) {
    std::vector<fs::path> pngs;
    for (const auto& e : fs::directory_iterator(images))
      if (e.path().extension() == ".png") pngs.push_back(e.path());
    std::sort(pngs.begin(), pngs.end());
    if (!pngs.empty() && !pngSize(pngs.front(), &c.image_width, &c.image_height))
      throw ParseError(pngs.front().string(), "IHDR", "not a PNG image");
  }
  return c;
}

KittiRawDrive openKittiSequence(const fs::path& dir_in, const FrameRange& range) {
  checkFrameRange(range);
  KittiRawDrive drive;
  drive.layout = "sequence";
  drive.dir = fs::absolute(dir_in).lexically_normal();
  if (!drive.dir.has_filename()) drive.dir = drive.dir.parent_path();
  drive.date_dir = drive.dir;
  const fs::path velo_dir = drive.dir / "velodyne";
  const auto scans = listVelodyneScans(velo_dir, range);
  const auto times = readTimes(drive.dir / "times.txt");
  for (const auto& [n, path] : scans) {
    KittiRawFrame f;
    f.index = static_cast<int>(n);
    f.name = path.stem().string();
    f.velodyne = path;
    const fs::path img = drive.dir / "image_2" / (f.name + ".png");
    if (fs::exists(img)) f.image = img;
    if (n < static_cast<long>(times.size()))
      f.timestamp = times[static_cast<std::size_t>(n)];
    else if (!times.empty())  // a time for some frames only: the stamps would be made up
      throw ParseError((drive.dir / "times.txt").string(), "line " + std::to_string(n + 1),
                       "missing: " + std::to_string(times.size()) + " times for scan " +
                           path.filename().string() + " (frame " + std::to_string(n) + ")");
    drive.frames.push_back(f);
  }
  if (drive.frames.empty())
    throw InputError(drive.dir.string() + ": no frame in the selected range " +
                     std::to_string(range.first) + ".." + std::to_string(range.last));
  drive.has_oxts = false;
  if (fs::exists(drive.dir / "poses.txt")) drive.poses_file = drive.dir / "poses.txt";
  drive.calib = readKittiSequenceCalibration(drive.dir);
  return drive;
}

}  // namespace mapfuse::io
