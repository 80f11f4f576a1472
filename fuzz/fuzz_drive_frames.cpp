// A raw drive folder as lsm-build reads it (docs/formats-frames.md): the input holds, separated
// by "====" lines, frames.json, calibration.json, imu.csv, wheel.csv, gps.csv, frames.csv,
// observations.jsonl and truth_poses.csv; the target writes them into a scratch folder (a part
// the input lacks is absent) and reads the folder.
#include "fuzz_support.hpp"
#include "mapfuse/io/drive_frames.hpp"

using namespace mapfuse;

namespace {
const char* const kFiles[] = {"frames.json",        "calibration.json", "imu.csv",
                              "wheel.csv",          "gps.csv",          "frames.csv",
                              "observations.jsonl", "truth_poses.csv"};
constexpr std::size_t kCount = sizeof kFiles / sizeof kFiles[0];
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const auto parts = fuzz::splitParts(fuzz::bytesOf(data, size), kCount);
  const auto dir = fuzz::scratchDir() / "drive";
  std::filesystem::create_directories(dir);
  for (std::size_t i = 0; i < kCount; ++i) {
    std::error_code ec;
    std::filesystem::remove(dir / kFiles[i], ec);
    if (i < parts.size()) fuzz::writeFile(dir / kFiles[i], parts[i]);
  }
  io::DriveFrames d;
  // A file frames.json names but the input lacks is an I/O error (exit 4), as in a real folder.
  if (!fuzz::accepts([&] { d = io::readDriveFrames(dir); }, {ExitCode::kBadInput, ExitCode::kIo}))
    return 0;
  MAPFUSE_FUZZ_CHECK(!d.frames.empty());
  for (std::size_t i = 0; i < d.frames.size(); ++i) MAPFUSE_FUZZ_CHECK(d.frames[i].index == int(i));
  return 0;
}
