#include "memory/pixel_memory.h"

#include <cstdint>
#include <cstring>
#include <mutex>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#if defined(__SANITIZE_ADDRESS__)
#define SHADOWREF_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SHADOWREF_ASAN 1
#endif
#endif
#if defined(SHADOWREF_ASAN)
#include <sanitizer/asan_interface.h>
#else
#define ASAN_POISON_MEMORY_REGION(addr, size) ((void)(addr), (void)(size))
#define ASAN_UNPOISON_MEMORY_REGION(addr, size) ((void)(addr), (void)(size))
#endif

namespace shadowref {

namespace {

#if defined(SHADOWREF_ASAN)
// Under AddressSanitizer a block keeps at least this many poisoned bytes after the requested
// ones, so that a write past a buffer's end is reported as it is for the C heap's blocks.
constexpr std::size_t kGuardBytes = 64;
// Under AddressSanitizer every block handed out is filled with this byte first: a read of a pixel
// before its clear wrote it then changes the frame (and the golden hashes of the sanitizer build
// fail) instead of reading whatever the previous frame left.
constexpr int kUnwrittenByte = 0xA5;
#else
constexpr std::size_t kGuardBytes = 0;
#endif

std::size_t mappedSize(std::size_t bytes) {
  return (bytes + kGuardBytes + kHugePageSize - 1) / kHugePageSize * kHugePageSize;
}

void* mapBlock(std::size_t size) {
#if defined(__linux__)
  // Map 2 MB more than asked and cut the ends off, so that the block starts on a 2 MB boundary:
  // only an aligned 2 MB range can be one huge page.
  const std::size_t span = size + kHugePageSize;
  void* mapped = mmap(nullptr, span, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (mapped == MAP_FAILED) throw std::bad_alloc();
  char* const first = static_cast<char*>(mapped);
  const std::uintptr_t start = (reinterpret_cast<std::uintptr_t>(first) + kHugePageSize - 1) & ~(kHugePageSize - 1);
  char* const block = reinterpret_cast<char*>(start);
  if (block > first) munmap(first, std::size_t(block - first));
  char* const end = block + size;
  if (first + span > end) munmap(end, std::size_t(first + span - end));
#if defined(MADV_HUGEPAGE)
  // Advice only: a kernel without transparent huge pages refuses it, and the block stays as it is.
  (void)madvise(block, size, MADV_HUGEPAGE);
#endif
  return block;
#else
  return ::operator new(size, std::align_val_t(kHugePageSize));
#endif
}

void unmapBlock(void* block, std::size_t size) noexcept {
#if defined(__linux__)
  munmap(block, size);
#else
  ::operator delete(block, size, std::align_val_t(kHugePageSize));
#endif
}

struct KeptBlock {
  void* block;
  std::size_t size;
};

class PixelPool {
 public:
  void* take(std::size_t size) {
    {
      std::lock_guard lock(mutex_);
      // The most recently freed block of the size first: the likeliest to be in the caches still.
      for (std::size_t i = kept_.size(); i-- > 0;) {
        if (kept_[i].size != size) continue;
        void* block = kept_[i].block;
        kept_.erase(kept_.begin() + std::ptrdiff_t(i));
        bytesKept_ -= size;
        return block;
      }
    }
    void* block = mapBlock(size);
    std::lock_guard lock(mutex_);
    ++blocksMapped_;
    return block;
  }

  void give(void* block, std::size_t size) noexcept {
    {
      std::lock_guard lock(mutex_);
      if (bytesKept_ + size <= kPixelMemoryKept) {
        try {
          kept_.push_back({block, size});
          bytesKept_ += size;
          return;
        } catch (...) {
          // No memory for the list's entry: unmap the block instead.
        }
      }
    }
    ASAN_UNPOISON_MEMORY_REGION(block, size);  // the next mapping at this address starts clean
    unmapBlock(block, size);
  }

  PixelMemoryCounts counts() {
    std::lock_guard lock(mutex_);
    return {blocksMapped_, kept_.size(), bytesKept_};
  }

 private:
  std::mutex mutex_;
  std::vector<KeptBlock> kept_;
  std::size_t bytesKept_ = 0;
  std::size_t blocksMapped_ = 0;
};

// Never destroyed: buffers of static objects may be freed after every other static is gone.
PixelPool& pool() {
  static PixelPool* const p = new PixelPool;
  return *p;
}

}  // namespace

void* takePixelBlock(std::size_t bytes) {
  const std::size_t size = mappedSize(bytes);
  void* block = pool().take(size);
#if defined(SHADOWREF_ASAN)
  ASAN_UNPOISON_MEMORY_REGION(block, bytes);
  std::memset(block, kUnwrittenByte, bytes);
  ASAN_POISON_MEMORY_REGION(static_cast<char*>(block) + bytes, size - bytes);
#endif
  return block;
}

void returnPixelBlock(void* block, std::size_t bytes) noexcept {
  const std::size_t size = mappedSize(bytes);
  ASAN_POISON_MEMORY_REGION(block, size);  // a kept block is not to be touched until taken again
  pool().give(block, size);
}

PixelMemoryCounts pixelMemoryCounts() { return pool().counts(); }

}  // namespace shadowref
