#include "raster/allocator_tuning.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace shadowref {

void keepFreedMemoryForReuse() {
#if defined(__GLIBC__)
  // Serve large blocks from the heap instead of mmap, and never give the heap's top back.
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

}  // namespace shadowref
