// HugePageAllocator: large blocks aligned to 2 MB (so that whole huge pages can back them), small
// ones as std::allocator gives them, and the pixel buffers built on it behave as vectors do.
#include <cstdint>
#include <vector>

#include <catch2/catch.hpp>

#include "raster/framebuffer.h"
#include "raster/huge_page_allocator.h"

using namespace shadowref;

TEST_CASE("blocks of a megabyte and more start on a 2 MB boundary, and are usable to their end", "[raster]") {
  HugePageAllocator<uint32_t> alloc;
  for (size_t bytes : {size_t(1) << 20, (size_t(3) << 20) + 12, size_t(16) << 20}) {
    const size_t n = bytes / sizeof(uint32_t);
    uint32_t* p = alloc.allocate(n);
    CHECK(reinterpret_cast<uintptr_t>(p) % kHugePageSize == 0);
    p[0] = 1;
    p[n - 1] = 2;  // the last element is ours (ASan would object otherwise)
    CHECK(p[0] + p[n - 1] == 3);
    alloc.deallocate(p, n);
  }
  // Below the threshold: an ordinary block (alignment as operator new gives it, nothing more).
  uint32_t* small = alloc.allocate(16);
  small[15] = 7;
  CHECK(small[15] == 7);
  alloc.deallocate(small, 16);
}

TEST_CASE("a pixel buffer in huge pages keeps its values through growth and copies", "[raster]") {
  PixelVector<uint32_t> v;
  v.assign(100, 5u);
  v.resize(size_t(1) << 20, 9u);  // 4 MB: moved into a huge-page block
  CHECK(reinterpret_cast<uintptr_t>(v.data()) % kHugePageSize == 0);
  CHECK(v[99] == 5u);
  CHECK(v[100] == 9u);
  const PixelVector<uint32_t> copy = v;
  CHECK(copy == v);
  v.resize(10);
  v.shrink_to_fit();  // back below the threshold: an ordinary block
  CHECK(v[9] == 5u);
}
