// The simulator's calibration.json (docs/formats-frames.md), read by lsm-build.
#include "fuzz_support.hpp"
#include "mapfuse/io/bounds.hpp"
#include "mapfuse/io/camera_calib.hpp"
#include "mapfuse/io/document.hpp"

using namespace mapfuse;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string bytes = fuzz::bytesOf(data, size);
  CameraCalib c;
  if (!fuzz::accepts([&] {
        c = io::cameraCalibFromJson(
            io::parseDocument(bytes, io::Encoding::kJson, "calibration.json"), "calibration.json");
      }))
    return 0;
  MAPFUSE_FUZZ_CHECK(int64_t(c.width) * c.height <= io::bounds::kMaxImagePixels);
  MAPFUSE_FUZZ_CHECK(c.K.allFinite() && c.T_body_cam.matrix().allFinite());
  return 0;
}
