// The pixel buffers' memory (pixel_memory.h): 2 MB-aligned blocks, kept when freed and handed to
// the next request of the same size — on any thread — and frames that do not depend on what a
// reused block held before.
#include <cstdint>
#include <cstring>
#include <thread>
#include <vector>

#include <catch2/catch.hpp>

#include "gl/framebuffer.h"
#include "memory/pixel_memory.h"
#include "shadow/frame_renderer.h"
#include "support/frame_compare.h"
#include "support/generated_scene.h"

using namespace shadowref;

namespace {

bool alignedToHugePage(const void* p) { return reinterpret_cast<std::uintptr_t>(p) % kHugePageSize == 0; }

}  // namespace

TEST_CASE("pixel blocks are 2 MB-aligned and every requested byte can be written", "[raster][memory]") {
  for (const std::size_t bytes : {kPixelBlockMin, kHugePageSize - 8, kHugePageSize, 3 * kHugePageSize + 12345}) {
    INFO(bytes << " bytes");
    auto* block = static_cast<unsigned char*>(takePixelBlock(bytes));
    CHECK(alignedToHugePage(block));
    std::memset(block, 0x5C, bytes);
    CHECK(block[0] == 0x5C);
    CHECK(block[bytes - 1] == 0x5C);
    returnPixelBlock(block, bytes);
  }
}

TEST_CASE("a freed pixel block is handed to the next request of its size, not mapped again", "[raster][memory]") {
  const std::size_t bytes = 5 * kHugePageSize + 100;
  void* first = takePixelBlock(bytes);
  returnPixelBlock(first, bytes);
  const PixelMemoryCounts before = pixelMemoryCounts();
  void* second = takePixelBlock(bytes);
  CHECK(second == first);
  CHECK(pixelMemoryCounts().blocksMapped == before.blocksMapped);
  CHECK(pixelMemoryCounts().blocksKept == before.blocksKept - 1);
  // Another size in the same 2 MB pages takes the same block too; one needing more pages does not.
  returnPixelBlock(second, bytes);
  const std::size_t sameBytes = 6 * kHugePageSize - 4096, largerBytes = 6 * kHugePageSize + 1;
  void* sameSize = takePixelBlock(sameBytes);
  CHECK(sameSize == first);
  void* larger = takePixelBlock(largerBytes);
  CHECK(larger != first);
  CHECK(pixelMemoryCounts().blocksMapped == before.blocksMapped + 1);
  returnPixelBlock(sameSize, sameBytes);
  returnPixelBlock(larger, largerBytes);
}

TEST_CASE("a pixel block freed on another thread is reused on this one", "[raster][memory]") {
  // Round 12's huge pages came from the C heap: a block freed by a worker went back to the kernel
  // and the next frame faulted in fresh pages. The pool is one for the process.
  const std::size_t bytes = 3 * kHugePageSize;
  void* block = nullptr;
  std::thread([&] { block = takePixelBlock(bytes); }).join();
  std::thread([&] { returnPixelBlock(block, bytes); }).join();
  const std::size_t mapped = pixelMemoryCounts().blocksMapped;
  void* again = takePixelBlock(bytes);
  CHECK(again == block);
  CHECK(pixelMemoryCounts().blocksMapped == mapped);
  returnPixelBlock(again, bytes);
}

TEST_CASE("the pool keeps at most kPixelMemoryKept bytes of freed blocks", "[raster][memory]") {
  const std::size_t bytes = 64 * kHugePageSize;  // 128 MB: five of them exceed the 512 MB kept
  std::vector<void*> blocks;
  for (int i = 0; i < 6; ++i) blocks.push_back(takePixelBlock(bytes));
  for (void* b : blocks) returnPixelBlock(b, bytes);
  const PixelMemoryCounts counts = pixelMemoryCounts();
  CHECK(counts.bytesKept <= kPixelMemoryKept);
  CHECK(counts.bytesKept >= kPixelMemoryKept - bytes);  // all that fit were kept
}

TEST_CASE("pixel vectors of a megabyte and more live in pool blocks, smaller ones on the heap", "[raster][memory]") {
  PixelVector<glm::vec4> large;
  large.resize(kPixelBlockMin / sizeof(glm::vec4));
  CHECK(alignedToHugePage(large.data()));
  PixelVector<uint8_t> small;
  small.resize(4096);
  small[4095] = 7;
  CHECK(small[4095] == 7);
}

TEST_CASE("frames drawn into reused blocks do not depend on what the blocks held", "[raster][memory][determinism]") {
  // The room, then the outdoor scene with a shadow map into the same blocks, then the room again:
  // a pixel read before its clear wrote it would bring the outdoor frame's bytes into the room's.
  // A second frame of the same scene maps no new blocks: the pages are the first frame's.
#if defined(__SANITIZE_ADDRESS__)
  const int size = 256;  // the colour buffer (1 MB) and the shadow map come from the pool
#else
  const int size = 512;  // the colour (4 MB) and depth (1 MB) buffers and the shadow map too
#endif
  const Scene room = shadowref::testing::generatedScene("room", "zfail", size, size);
  const Scene outdoor = shadowref::testing::generatedScene("outdoor", "shadowmap", size, size);
  for (int threads : {1, 2}) {
    INFO(threads << " threads");
    FrameOptions options;
    options.threads = threads;
    options.keepStencil = true;
    const FrameResult first = renderFrame(room, options);
    (void)renderFrame(outdoor, options);  // freed at once: its blocks are kept for the next frame
    shadowref::testing::requireIdenticalFrames(first, renderFrame(room, options));
    const std::size_t mapped = pixelMemoryCounts().blocksMapped;
    (void)renderFrame(room, options);
    (void)renderFrame(outdoor, options);
    CHECK(pixelMemoryCounts().blocksMapped == mapped);
  }
}
