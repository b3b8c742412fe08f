// A list of n items that one task works through from the front while others, done with their own
// lists, take items from the back (Renderer::countByBands): every item is claimed exactly once,
// in chunks, by a compare-and-swap on one word holding both ends.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>

namespace shadowref {

class TwoEndedClaims {
 public:
  // Nothing to claim until open(): a task that looks before the list's owner has filled it finds
  // it empty.
  TwoEndedClaims() = default;
  TwoEndedClaims(const TwoEndedClaims&) = delete;
  TwoEndedClaims& operator=(const TwoEndedClaims&) = delete;

  // Items [0, n) to claim. The list's contents written before this call are seen by every task that
  // claims an item after it.
  void open(uint32_t n) { ends_.store(uint64_t(n) << 32, std::memory_order_release); }
  void close() { ends_.store(0, std::memory_order_relaxed); }

  // Up to `most` items from the front, [first, last); false when none is left.
  bool claimFront(uint32_t most, uint32_t& first, uint32_t& last) { return claim(most, true, first, last); }
  // Up to `most` items from the back, [first, last); false when none is left.
  bool claimBack(uint32_t most, uint32_t& first, uint32_t& last) { return claim(most, false, first, last); }

  // Items not yet claimed (a moment's reading: others may be claiming).
  uint32_t left() const {
    const uint64_t e = ends_.load(std::memory_order_relaxed);
    const uint32_t front = uint32_t(e), back = uint32_t(e >> 32);
    return back > front ? back - front : 0;
  }

 private:
  bool claim(uint32_t most, bool fromFront, uint32_t& first, uint32_t& last) {
    uint64_t e = ends_.load(std::memory_order_acquire);
    for (;;) {
      const uint32_t front = uint32_t(e), back = uint32_t(e >> 32);
      if (front >= back) return false;
      const uint32_t take = std::min(std::max(most, uint32_t(1)), back - front);
      const uint64_t next = fromFront ? e + take : (uint64_t(back - take) << 32) | front;
      if (ends_.compare_exchange_weak(e, next, std::memory_order_acq_rel, std::memory_order_acquire)) {
        first = fromFront ? front : back - take;
        last = first + take;
        return true;
      }
    }
  }

  // Low half: the front (the next item the owner takes), high half: the back (one past the last
  // item a thief may take).
  alignas(64) std::atomic<uint64_t> ends_{0};
};

}  // namespace shadowref
