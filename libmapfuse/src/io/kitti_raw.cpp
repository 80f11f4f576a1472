#include "mapfuse/io/kitti_raw.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <limits>
#include <sstream>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "kitti_sequence.hpp"
#include "mapfuse/io/oxts_line.hpp"

namespace mapfuse::io {
namespace fs = std::filesystem;
namespace {

/// Lines of a timestamps file, parsed; empty when the file does not exist.
std::vector<double> readTimestamps(const fs::path& path) {
  if (!fs::exists(path)) return {};
  return parseKittiTimestamps(readBytes(path), path.string());
}

}  // namespace

std::vector<std::pair<long, fs::path>> listVelodyneScans(const fs::path& velo_dir,
                                                        const FrameRange& range) {
  if (!fs::is_directory(velo_dir)) throw IoError(velo_dir.string(), "folder not found");
  std::vector<std::pair<long, fs::path>> scans;
  for (const auto& e : fs::directory_iterator(velo_dir)) {
    if (e.path().extension() != ".bin") continue;
    const long n = kittiFrameNumber(e.path().stem().string());
    if (n >= 0) scans.emplace_back(n, e.path());
  }
  std::sort(scans.begin(), scans.end());
  if (scans.empty()) throw InputError(velo_dir.string() + ": no Velodyne scans (*.bin)");
  std::vector<std::pair<long, fs::path>> selected;
  int counter = 0;
  for (auto& scan : scans) {
    const long n = scan.first;
    if (n < range.first || (range.last >= 0 && n > range.last)) continue;
    if (counter++ % range.stride == 0) selected.push_back(std::move(scan));
  }
  return selected;
}

long kittiFrameNumber(const std::string& stem) {
  if (stem.empty() || stem.size() > 12) return -1;
  for (char c : stem)
    if (!std::isdigit(static_cast<unsigned char>(c))) return -1;
  const long n = std::stol(stem);
  return n <= std::numeric_limits<int>::max() ? n : -1;  // frame indices are ints
}

void checkFrameRange(const FrameRange& range) {
  if (range.stride < 1) throw InputError("frame stride must be >= 1");
  if (range.first < 0) throw InputError("first frame must be >= 0");
  if (range.last >= 0 && range.last < range.first)
    throw InputError("last frame " + std::to_string(range.last) + " is before first frame " +
                     std::to_string(range.first));
}

std::vector<double> parseKittiTimestamps(const std::string& text, const std::string& file) {
  std::vector<double> out;
  std::istringstream in(text);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    out.push_back(parseKittiTimestamp(line, file, "line " + std::to_string(n)));
  }
  return out;
}

double parseKittiTimestamp(const std::string& text, const std::string& file,
                           const std::string& field) {
  // YYYY-MM-DD HH:MM:SS[.fff...], every part digits only (no sign, no exponent, no "nan").
  auto bad = [&]() {
    throw ParseError(file, field, "not a timestamp 'YYYY-MM-DD HH:MM:SS.f': '" + text + "'");
  };
  std::size_t i = 0;
  auto digits = [&](std::size_t min_count, std::size_t max_count) {
    long v = 0;
    std::size_t count = 0;
    while (i < text.size() && count < max_count &&
           std::isdigit(static_cast<unsigned char>(text[i]))) {
      if (count < 9) v = v * 10 + (text[i] - '0');  // the fraction's value is not needed
      ++i;
      ++count;
    }
    if (count < min_count) bad();
    return v;
  };
  auto expect = [&](char c) {
    if (i >= text.size() || text[i] != c) bad();
    ++i;
  };
  digits(4, 4);
  expect('-');
  const long month = digits(1, 2);
  expect('-');
  const long day = digits(1, 2);
  expect(' ');
  const long h = digits(1, 2);
  expect(':');
  const long mi = digits(1, 2);
  expect(':');
  const std::size_t seconds_at = i;
  digits(1, 2);
  if (i < text.size() && text[i] == '.') {
    ++i;
    digits(1, 30);
  }
  if (i != text.size()) bad();
  const double s = std::strtod(text.c_str() + seconds_at, nullptr);
  if (month < 1 || month > 12 || day < 1 || day > 31 || h > 23 || mi > 59 || !(s < 61)) bad();
  return h * 3600.0 + mi * 60.0 + s;
}

KittiRawDrive openKittiRawDrive(const fs::path& drive_dir, const FrameRange& range) {
  checkFrameRange(range);
  if (isKittiSequence(drive_dir)) return openKittiSequence(drive_dir, range);
  KittiRawDrive drive;
  drive.dir = fs::absolute(drive_dir).lexically_normal();
  if (!drive.dir.has_filename()) drive.dir = drive.dir.parent_path();
  if (!fs::is_directory(drive.dir)) throw IoError(drive_dir.string(), "drive folder not found");
  drive.date_dir = drive.dir.parent_path();
  const fs::path velo_dir = drive.dir / "velodyne_points" / "data";
  const auto scans = listVelodyneScans(velo_dir, range);

  const auto stamps = readTimestamps(drive.dir / "velodyne_points" / "timestamps.txt");
  const auto starts = readTimestamps(drive.dir / "velodyne_points" / "timestamps_start.txt");
  const auto ends = readTimestamps(drive.dir / "velodyne_points" / "timestamps_end.txt");
  auto at = [](const std::vector<double>& v, long i) {
    return i < static_cast<long>(v.size()) ? v[static_cast<std::size_t>(i)] : std::nan("");
  };

  for (const auto& [n, path] : scans) {
    KittiRawFrame f;
    f.index = static_cast<int>(n);
    f.name = path.stem().string();
    f.velodyne = path;
    const fs::path img = drive.dir / "image_02" / "data" / (f.name + ".png");
    if (fs::exists(img)) f.image = img;
    const fs::path ox = drive.dir / "oxts" / "data" / (f.name + ".txt");
    if (fs::exists(ox)) f.oxts = ox;
    f.timestamp = at(stamps, n);
    f.scan_start = at(starts, n);
    f.scan_end = at(ends, n);
    drive.frames.push_back(f);
  }
  if (drive.frames.empty())
    throw InputError(drive.dir.string() + ": no frame in the selected range " +
                     std::to_string(range.first) + ".." + std::to_string(range.last));
  drive.has_oxts = std::all_of(drive.frames.begin(), drive.frames.end(),
                               [](const KittiRawFrame& f) { return !f.oxts.empty(); });
  drive.calib = readKittiCalibration(drive.date_dir);
  return drive;
}

geo::OxtsRecord readOxts(const KittiRawFrame& frame) {
  if (frame.oxts.empty())
    throw IoError(frame.velodyne.string(), "frame " + frame.name + " has no OXTS record");
  std::string text = readBytes(frame.oxts);
  const auto eol = text.find('\n');
  if (eol != std::string::npos) text.resize(eol);
  return io::parseOxtsLine(text, frame.oxts.string());
}

}  // namespace mapfuse::io
