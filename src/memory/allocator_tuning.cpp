#include "memory/allocator_tuning.h"

#include <cstdlib>  // any libc header: it defines __GLIBC__ on glibc
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace shadowref {

void keepFreedMemoryForReuse() {
#if defined(__GLIBC__)
  // Serve large blocks from the heap instead of mmap, and do not give the heap's top back to the
  // kernel, so the next frame's buffers are the last frame's memory.
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

}  // namespace shadowref
