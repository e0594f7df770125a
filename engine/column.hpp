// Aligned, padded column storage: the unit every table is made of.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include "engine/aligned_allocator.hpp"
#include "engine/intrinsics.hpp"

namespace gf {

// Columns are 64-byte aligned and padded to whole batches of this many elements, so a kernel
// may load a full xsimd batch at any row index that is a multiple of it without a bounds branch
// (engine/simd.hpp checks that the batch width divides it).
inline constexpr std::size_t kColumnPad = 8;

inline constexpr std::size_t padded_size(std::size_t n) {
  return (n + kColumnPad - 1) / kColumnPad * kColumnPad;
}

template <class T>
class Column {
 public:
  using value_type = T;

  Column() = default;
  explicit Column(std::size_t n, T fill = T{}) { resize(n, fill); }

  // Keeps the padding rows zero (or `fill`), so reductions over padded batches add nothing.
  void resize(std::size_t n, T fill = T{}) {
    data_.resize(padded_size(n), fill);
    for (std::size_t i = n; i < data_.size(); ++i) data_[i] = fill;
    n_ = n;
  }
  void assign(std::size_t n, T value) {
    data_.assign(padded_size(n), value);
    n_ = n;
  }
  void clear() { resize(0); }

  std::size_t size() const { return n_; }
  std::size_t padded() const { return data_.size(); }
  bool empty() const { return n_ == 0; }

  T* data() { return data_.data(); }
  const T* data() const { return data_.data(); }
  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }
  T* begin() { return data_.data(); }
  T* end() { return data_.data() + n_; }
  const T* begin() const { return data_.data(); }
  const T* end() const { return data_.data() + n_; }
  std::span<T> span() { return {data_.data(), n_}; }
  std::span<const T> span() const { return {data_.data(), n_}; }

  void push_back(T v) {
    resize(n_ + 1);
    data_[n_ - 1] = v;
  }

  // Reorders rows so that new row r holds old row perm[r]. The old storage becomes this thread's
  // scratch for the next permutation of a column of the same type, so steady state allocates nothing.
  void permute(std::span<const std::uint32_t> perm) {
    static thread_local std::vector<T, AlignedAllocator<T, 64>> scratch;
    scratch.resize(data_.size());
    for (std::size_t r = 0; r < perm.size(); ++r) scratch[r] = data_[perm[r]];
    for (std::size_t r = perm.size(); r < data_.size(); ++r) scratch[r] = T{};
    data_.swap(scratch);
  }

  std::size_t bytes() const { return data_.capacity() * sizeof(T); }

 private:
  std::vector<T, AlignedAllocator<T, 64>> data_;
  std::size_t n_ = 0;
};

using ColumnD = Column<double>;

}  // namespace gf
