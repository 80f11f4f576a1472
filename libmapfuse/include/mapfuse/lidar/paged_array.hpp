#pragma once
/// @file An append-only array kept in fixed-size pages (2^PageBits elements each): growing never
/// moves or copies the elements already stored, so there is no moment where an old and a new
/// copy of the whole array coexist (std::vector's doubling peaks at up to 2x its size), and
/// indices stay stable. Element i is pages[i >> PageBits][i & (page size - 1)]. Only the first
/// page grows by doubling (small arrays stay small); later pages are allocated full.
#include <algorithm>
#include <cstddef>
#include <iterator>
#include <vector>

namespace mapfuse::lidar {

template <typename T, int PageBits = 16>
class PagedArray {
 public:
  static constexpr std::size_t kPageSize = std::size_t{1} << PageBits;  ///< elements per page

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  T& operator[](std::size_t i) { return pages_[i >> PageBits][i & (kPageSize - 1)]; }
  const T& operator[](std::size_t i) const { return pages_[i >> PageBits][i & (kPageSize - 1)]; }

  void push_back(const T& v) {
    const std::size_t p = size_ >> PageBits;
    if (p == pages_.size()) {
      pages_.emplace_back();
      if (p > 0) pages_.back().reserve(kPageSize);
    }
    std::vector<T>& page = pages_[p];
    if (page.size() == page.capacity())
      page.reserve(std::min(kPageSize, std::max<std::size_t>(16, 2 * page.capacity())));
    page.push_back(v);
    ++size_;
  }

  /// @brief Drops the elements from index n on (n <= size()) and the pages left empty.
  void truncate(std::size_t n) {
    if (n >= size_) return;
    pages_.resize(pagesFor(n));
    if (n & (kPageSize - 1)) pages_.back().resize(n & (kPageSize - 1));
    size_ = n;
  }

  /// @brief Allocates the pages for n elements up front.
  void reserve(std::size_t n) {
    const std::size_t np = pagesFor(n);
    if (pages_.size() < np) pages_.resize(np);
    for (std::size_t i = 0; i < np; ++i) pages_[i].reserve(std::min(kPageSize, n - i * kPageSize));
  }

  /// @brief Releases the pages beyond size() and the unused part of the last one (copies at
  /// most one page).
  void shrinkToFit() {
    pages_.resize(pagesFor(size_));
    if (!pages_.empty()) pages_.back().shrink_to_fit();
    pages_.shrink_to_fit();
  }

  /// @brief Elements that fit in the allocated pages.
  std::size_t capacity() const {
    std::size_t c = 0;
    for (const auto& p : pages_) c += p.capacity();
    return c;
  }

  class const_iterator {
   public:
    using iterator_category = std::forward_iterator_tag;
    using value_type = T;
    using difference_type = std::ptrdiff_t;
    using pointer = const T*;
    using reference = const T&;
    const_iterator(const PagedArray* a, std::size_t i) : a_(a), i_(i) {}
    reference operator*() const { return (*a_)[i_]; }
    pointer operator->() const { return &(*a_)[i_]; }
    const_iterator& operator++() {
      ++i_;
      return *this;
    }
    bool operator==(const const_iterator& o) const { return i_ == o.i_; }
    bool operator!=(const const_iterator& o) const { return i_ != o.i_; }

   private:
    const PagedArray* a_;
    std::size_t i_;
  };
  const_iterator begin() const { return {this, 0}; }
  const_iterator end() const { return {this, size_}; }

 private:
  static std::size_t pagesFor(std::size_t n) { return (n + kPageSize - 1) >> PageBits; }
  std::vector<std::vector<T>> pages_;
  std::size_t size_ = 0;
};

}  // namespace mapfuse::lidar
