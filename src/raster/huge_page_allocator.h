// An allocator that asks the kernel to back large buffers with 2 MB pages. A frame's buffers are
// megabytes each (an 800x640 float RGBA colour buffer 8 MB, a 2048² shadow map 16 MB) and are
// read and written all over: in 4 KB pages the address translations alone miss the TLB — a
// shadow lookup per fragment lands on a different page of the map, a lit pass walks the colour
// buffer row by row — and the frames measured 3-5 % slower. Blocks of at least kHugePageBlock
// bytes are aligned to 2 MB and advised MADV_HUGEPAGE (honoured where the kernel's transparent
// huge pages are "always" or "madvise"; elsewhere, and off Linux, they are plain blocks).
// Smaller ones come from std::allocator. Nothing about the bytes a frame computes changes.
#pragma once

#include <cstddef>
#include <memory>
#include <new>

namespace shadowref {

inline constexpr std::size_t kHugePageSize = std::size_t(2) << 20;
inline constexpr std::size_t kHugePageBlock = std::size_t(1) << 20;

// A block of `bytes` (at least kHugePageBlock), 2 MB-aligned and advised for huge pages; freed by
// freeHugePageBlock with the same size.
void* allocateHugePageBlock(std::size_t bytes);
void freeHugePageBlock(void* p, std::size_t bytes) noexcept;

template <class T>
struct HugePageAllocator : std::allocator<T> {
  using std::allocator<T>::allocator;
  template <class U>
  struct rebind {
    using other = HugePageAllocator<U>;
  };
  T* allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    if (n * sizeof(T) < kHugePageBlock) return std::allocator<T>::allocate(n);
    return static_cast<T*>(allocateHugePageBlock(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (n * sizeof(T) < kHugePageBlock) std::allocator<T>::deallocate(p, n);
    else freeHugePageBlock(p, n * sizeof(T));
  }
};

}  // namespace shadowref
