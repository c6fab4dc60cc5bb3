// A vector with a fixed capacity stored inline: no heap allocation, trivially copyable for
// trivially copyable T. For small per-step records (one entry per wheel) that hot loops fill and
// snapshots copy.
#pragma once

#include <array>
#include <cstddef>

#include "vb/engine/error.h"

namespace vb {

template <typename T, size_t kCapacity>
class FixedVector {
 public:
  FixedVector() = default;
  FixedVector(std::initializer_list<T> values) {
    for (const T& v : values) push_back(v);
  }
  static constexpr size_t capacity() { return kCapacity; }
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  void clear() { size_ = 0; }
  void push_back(const T& v) {
    VB_DEMAND(size_ < kCapacity);
    data_[size_++] = v;
  }
  void resize(size_t n, const T& fill = T()) {
    VB_DEMAND(n <= kCapacity);
    for (size_t i = size_; i < n; ++i) data_[i] = fill;
    size_ = n;
  }
  T& operator[](size_t i) { return data_[i]; }
  const T& operator[](size_t i) const { return data_[i]; }
  T* begin() { return data_.data(); }
  T* end() { return data_.data() + size_; }
  const T* begin() const { return data_.data(); }
  const T* end() const { return data_.data() + size_; }
  bool operator==(const FixedVector& o) const {
    if (size_ != o.size_) return false;
    for (size_t i = 0; i < size_; ++i)
      if (!(data_[i] == o.data_[i])) return false;
    return true;
  }
  bool operator!=(const FixedVector& o) const { return !(*this == o); }

 private:
  std::array<T, kCapacity> data_{};
  size_t size_ = 0;
};

}  // namespace vb
