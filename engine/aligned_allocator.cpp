#include "engine/aligned_allocator.hpp"

#include <new>

namespace gf {

void* allocate_aligned(std::size_t bytes, std::size_t align) { return ::operator new(bytes, std::align_val_t{align}); }

void free_aligned(void* p, std::size_t align) noexcept { ::operator delete(p, std::align_val_t{align}); }

}  // namespace gf
