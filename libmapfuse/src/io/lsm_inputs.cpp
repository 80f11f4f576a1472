// Lists of LSM inputs (lsm_io.hpp): the same file or drive twice refused, files decoded side by
// side, outputs written with the inputs' names.
#include <filesystem>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/parallel_for.hpp"
#include "mapfuse/io/lsm_io.hpp"

namespace mapfuse::io {

void refuseSameFile(const std::vector<std::string>& files) {
  namespace fs = std::filesystem;
  for (std::size_t i = 0; i < files.size(); ++i)
    for (std::size_t j = 0; j < i; ++j) {
      std::error_code ec;
      if (files[i] == files[j] || fs::equivalent(files[i], files[j], ec))
        throw ConfigError("inputs " + files[j] + " and " + files[i] +
                          " are the same file (its data would count twice)");
    }
}

void refuseSameDrive(const std::vector<std::string>& files,
                     const std::vector<std::string>& drive_ids) {
  for (std::size_t i = 0; i < files.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (drive_ids[j] == drive_ids[i])
        throw ConfigError("inputs " + files[j] + " and " + files[i] + " hold the same drive '" +
                          drive_ids[i] + "' (its data would count twice)");
}

std::vector<Lsm> readLsmInputs(const std::vector<std::string>& files, bool covariances) {
  refuseSameFile(files);
  // Decoded side by side (the files are independent); errors reported as a serial read would,
  // the first file's first.
  std::vector<Lsm> lsms(files.size());
  parallelFor(files.size(), [&](std::size_t i) {
    lsms[i] = readLsm(files[i]);
    if (!covariances)
      for (Element& e : lsms[i].elements) std::vector<Eigen::Matrix3d>().swap(e.covariances);
  });
  std::vector<std::string> ids;
  for (const Lsm& l : lsms) ids.push_back(l.drive_id);
  refuseSameDrive(files, ids);
  return lsms;
}

void writeWithKeyframes(const std::vector<std::string>& inputs, std::vector<Lsm>& updated,
                        const std::filesystem::path& out_dir) {
  parallelFor(inputs.size(), [&](std::size_t i) {
    Lsm whole = readLsm(inputs[i]);
    whole.keyframes = std::move(updated[i].keyframes);
    std::vector<Element>().swap(updated[i].elements);
    writeLsm(out_dir / std::filesystem::path(inputs[i]).filename(), whole);
  });
}

}  // namespace mapfuse::io
