// Where a frame's large pixel buffers live: in 2 MB pages, kept from one frame for the next.
//
// A frame's buffers are megabytes each (an 800x640 float RGBA colour buffer 8 MB, a 2048² shadow
// map 16 MB) and are read and written all over: in 4 KB pages the address translations alone
// miss the TLB — each shadow lookup lands on another page of the map. Blocks of at least
// kPixelBlockMin bytes are therefore mapped 2 MB-aligned and advised MADV_HUGEPAGE (honoured
// where the kernel's transparent huge pages are "always" or "madvise"; elsewhere they are plain
// pages). A freed block is not given back to the kernel but kept, up to kPixelMemoryKept bytes,
// and handed to the next request of the same size: a renderer that draws frame after frame
// reuses the pages it has, on any thread. (Round 12 advised huge pages on blocks from the C
// heap: freed by a worker thread's arena they went back to the kernel, and two threads faulted
// in fresh 2 MB pages every frame.)
//
// Only where the memory comes from changes: the bytes a frame computes do not (every byte of a
// pixel buffer is written by its clear before anything reads it, clear.h).
#pragma once

#include <cstddef>
#include <memory>
#include <new>

namespace shadowref {

inline constexpr std::size_t kHugePageSize = std::size_t(2) << 20;
// Smaller buffers (a 160x128 test frame, a stencil of 800x640) come from the C heap.
inline constexpr std::size_t kPixelBlockMin = std::size_t(1) << 20;
// The most bytes of freed blocks kept for reuse; a block freed beyond it is unmapped.
inline constexpr std::size_t kPixelMemoryKept = std::size_t(512) << 20;

// A block for `bytes` (at least kPixelBlockMin): 2 MB-aligned, a reused one where a block of the
// same size in 2 MB pages was freed before. Throws std::bad_alloc when no memory is left.
void* takePixelBlock(std::size_t bytes);
// Gives the block back (the same `bytes` it was taken with), to be kept or unmapped.
void returnPixelBlock(void* block, std::size_t bytes) noexcept;

// What the pool holds now, for tests and diagnostics.
struct PixelMemoryCounts {
  std::size_t blocksMapped = 0;  // blocks ever mapped (a reused block is not mapped again)
  std::size_t blocksKept = 0;    // freed blocks waiting for reuse
  std::size_t bytesKept = 0;
};
PixelMemoryCounts pixelMemoryCounts();

// The allocator of pixel buffers: blocks of kPixelBlockMin bytes and more from the pool above,
// smaller ones from std::allocator.
template <class T>
struct PixelAllocator : std::allocator<T> {
  using std::allocator<T>::allocator;
  template <class U>
  struct rebind {
    using other = PixelAllocator<U>;
  };
  T* allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    if (n * sizeof(T) < kPixelBlockMin) return std::allocator<T>::allocate(n);
    return static_cast<T*>(takePixelBlock(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (n * sizeof(T) < kPixelBlockMin) std::allocator<T>::deallocate(p, n);
    else returnPixelBlock(p, n * sizeof(T));
  }
};

}  // namespace shadowref
