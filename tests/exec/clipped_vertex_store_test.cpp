// ClippedVertexStore: window vertices point at its vertices until the flush, so a vertex must keep
// its address and value however many come after it, and a cleared store must hand out its
// blocks again.
#include <vector>

#include <catch2/catch.hpp>

#include "exec/clipped_vertex_store.h"

using namespace shadowref;

namespace {
ClipVertex numbered(int i) {
  ClipVertex v;
  v.position = {double(i), -double(i), 0.5 * i, 1.0};
  for (size_t j = 0; j < v.varyings.size(); ++j) v.varyings[j] = double(i) + 0.001 * double(j);
  return v;
}
}  // namespace

TEST_CASE("a clipped vertex keeps its address and value until the store is cleared", "[raster][clip]") {
  ClippedVertexStore store;
  std::vector<const ClipVertex*> at;
  for (int i = 0; i < 1000; ++i) at.push_back(&store.push(numbered(i)));  // several blocks
  REQUIRE(store.size() == 1000);
  for (int i = 0; i < 1000; ++i) {
    const ClipVertex expected = numbered(i);
    CHECK(at[size_t(i)]->position == expected.position);
    CHECK(at[size_t(i)]->varyings == expected.varyings);
  }
  // Cleared, it fills the same memory again, from the start.
  store.clear();
  CHECK(store.size() == 0);
  for (int i = 0; i < 1000; ++i) CHECK(&store.push(numbered(-i)) == at[size_t(i)]);
  CHECK(at[999]->position == numbered(-999).position);
}
