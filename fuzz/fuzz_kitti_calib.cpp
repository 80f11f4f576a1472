// A KITTI raw date folder's calibration: calib_cam_to_cam.txt, calib_velo_to_cam.txt and
// (optional) calib_imu_to_velo.txt, as three parts of the input separated by "====" lines; and
// lsm-build's camera built from it.
#include "fuzz_support.hpp"
#include "mapfuse/io/bounds.hpp"
#include "mapfuse/io/kitti_calib.hpp"

using namespace mapfuse;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const auto parts = fuzz::splitParts(fuzz::bytesOf(data, size), 3);
  io::KittiCalibration c;
  if (!fuzz::accepts([&] {
        const auto cam = io::KittiCalibFile::parse(parts[0], "calib_cam_to_cam.txt");
        const auto velo =
            io::KittiCalibFile::parse(parts.size() > 1 ? parts[1] : "", "calib_velo_to_cam.txt");
        if (parts.size() > 2) {
          const auto imu = io::KittiCalibFile::parse(parts[2], "calib_imu_to_velo.txt");
          c = io::kittiCalibrationFromFiles(cam, velo, &imu);
        } else {
          c = io::kittiCalibrationFromFiles(cam, velo, nullptr);
        }
      }))
    return 0;
  MAPFUSE_FUZZ_CHECK(c.image_width >= 1 && c.image_height >= 1);
  MAPFUSE_FUZZ_CHECK(int64_t(c.image_width) * c.image_height <= io::bounds::kMaxImagePixels);
  MAPFUSE_FUZZ_CHECK(c.veloToImage2().allFinite());
  MAPFUSE_FUZZ_CHECK(c.P_rect_02.leftCols<3>().determinant() != 0.0);
  return 0;
}
