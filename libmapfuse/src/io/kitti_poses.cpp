#include "mapfuse/io/kitti_poses.hpp"

#include <Eigen/SVD>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/bounds.hpp"

namespace mapfuse::io {

std::vector<Pose3> readKittiOdometryPoses(const std::filesystem::path& path) {
  return parseKittiOdometryPoses(readBytes(path), path.string());
}

std::vector<Pose3> parseKittiOdometryPoses(const std::string& text, const std::string& file) {
  std::istringstream in(text);
  std::vector<Pose3> poses;
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    std::istringstream ls(line);
    std::vector<double> v;
    std::string tok;
    while (ls >> tok) {
      try {
        std::size_t used = 0;
        v.push_back(std::stod(tok, &used));
        if (used != tok.size() || !std::isfinite(v.back())) throw std::invalid_argument(tok);
      } catch (const std::exception&) {
        throw ParseError(file, "line " + std::to_string(n), "not a number: '" + tok + "'");
      }
    }
    if (v.empty()) continue;
    if (v.size() != 12)
      throw ParseError(file, "line " + std::to_string(n),
                       "has " + std::to_string(v.size()) + " numbers, expected 12");
    Eigen::Matrix3d R;
    R << v[0], v[1], v[2], v[4], v[5], v[6], v[8], v[9], v[10];
    if ((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-3 ||
        !(R.determinant() > 0))
      throw ParseError(
          file, "line " + std::to_string(n),
          "rotation is not orthonormal with det +1 (det " + std::to_string(R.determinant()) + ")");
    Pose3 T = Pose3::Identity();
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
    T.linear() = svd.matrixU() * svd.matrixV().transpose();
    T.translation() = Eigen::Vector3d(v[3], v[7], v[11]);
    if (T.translation().cwiseAbs().maxCoeff() > bounds::kMaxCoordinate)
      throw ParseError(file, "line " + std::to_string(n),
                       "translation outside " +
                           bounds::rangeText(-bounds::kMaxCoordinate, bounds::kMaxCoordinate) +
                           " m");
    poses.push_back(T);
  }
  if (poses.empty()) throw ParseError(file, "", "no poses");
  return poses;
}

void writeKittiOdometryPoses(const std::filesystem::path& path, const std::vector<Pose3>& poses) {
  std::string out;
  char buf[64];
  for (const Pose3& T : poses) {
    const Eigen::Matrix4d m = T.matrix();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) {
        std::snprintf(buf, sizeof buf, "%s%.12e", (r == 0 && c == 0) ? "" : " ", m(r, c));
        out += buf;
      }
    out += "\n";
  }
  writeBytesAtomic(path, out);
}

}  // namespace mapfuse::io
