#include "raster/huge_page_allocator.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace shadowref {

namespace {
std::size_t roundUpToHugePages(std::size_t bytes) { return (bytes + kHugePageSize - 1) / kHugePageSize * kHugePageSize; }
}  // namespace

void* allocateHugePageBlock(std::size_t bytes) {
  const std::size_t size = roundUpToHugePages(bytes);
  void* p = ::operator new(size, std::align_val_t(kHugePageSize));
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // Advice only: a kernel without transparent huge pages refuses it, and the block stays as it is.
  (void)madvise(p, size, MADV_HUGEPAGE);
#endif
  return p;
}

void freeHugePageBlock(void* p, std::size_t bytes) noexcept {
  ::operator delete(p, roundUpToHugePages(bytes), std::align_val_t(kHugePageSize));
}

}  // namespace shadowref
