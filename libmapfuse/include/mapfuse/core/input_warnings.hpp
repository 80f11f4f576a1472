#pragma once
/// @file What a reader found untrustworthy but could still use (docs/formats.md "Map content
/// checks"): one entry per kind of fault, with its count and the first example, so that 80
/// records with the same quirk give one warning, not 80, and the summary can say so.
#include <map>
#include <string>

namespace mapfuse {

class InputWarnings {
 public:
  struct Entry {
    int count = 0;
    std::string first;  ///< the first example: file, element, value
  };

  /// @brief Counts one occurrence of `kind`; the first one's `example` is kept.
  void add(const std::string& kind, const std::string& example) {
    Entry& e = entries_[kind];
    if (e.count++ == 0) e.first = example;
  }
  /// @brief Adds every entry of `other` (counts summed, the first example kept).
  void merge(const InputWarnings& other) {
    for (const auto& [kind, e] : other.entries_) {
      Entry& mine = entries_[kind];
      if (mine.count == 0) mine.first = e.first;
      mine.count += e.count;
    }
  }
  int count(const std::string& kind) const {
    const auto it = entries_.find(kind);
    return it == entries_.end() ? 0 : it->second.count;
  }
  bool empty() const { return entries_.empty(); }
  const std::map<std::string, Entry>& entries() const { return entries_; }

 private:
  std::map<std::string, Entry> entries_;
};

}  // namespace mapfuse
