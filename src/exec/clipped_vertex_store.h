// Where the vertices that clipping makes live until their triangles are rasterized: window
// vertices point at them (WindowVertex::source, for the varyings), so they must not move while
// any of their draws waits. A shadow volume pass clips ten thousand triangles against the guard
// band (their far ends are points at infinity); a std::deque of 160-byte vertices gave every three
// of them a node of their own, allocated on an assembly thread and freed on the flushing one —
// a serial cost that grows with the volume's size. Here they go into blocks of
// kBlockVertices that are kept when the store is emptied, for the next pass.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "gl/vertex.h"

namespace shadowref {

class ClippedVertexStore {
 public:
  // Copies v to the end; the copy keeps its address until clear().
  const ClipVertex& push(const ClipVertex& v) {
    if (used_ == blocks_.size() * kBlockVertices) blocks_.push_back(std::make_unique_for_overwrite<ClipVertex[]>(kBlockVertices));
    ClipVertex& slot = blocks_[used_ / kBlockVertices][used_ % kBlockVertices];
    slot = v;
    ++used_;
    return slot;
  }
  // Forgets every vertex; the blocks stay for the next ones.
  void clear() { used_ = 0; }
  size_t size() const { return used_; }

 private:
  static constexpr size_t kBlockVertices = 256;  // 40 KB
  std::vector<std::unique_ptr<ClipVertex[]>> blocks_;
  size_t used_ = 0;
};

}  // namespace shadowref
