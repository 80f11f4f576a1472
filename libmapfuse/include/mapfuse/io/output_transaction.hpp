#pragma once
/// @file A run's outputs replaced as a set. While an OutputTransaction is open, every atomic
/// write (io/atomic_file.hpp) goes to its temporary file "<path>.tmp-<pid>" and stays there;
/// commit() renames them all onto their targets in the order they were written (so the file a
/// stage writes last, its summary, appears last: batch rules target it). A run that fails before
/// commit() removes its temporary files and leaves the previous outputs exactly as they were.
///
/// Opening a transaction also takes an advisory lock on the output folder (a second run on the
/// same folder is refused at once, exit 4, instead of mixing its files with the first one's),
/// checks that the folder can be created and written before any work starts, and removes the
/// temporary files that killed runs left there.
#include <filesystem>
#include <mutex>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace mapfuse::io {

class OutputTransaction {
 public:
  /// @brief Creates `folder` if needed, locks it and removes stale temporary files in it.
  /// @throws IoError (exit 4) when the folder cannot be created or written, or when another
  /// process holds its lock (the message names that process).
  explicit OutputTransaction(const std::filesystem::path& folder);
  /// @brief Without commit(): removes every staged temporary file (the previous outputs stay).
  ~OutputTransaction();
  OutputTransaction(const OutputTransaction&) = delete;
  OutputTransaction& operator=(const OutputTransaction&) = delete;

  /// @brief Renames every staged file onto its target, in write order. Checks first that no
  /// target is a folder, so a set is not left half replaced for a foreseeable reason.
  /// @throws IoError naming the file that cannot be replaced.
  void commit();

  /// @brief The open transaction of this process, or nullptr.
  static OutputTransaction* active();

  /// @brief Called by the atomic writers: `tmp` holds the finished content of `target`.
  void stage(const std::filesystem::path& tmp, const std::filesystem::path& target);

  /// @brief The staged temporary file holding `target`'s new content, or empty when `target`
  /// was not written in this transaction.
  std::filesystem::path stagedPath(const std::filesystem::path& target);

  const std::filesystem::path& folder() const { return folder_; }
  std::size_t staged() const { return files_.size(); }

 private:
  void rollback() noexcept;
  void removeWhatWasCreated() noexcept;
  std::filesystem::path folder_;
  int lock_fd_ = -1;
  bool done_ = false;
  bool committed_ = false;
  /// A run that ends without committing leaves the disk as it found it: the lock file it
  /// created, and the folders it created (outermost first), are removed again if empty.
  bool lock_created_ = false;
  std::filesystem::path created_root_;
  std::mutex mutex_;
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> files_;  // tmp, target
  std::unordered_map<std::string, std::size_t> index_;  // target -> its entry in files_
  OutputTransaction* outer_ = nullptr;
};

/// @brief Where the newest content of `target` is: its staged temporary file while the open
/// transaction holds it (e.g. to measure a file just written), else `target` itself.
std::filesystem::path contentPath(const std::filesystem::path& target);

/// @brief Removes "<name>.tmp-<pid>" files below `folder` whose process no longer runs.
/// @return how many were removed.
std::size_t removeStaleTemporaries(const std::filesystem::path& folder);

}  // namespace mapfuse::io
