// The setups of one pending draw that meet a band's rows, in submission order (Renderer::
// rasterizeBand), each fetched into the cache a few setups before the band rasterizes it.
//
// One band reads its draw's setups in order and rasterizes all of them: the hardware prefetcher
// sees a stream and runs ahead. Cut into bands, a band reads only the setups that meet its rows —
// a scattered part of a few megabytes of setups (300 bytes each) — and waits
// for each from the shared cache, so that several bands at one thread take longer than one band.
// So each setup is asked for kAhead setups before it is rasterized: the wait is hidden behind the
// setups before it, for a few more instructions. Which setups are rasterized, and in what order, is
// unchanged: only when their bytes arrive.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>

#include "gl/triangle_setup.h"

namespace shadowref {

// Asks for every cache line of a setup: one every 64 bytes from its first byte, and its last
// byte's (a setup need not start a line), unrolled (the count is a constant).
inline void fetchSetup(const TriangleSetup* t) {
  const char* const setup = reinterpret_cast<const char*>(t);
  constexpr size_t kLine = 64;
  [&]<size_t... k>(std::index_sequence<k...>) {
    (__builtin_prefetch(setup + k * kLine), ...);
  }(std::make_index_sequence<(sizeof(TriangleSetup) + kLine - 1) / kLine>());
  __builtin_prefetch(setup + sizeof(TriangleSetup) - 1);
}

class BandSetups {
 public:
  // `bounds` and `setups` are the draw's, one entry a setup; the band's rows are [first, last].
  // `cut`: the band holds only part of the draw's rows. Otherwise it reads every setup in order,
  // a stream the hardware fetches ahead by itself, and nothing is asked for early.
  BandSetups(std::span<const SetupBounds> bounds, std::span<const TriangleSetup* const> setups, int first, int last,
             bool cut)
      : bounds_(bounds), setups_(setups), first_(first), last_(last), fetch_(cut) {
    if (!fetch_) return;
    for (; waiting_ < kAhead; ++waiting_) {
      const size_t i = nextMeeting(scanned_);
      if (i == bounds_.size()) break;
      fetch(i);
      ahead_[size_t(waiting_)] = i;
    }
  }

  // The next setup that meets the band's rows: its index in the draw's lists, or false when none
  // is left.
  bool next(size_t& index) {
    if (!fetch_) {
      scanned_ = nextMeeting(scanned_);
      if (scanned_ == bounds_.size()) return false;
      index = scanned_++;
      return true;
    }
    if (waiting_ == 0) return false;
    // The oldest one asked for leaves the ring; the next one found takes its slot, the newest.
    index = ahead_[oldest_];
    const size_t i = nextMeeting(scanned_);
    if (i < bounds_.size()) {
      fetch(i);
      ahead_[oldest_] = i;
    } else {
      --waiting_;
    }
    oldest_ = (oldest_ + 1) % size_t(kAhead);
    return true;
  }

  // Setups fetched ahead of the one rasterized: about one setup's rasterization (a volume side in
  // a band, a small triangle's spans) covers the wait for one from the shared cache, and four
  // measured no slower than eight or sixteen.
  static constexpr int kAhead = 4;

 private:
  // The first setup from `i` on that meets the rows, or the end. In locals: the loop around
  // next() rasterizes, and members kept across those calls would be read again at every step.
  size_t nextMeeting(size_t i) const {
    const SetupBounds* const bounds = bounds_.data();
    const size_t end = bounds_.size();
    const int first = first_, last = last_;
    while (i < end && (bounds[i].maxY < first || bounds[i].minY > last)) ++i;
    return i;
  }

  // Asks for setup i (which meets the rows); the scan goes on after it.
  void fetch(size_t i) {
    scanned_ = i + 1;
    fetchSetup(setups_[i]);
  }

  std::span<const SetupBounds> bounds_;
  std::span<const TriangleSetup* const> setups_;
  int first_, last_;
  bool fetch_;
  size_t scanned_ = 0;  // where the scan for the next meeting setup goes on
  // Fetching: the setups asked for and not yet handed out, in order from ahead_[oldest_] round the
  // ring; waiting_ of them.
  size_t ahead_[kAhead] = {};
  size_t oldest_ = 0;
  int waiting_ = 0;
};

}  // namespace shadowref
