#include "mapfuse/io/atomic_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/output_transaction.hpp"

namespace mapfuse::io {
namespace {
/// Largest file readBytes reads whole [bytes]: a cap so that a mistaken path (a disk image, a
/// huge log) fails at once naming the file instead of exhausting memory (exit 1).
constexpr std::uintmax_t kMaxReadBytes = std::uintmax_t(4) << 30;
}  // namespace

void writeFileAtomic(const std::filesystem::path& path,
                     const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (path.has_parent_path()) {
    fs::create_directories(path.parent_path(), ec);
    if (ec) throw IoError(path.parent_path().string(), "cannot create folder: " + ec.message());
  }
  const fs::path tmp = path.string() + ".tmp-" + std::to_string(::getpid());
  try {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw IoError(tmp.string(), std::string("cannot create: ") + std::strerror(errno));
    write(out);
    out.flush();
    if (!out) throw IoError(tmp.string(), "write failed (disk full?)");
    out.close();
    if (OutputTransaction* tx = OutputTransaction::active()) {
      tx->stage(tmp, path);  // renamed with the rest of the run's outputs at commit
      return;
    }
    fs::rename(tmp, path, ec);
    if (ec) throw IoError(path.string(), "cannot rename temporary file: " + ec.message());
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
}

void writeBytesAtomic(const std::filesystem::path& path, const std::string& bytes) {
  writeFileAtomic(path, [&](std::ostream& out) { out.write(bytes.data(), bytes.size()); });
}

std::string readBytes(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw IoError(path.string(), "is a folder, not a file");
  // /dev/zero or a FIFO would be read without end (2.1 GB, then "out of memory", exit 1).
  if (fs::exists(path, ec) && !fs::is_regular_file(path, ec))
    throw IoError(path.string(), "is not a regular file (a device or pipe); give a file");
  if (const auto size = fs::file_size(path, ec); !ec && size > kMaxReadBytes)
    throw IoError(path.string(), "is " + std::to_string(size >> 20) + " MiB, more than the " +
                                     std::to_string(kMaxReadBytes >> 20) +
                                     " MiB a mapfuse document may hold");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path.string(), std::string("cannot open: ") + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw IoError(path.string(), "read failed");
  return ss.str();
}

}  // namespace mapfuse::io
