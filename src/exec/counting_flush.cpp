// A flush of stencil counting only (the shadow volumes' pass), counted by runs of triangles or by
// bands the threads help each other finish.
//
// Each fragment of such a flush adds 0, 1 or 255 to its pixel's stencil byte, modulo 256, after a
// depth test against a depth buffer nothing in the flush writes. Addition modulo 256 does not care
// about order or grouping, so the threads may count any triangles in any order, each into a
// stencil of its own, and the sum of the stencils is the byte one thread counting in submission
// order makes. Cut into bands of rows as a shaded pass is (three a thread, of shrinking shares,
// taken in order), every volume side that crosses a band's edge is set up again for each band it
// reaches, which costs most where many setups cross each row. So a counting flush
// goes either by runs of whole triangles (countByTriangles: many setups across a row), or by one
// band a thread of equal estimated work, the last of a band's setups counted by whichever thread is
// free (countByBands: the rest).
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "exec/band_setups.h"
#include "exec/renderer.h"
#include "exec/stencil_sum.h"

namespace shadowref {

namespace {

// Runs of triangles per thread: enough that the threads' ends even out (a thread that takes the
// last run waits for nothing else), few enough that the runs' starts cost little.
constexpr size_t kRunsPerThread = 16;
// The extra stencils together stay below this many bytes: with more threads than that allows,
// or a framebuffer too large for even one more stencil, the flush goes by bands.
constexpr size_t kMaxExtraStencilBytes = size_t(64) << 20;
// Setups sampled for the choice between bands and runs of triangles.
constexpr size_t kSampledSetups = 1024;
// Rows of the final sum a task adds at least.
constexpr int64_t kPixelsPerSumPart = 1 << 15;
// countByBands: a claim takes a kClaimShare-th of a band's share of the setups left.
constexpr int kClaimShare = 8;

}  // namespace

// The stencils of the threads but the first, kept zero between flushes (the sum zeroes what it
// read), and kept from flush to flush by the renderer: new ones would be zeroed and paged in each
// time.
std::vector<std::vector<uint8_t>>& Renderer::extraStencils(size_t count, size_t pixels) {
  if (extraStencils_.size() < count) extraStencils_.resize(count);
  for (size_t k = 0; k < count; ++k)
    if (extraStencils_[k].size() != pixels) extraStencils_[k].assign(pixels, 0);
  return extraStencils_;
}

bool Renderer::countsInAnyOrder() const {
  if (oneFragmentAtATime_ || !fb_.hasStencil()) return false;
  for (const PendingClear& c : pendingClears_)
    if (c.beforeDraw != 0) return false;  // a clear between draws would count in the middle
  for (const PendingDraw& d : pending_) {
    if (d.count > 0 && !FragmentProcessor::onlyAddsToStencil(fb_, d.state, d.shader)) return false;
    if (d.watch.observer) return false;  // drawn while the pixel history watched: it sees fragments in order
  }
  return size_t(threads()) * fb_.pixelCount() <= kMaxExtraStencilBytes;
}

bool Renderer::countsByTriangles() const {
  // Cut into bands, each setup that crosses a band's edge is started again there (about 1200
  // instructions); counted by triangles, a thread's rows are no longer in its cache, and each
  // thread reads the whole screen's depth, not its band's. Runs of triangles pay only where more
  // setups cross an average row than it has pixels: then the setups started again in every band
  // cost more than the cache misses.
  // Every few setups, for a sample of about kSampledSetups: the rows each covers in its region.
  size_t setups = 0;
  for (const PendingDraw& d : pending_) setups += d.count;
  const size_t stride = std::max<size_t>(1, setups / kSampledSetups);
  int64_t rows = 0, sampled = 0;
  size_t skip = 0;  // where the sample goes on in the next draw
  for (const PendingDraw& d : pending_) {
    size_t i = skip;
    for (; i < d.count; i += stride, ++sampled) {
      const SetupBounds& b = pendingBounds_[d.first + i];
      const Rect& r = d.region;
      const bool columns = std::max(b.minX, r.x) <= std::min(b.maxX, r.x + r.width - 1);
      if (columns) rows += std::max(0, std::min(b.maxY, r.y + r.height - 1) - std::max(b.minY, r.y) + 1);
    }
    skip = i - d.count;
  }
  const double acrossARow = double(rows) / double(std::max<int64_t>(sampled, 1)) * double(setups) / double(fb_.height());
  return acrossARow >= double(fb_.width());
}

// The pending draws' setups cut into `runs` runs of about the same length, a draw between runs
// where it is long and many short ones in one run: countPieces_, and countRunFirst_ for where each
// run's pieces start; returns the count.
int Renderer::cutIntoRuns(size_t runs) {
  size_t total = 0;
  for (const PendingDraw& d : pending_) total += d.count;
  runs = std::max<size_t>(1, std::min(total, runs));
  const size_t perRun = (total + runs - 1) / runs;
  countPieces_.clear();
  countRunFirst_.assign(1, 0);
  size_t inRun = 0;
  for (size_t d = 0; d < pending_.size(); ++d) {
    for (size_t at = 0; at < pending_[d].count;) {
      const size_t take = std::min(pending_[d].count - at, perRun - inRun);
      countPieces_.push_back({d, pending_[d].first + at, pending_[d].first + at + take});
      at += take;
      inRun += take;
      if (inRun == perRun) {
        countRunFirst_.push_back(countPieces_.size());
        inRun = 0;
      }
    }
  }
  if (inRun > 0) countRunFirst_.push_back(countPieces_.size());
  return int(countRunFirst_.size()) - 1;
}

// The extra stencils' rows that were counted into (task k's in extra[k - 1]), added to the
// framebuffer's and zeroed, in parts of rows on the threads.
void Renderer::addExtraStencils(std::vector<std::vector<uint8_t>>& extra, size_t firstTask) {
  int lo = fb_.height(), hi = -1;
  for (size_t k = firstTask; k < countTasks_.size(); ++k) {
    CountTask& t = countTasks_[k];
    t.minY = std::max(t.minY, 0);
    t.maxY = std::min(t.maxY, fb_.height() - 1);
    if (t.minY > t.maxY) continue;
    lo = std::min(lo, t.minY);
    hi = std::max(hi, t.maxY);
  }
  if (lo > hi) return;
  const int width = fb_.width();
  const int rows = hi - lo + 1;
  const int parts = int(std::clamp<int64_t>(int64_t(rows) * width / kPixelsPerSumPart, 1, rows));
  uint8_t* const stencil = fb_.stencil().data();
  pool_->run(parts, [&](int part) {
    const int y0 = lo + int(int64_t(rows) * part / parts), y1 = lo + int(int64_t(rows) * (part + 1) / parts);
    for (size_t k = firstTask; k < countTasks_.size(); ++k) {
      const CountTask& t = countTasks_[k];
      const int from = std::max(y0, t.minY), to = std::min(y1, t.maxY + 1);
      if (from >= to) continue;
      const size_t first = size_t(from) * size_t(width), last = size_t(to) * size_t(width);
      addAndZeroCounts(stencil + first, extra[k - firstTask].data() + first, last - first);
    }
  });
}

void Renderer::countByTriangles() {
  clearsNow();  // before every draw: the counts start from the cleared stencil
  const int tasks = threads();
  const int runCount = cutIntoRuns(size_t(tasks) * kRunsPerThread);

  // Task 0 counts into the framebuffer's stencil, task k > 0 into extra stencil k - 1. A thread
  // runs one task at a time, so each stencil has one writer.
  const size_t pixels = fb_.pixelCount();
  std::vector<std::vector<uint8_t>>& extra = extraStencils(size_t(tasks - 1), pixels);
  countTasks_.assign(size_t(tasks), CountTask{});
  std::atomic<int> nextRun{0};
  auto countRuns = [&](int task, int thread) {
    uint8_t* const target = task == 0 ? fb_.stencil().data() : extra[size_t(task - 1)].data();
    CountTask& mine = countTasks_[size_t(task)];
    for (int r; (r = nextRun.fetch_add(1, std::memory_order_relaxed)) < runCount;) {
      for (size_t p = countRunFirst_[size_t(r)]; p < countRunFirst_[size_t(r) + 1]; ++p) {
        const CountPiece& piece = countPieces_[p];
        const PendingDraw& draw = pending_[piece.draw];
        FragmentProcessor fragments(fb_, draw.state, draw.shader, mine.stats, nullptr, scratch_[size_t(thread)]);
        fragments.countInto(target);
        for (size_t i = piece.first; i < piece.last; ++i) rasterizeOne(*pendingSetups_[i], draw.region, fragments);
        mine.minY = std::min(mine.minY, draw.minY);
        mine.maxY = std::max(mine.maxY, draw.maxY);
      }
    }
  };

  try {
    pool_->runOnThreads(tasks, countRuns);
  } catch (...) {
    for (size_t k = 0; k + 1 < size_t(tasks); ++k) std::fill(extra[k].begin(), extra[k].end(), uint8_t(0));
    throw;
  }
  addExtraStencils(extra, 1);
  for (const CountTask& t : countTasks_) stats_ += t.stats;
  ++trianglesCountedFlushes_;
}

// The setups of every pending draw that meet rows [y0, y1], in submission order.
void Renderer::collectBandEntries(int y0, int y1, std::vector<CountEntry>& entries) const {
  entries.clear();
  for (size_t d = 0; d < pending_.size(); ++d) {
    const PendingDraw& draw = pending_[d];
    const int first = std::max(y0, draw.minY), last = std::min(y1, draw.maxY);
    if (first > last) continue;  // also a draw with nothing to rasterize (minY > maxY)
    const SetupBounds* const bounds = pendingBounds_.data();
    for (size_t i = draw.first; i < draw.first + draw.count; ++i)
      if (bounds[i].maxY >= first && bounds[i].minY <= last) entries.push_back({uint32_t(d), uint32_t(i)});
  }
}

// Entries [first, last) of a band of rows [y0, y1], each rasterized inside those rows with its
// own draw's state, counted into `target`: the band's own setups, or some its task left to others.
void Renderer::countEntries(const std::vector<CountEntry>& entries, uint32_t first, uint32_t last, int y0, int y1,
                            uint8_t* target, RasterStats& stats, SpanScratch& scratch) const {
  std::optional<FragmentProcessor> fragments;
  uint32_t current = std::numeric_limits<uint32_t>::max();
  Rect band;
  for (uint32_t k = first; k < last; ++k) {
    // A band's setups are a scattered part of the pass's (band_setups.h).
    if (k + BandSetups::kAhead < last) fetchSetup(pendingSetups_[entries[k + BandSetups::kAhead].setup]);
    const CountEntry& e = entries[k];
    if (e.draw != current) {
      current = e.draw;
      const PendingDraw& draw = pending_[current];
      fragments.emplace(fb_, draw.state, draw.shader, stats, nullptr, scratch);
      fragments->countInto(target);
      band = regionInRows(draw.region, y0, y1);
    }
    rasterizeOne(*pendingSetups_[e.setup], band, *fragments);
  }
}

// One band of rows a thread, of equal estimated work; a thread counts its own band's setups from
// the front, into the framebuffer's stencil, and then, while any band has setups left, takes the
// last of them — from the band with the most left — into a stencil of its own, added to the
// framebuffer's at the end. A setup is started in every band it meets: at two threads in two bands
// at most, where the shaded passes' six cut a volume side up to six times, and the threads end
// together without small bands at the end.
void Renderer::countByBands(int minY, int maxY) {
  clearsNow();  // before every draw: the counts start from the cleared stencil
  const int bands = splitIntoBands(minY, maxY, threads(), RowWork::Shares::Equal);
  if (countBandCount_ < size_t(bands)) {
    countBands_ = std::make_unique<CountBand[]>(size_t(bands));
    countBandCount_ = size_t(bands);
  }
  for (int b = 0; b < bands; ++b) countBands_[size_t(b)].claims.close();
  const size_t pixels = fb_.pixelCount();
  std::vector<std::vector<uint8_t>>& extra = extraStencils(size_t(bands), pixels);
  countTasks_.assign(size_t(bands), CountTask{});
  auto rowsOf = [&](int b) { return std::pair{bandFirstRow_[size_t(b)], bandFirstRow_[size_t(b) + 1] - 1}; };
  // Setups a claim takes: a kClaimShare-th of a band's share of those left, so that the last
  // claims, small, end the threads together.
  auto claimSize = [bands](uint32_t left) { return std::max<uint32_t>(1, left / uint32_t(kClaimShare * bands)); };
  auto countBand = [&](int task, int thread) {
    SpanScratch& scratch = scratch_[size_t(thread)];
    CountBand& own = countBands_[size_t(task)];
    CountTask& mine = countTasks_[size_t(task)];
    const auto [y0, y1] = rowsOf(task);
    collectBandEntries(y0, y1, own.entries);
    own.claims.open(uint32_t(own.entries.size()));
    for (uint32_t first, last; own.claims.claimFront(claimSize(own.claims.left()), first, last);)
      countEntries(own.entries, first, last, y0, y1, fb_.stencil().data(), mine.stats, scratch);
    for (;;) {
      int from = -1;
      uint32_t most = 0;
      for (int b = 0; b < bands; ++b)
        if (const uint32_t left = countBands_[size_t(b)].claims.left(); left > most) {
          most = left;
          from = b;
        }
      if (from < 0) break;
      uint32_t first, last;
      if (!countBands_[size_t(from)].claims.claimBack(claimSize(most), first, last)) continue;
      const auto [b0, b1] = rowsOf(from);
      const std::vector<CountEntry>& entries = countBands_[size_t(from)].entries;
      countEntries(entries, first, last, b0, b1, extra[size_t(task)].data(), mine.stats, scratch);
      // The sum adds only the rows these setups reach, not the whole band's: the last setups of a
      // band often cover only a few of its rows.
      for (uint32_t k = first; k < last; ++k) {
        const SetupBounds& b = pendingBounds_[entries[k].setup];
        mine.minY = std::min(mine.minY, std::max(b.minY, b0));
        mine.maxY = std::max(mine.maxY, std::min(b.maxY, b1));
      }
    }
  };

  try {
    pool_->runOnThreads(bands, countBand);
  } catch (...) {
    for (size_t k = 0; k < size_t(bands); ++k) std::fill(extra[k].begin(), extra[k].end(), uint8_t(0));
    throw;
  }
  addExtraStencils(extra, 0);
  for (const CountTask& t : countTasks_) stats_ += t.stats;
  ++bandsCountedFlushes_;
}

}  // namespace shadowref
