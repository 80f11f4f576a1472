#include "mapfuse/io/output_transaction.hpp"

#include <cctype>

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "mapfuse/core/error.hpp"

namespace mapfuse::io {

namespace fs = std::filesystem;

namespace {
std::atomic<OutputTransaction*> g_active{nullptr};
constexpr const char* kLockName = ".mapfuse.lock";

/// The pid of a "<name>.tmp-<pid>" file, or 0.
long tempOwner(const fs::path& p) {
  const std::string name = p.filename().string();
  const auto at = name.rfind(".tmp-");
  if (at == std::string::npos || at + 5 >= name.size()) return 0;
  // "<name>.tmp-<pid>", or "<name>.tmp-<pid>.<ext>" for writers that pick their format by the
  // extension (OpenCV's forests: "rtrees_<class>.yml.tmp-<pid>.yml")
  long pid = 0;
  std::size_t i = at + 5;
  for (; i < name.size() && name[i] != '.'; ++i) {
    if (name[i] < '0' || name[i] > '9' || pid > 100000000) return 0;
    pid = pid * 10 + (name[i] - '0');
  }
  if (i == at + 5) return 0;
  if (i < name.size()) {  // an extension: letters only
    if (i + 1 == name.size()) return 0;
    for (std::size_t j = i + 1; j < name.size(); ++j)
      if (!std::isalpha(static_cast<unsigned char>(name[j]))) return 0;
  }
  return pid;
}

bool processRuns(long pid) {
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}
}  // namespace

/// Absolute, normal, without a trailing separator (so that parent_path() goes up).
fs::path normalFolder(const fs::path& folder) {
  std::error_code ec;
  fs::path p = fs::absolute(folder, ec).lexically_normal();
  if (p.filename().empty() && p.has_parent_path()) p = p.parent_path();
  return p;
}

std::size_t removeStaleTemporaries(const fs::path& folder) {
  std::size_t removed = 0;
  std::error_code ec;
  for (fs::recursive_directory_iterator
           it(folder, fs::directory_options::skip_permission_denied, ec),
       end;
       !ec && it != end; it.increment(ec)) {
    if (!it->is_regular_file(ec)) continue;
    const long pid = tempOwner(it->path());
    if (pid <= 0 || pid == ::getpid() || processRuns(pid)) continue;
    std::error_code rm;
    if (fs::remove(it->path(), rm)) ++removed;
  }
  return removed;
}

OutputTransaction::OutputTransaction(const fs::path& folder) : folder_(folder) {
  if (g_active.load() != nullptr)
    throw std::logic_error("an output transaction is already open in this process");
  std::error_code ec;
  for (fs::path p = normalFolder(folder_); !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    created_root_ = p;
    if (p == p.parent_path()) break;
  }
  fs::create_directories(folder_, ec);
  if (ec || !fs::is_directory(folder_))
    throw IoError(folder_.string(),
                  "cannot create the output folder: " +
                      (ec ? ec.message() : std::string("a file of that name is in the way")));
  const fs::path lock = folder_ / kLockName;
  lock_created_ = !fs::exists(lock, ec);
  lock_fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock_fd_ < 0) {
    const std::string why = std::strerror(errno);
    lock_created_ = false;
    removeWhatWasCreated();
    throw IoError(folder_.string(), "output folder is not writable: " + why);
  }
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    char owner[32] = {0};
    const ssize_t n = ::pread(lock_fd_, owner, sizeof owner - 1, 0);
    ::close(lock_fd_);
    lock_fd_ = -1;
    lock_created_ = false;  // the other run's
    throw IoError(folder_.string(),
                  "another mapfuse run is writing this output folder" +
                      (n > 0 ? " (pid " + std::string(owner, static_cast<std::size_t>(n)) + ")"
                             : std::string()) +
                      "; wait for it to finish or choose another folder");
  }
  const std::string pid = std::to_string(::getpid());
  if (::ftruncate(lock_fd_, 0) != 0 || ::pwrite(lock_fd_, pid.data(), pid.size(), 0) < 0) {
    const std::string why = std::strerror(errno);
    ::close(lock_fd_);
    lock_fd_ = -1;
    removeWhatWasCreated();
    throw IoError(lock.string(), "cannot write: " + why);
  }
  removeStaleTemporaries(folder_);
  g_active.store(this);
}

OutputTransaction::~OutputTransaction() {
  if (!done_) rollback();
  if (g_active.load() == this) g_active.store(nullptr);
  if (!committed_) removeWhatWasCreated();  // while still holding the lock
  if (lock_fd_ >= 0) ::close(lock_fd_);     // releases the lock
}

void OutputTransaction::removeWhatWasCreated() noexcept {
  std::error_code ec;
  if (lock_created_) fs::remove(folder_ / kLockName, ec);
  lock_created_ = false;
  if (created_root_.empty()) return;
  // fs::remove only removes empty folders: from the output folder up to the outermost created
  for (fs::path p = normalFolder(folder_);; p = p.parent_path()) {
    if (!fs::remove(p, ec) || p == created_root_ || p == p.parent_path()) break;
  }
  created_root_.clear();
}

OutputTransaction* OutputTransaction::active() {
  return g_active.load();
}

void OutputTransaction::stage(const fs::path& tmp, const fs::path& target) {
  std::lock_guard<std::mutex> guard(mutex_);
  const auto [at, fresh] = index_.emplace(target.lexically_normal().string(), files_.size());
  if (!fresh) {  // written again: the newer content counts
    auto& f = files_[at->second];
    if (f.first != tmp) {
      std::error_code ec;
      fs::remove(f.first, ec);
      f.first = tmp;
    }
    return;
  }
  files_.emplace_back(tmp, target);
}

fs::path OutputTransaction::stagedPath(const fs::path& target) {
  std::lock_guard<std::mutex> guard(mutex_);
  for (const auto& f : files_)
    if (f.second == target) return f.first;
  return {};
}

fs::path contentPath(const fs::path& target) {
  if (OutputTransaction* t = OutputTransaction::active()) {
    fs::path staged = t->stagedPath(target);
    if (!staged.empty()) return staged;
  }
  return target;
}

void OutputTransaction::commit() {
  std::lock_guard<std::mutex> guard(mutex_);
  if (done_) return;
  for (const auto& [tmp, target] : files_) {
    std::error_code ec;
    if (fs::is_directory(target, ec)) {
      const std::string name = target.string();  // rollback() clears files_
      rollback();
      throw IoError(name,
                    "is a folder; cannot replace it with a file (no output of "
                    "this run was written)");
    }
  }
  for (const auto& [tmp, target] : files_) {
    std::error_code ec;
    fs::rename(tmp, target, ec);
    if (ec) {
      const std::string name = target.string();
      rollback();
      throw IoError(name, "cannot rename temporary file: " + ec.message());
    }
  }
  files_.clear();
  index_.clear();
  done_ = true;
  committed_ = true;
  g_active.store(nullptr);
}

void OutputTransaction::rollback() noexcept {
  for (const auto& f : files_) {
    std::error_code ec;
    fs::remove(f.first, ec);
  }
  files_.clear();
  index_.clear();
  done_ = true;
}

}  // namespace mapfuse::io
