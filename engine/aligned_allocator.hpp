// A standard allocator whose blocks start on an `Align`-byte boundary (C++17 aligned new), for the
// columns' storage. It keeps xsimd out of every file that holds a column: only the kernels include
// engine/simd.hpp, which costs about a second and a half of compile time per file at -march=native.
#pragma once

#include <cstddef>

namespace gf {

// `bytes` on an `align`-byte boundary (std::bad_alloc when there is no room), and its release. Out of
// line on purpose: GCC 12 follows an inlined aligned operator new's size into std::vector's growth of
// byte columns and reports writes past it that cannot happen (-Wstringop-overflow, a false positive).
void* allocate_aligned(std::size_t bytes, std::size_t align);
void free_aligned(void* p, std::size_t align) noexcept;

template <class T, std::size_t Align>
struct AlignedAllocator {
  static_assert(Align >= alignof(T) && (Align & (Align - 1)) == 0, "alignment must be a power of two");
  using value_type = T;
  template <class U>
  struct rebind {
    using other = AlignedAllocator<U, Align>;
  };

  AlignedAllocator() noexcept = default;
  template <class U>
  AlignedAllocator(const AlignedAllocator<U, Align>&) noexcept {}

  T* allocate(std::size_t n) { return static_cast<T*>(allocate_aligned(n * sizeof(T), Align)); }
  void deallocate(T* p, std::size_t) noexcept { free_aligned(p, Align); }

  template <class U>
  bool operator==(const AlignedAllocator<U, Align>&) const noexcept {
    return true;
  }
};

}  // namespace gf
