// The draw call: primitive assembly -> clipping -> triangle setup -> rasterization -> fragment
// operations, for triangles given in clip space ([GL 2.1, §2.11-§4.1]).
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <span>
#include <unordered_map>
#include <vector>

#include "gl/clear.h"
#include "gl/pipeline.h"
#include "exec/clipped_vertex_store.h"
#include "gl/clipper.h"
#include "memory/construct_later.h"
#include "exec/fragment_processor.h"
#include "gl/fragment_shader.h"
#include "gl/framebuffer.h"
#include "gl/primitive_assembly.h"
#include "gl/raster_stats.h"
#include "gl/render_state.h"
#include "exec/row_work.h"
#include "exec/setup_reuse.h"
#include "exec/thread_pool.h"
#include "gl/triangle_setup.h"
#include "exec/two_ended_claims.h"
#include "gl/vertex.h"

namespace shadowref {


class Renderer {
 public:
  // With a pool of its own of `threads` threads (0: all cores).
  explicit Renderer(Framebuffer& framebuffer, int threads = 1);
  // With `pool`'s threads (nullptr: one thread), shared with the renderers that run before and
  // after this one on the same thread (the frame's and its shadow maps'), never at the same time.
  Renderer(Framebuffer& framebuffer, std::shared_ptr<ThreadPool> pool);
  ~Renderer();  // does the clears still waiting (clear)

  // Rasterizes bands of rows on `threads` threads (0: all cores), a pool of its own from now on
  // when the count changes. The buffers come out byte-identical for every thread count.
  void setThreads(int threads);
  int threads() const { return pool_ ? pool_->threadCount() : 1; }
  // The pool it renders with (nullptr: one thread), to share with other renderers.
  const std::shared_ptr<ThreadPool>& pool() const { return pool_; }

  // Allocates the buffers the state needs (colour when a shader writes, depth when the depth
  // test is on, stencil when the stencil test is on), assembles and sets up the triangles, then
  // rasterizes them — at once, or with a DeferredDraws alive, when the last one ends. A shaded draw
  // of arrays drawn before, unchanged, in a state that sets them up alike takes the setups kept
  // then instead of assembling again (SetupReuse).
  void draw(const DrawCall& call);

  // glClear (clear.h) as the start of what is drawn next: the buffers are made at once, their rows
  // filled at the next flush (the next draw without a DeferredDraws alive, or the end of the last
  // DeferredDraws) — each band's rows by the thread that draws into them next, right before it
  // does, so that a cleared band is in that thread's cache when the draws read it (a 2048² depth
  // map or an 800x640 colour buffer, cleared whole and read back, is more than the caches hold).
  // The clear keeps its place among the draws. The framebuffer must not be read before that flush
  // (framebuffer() and the destructor do the clears still waiting).
  void clear(const ClearRequest& request);

  // For tests of the kernels: renderers made after this call with `on` send every covered pixel
  // through the one-fragment path (FragmentProcessor::process, which calls the reference's
  // processFragment), pixel by pixel in rasterizeTriangle's order, instead of the dispatch table's
  // kernels, and count no flush by triangles; assembly, setup reuse, bands and threads stay the
  // executor's. Tests render both ways and require the same bytes; nothing else should switch it.
  static void oneFragmentAtATime(bool on);

  Framebuffer& framebuffer() {
    if (deferDepth_ == 0 && !pendingClears_.empty()) flush();
    return fb_;
  }

  // Rasterizes every draw made since the first DeferredDraws began (DeferredDraws calls it).
  void flush();

  // Runs task(i) for i in [0, count) on the renderer's threads (or this one) and returns when all
  // are done: for independent work between draws, such as building each caster's volume. The
  // tasks must not draw.
  void parallelFor(int count, const std::function<void(int)>& task);
  const RasterStats& stats() const { return stats_; }
  void resetStats() { stats_ = {}; }

  // How many counting flushes went by runs of triangles (countByTriangles), and how many by one
  // band a thread that the threads help each other finish (countByBands); the rest went by the
  // shaded passes' bands.
  uint64_t flushesCountedByTriangles() const { return trianglesCountedFlushes_; }
  uint64_t flushesCountedByBands() const { return bandsCountedFlushes_; }
  // How many draws took the setups kept from an earlier draw of their arrays (SetupReuse).
  uint64_t drawsReusingSetups() const { return drawsReusingSetups_; }

  // Reports every fragment at pixel (x, y) to the observer (nullptr to stop).
  void watchPixel(int x, int y, FragmentObserver* observer) {
    watch_.x = x;
    watch_.y = y;
    watch_.observer = observer;
  }

 private:
  // What assembly needs of each vertex of an indexed draw, worked out once per vertex instead of
  // once per triangle corner: whether it is inside every clip plane, and if so its window vertex.
  struct VertexCorners {
    // Written only for the vertices inside (and read only for those): grown without zeroing, a
    // 56-byte vertex each: a large volume draw has thousands, in each workspace, and zeroing them
    // first would write every one twice.
    std::vector<WindowVertex, ConstructLaterAllocator<WindowVertex>> window;
    std::vector<uint8_t> inside;
    const ClipVertex* base = nullptr;  // the draw's vertices; empty: work per corner
  };
  // What one thread of triangle assembly works in: its share of the triangles' setups and their
  // bounds, the vertices clipping made (kept until the flush has rasterized them), scratch,
  // counters, and the corners of the draw it assembles (nullptr: work per corner).
  // Cache lines of its own: its thread writes its vectors' ends and counters per triangle.
  struct alignas(128) AssemblyWorkspace {
    const VertexCorners* corners = nullptr;
    VertexCorners ownCorners;  // a queued draw's (assembleQueued)
    SetupBlock setups;
    std::vector<SetupBounds> bounds;  // of each setup
    ClippedVertexStore clippedVertices;  // of every draw this workspace assembled since the last flush
    std::vector<ClipVertex> polygon, clipScratch, clipOut;
    std::vector<WindowVertex> windowPolygon;
    RasterStats stats;
  };
  // Fills `corners` for the call's triangles [firstTriangle, lastTriangle) (on the pool's threads
  // when given); leaves them empty for a draw without indices or with fewer of them there than
  // vertices.
  static void prepareCorners(const DrawCall& call, const ClipPlanes& planes, VertexCorners& corners, ThreadPool* pool,
                             size_t firstTriangle, size_t lastTriangle);
  void assembleRange(const DrawCall& call, size_t first, size_t last, const ClipPlanes& planes, int varyingCount,
                     AssemblyWorkspace& ws) const;
  static void startWorkspace(AssemblyWorkspace& ws, size_t triangles);
  void appendTriangles(const DrawCall& call, size_t first, size_t last, const ClipPlanes& planes, int varyingCount,
                       AssemblyWorkspace& ws) const;
  void assembleTriangle(const ClipVertex* a, const ClipVertex* b, const ClipVertex* c, const RenderState& state,
                        const ClipPlanes& planes, int varyingCount, AssemblyWorkspace& ws) const;
  void addSetup(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c, Facing facing,
                const RenderState& state, AssemblyWorkspace& ws) const;

  // A draw whose triangles are set up and wait to be rasterized, with a copy of its state.
  struct PendingDraw {
    RenderState state;
    const FragmentShader* shader = nullptr;
    int fragmentWork = kPlainFragmentWork;  // fragmentWorkOf its shader, for the bands' estimate (RowWork)
    PixelWatch watch;     // the pixel history's watch with this draw's index and tag
    Rect region;          // drawRegion of the state
    size_t first = 0, count = 0;  // its setups in pendingSetups_
    int minY = 0, maxY = -1;      // the rows its triangles may touch
    bool workCounted = false;     // its setups are in rowWork_ (assembleQueued counted them)
  };
  friend class DeferredDraws;
  PendingDraw pendingDrawFor(const DrawCall& call) const;
  bool collectSetups(std::span<AssemblyWorkspace> workspaces, PendingDraw& pending);
  void keepBlock(AssemblyWorkspace& ws);
  bool finishPending(PendingDraw& pending, size_t count) const;
  // Fills in `pending`'s count and rows from the rows its setups span (minY: INT_MAX, maxY: -1 for
  // none); false when it has nothing to rasterize.
  static bool settleRows(PendingDraw& pending, size_t count, int minY, int maxY);
  // A draw whose assembly waits for the flush (DeferredDraws with Geometry::Kept): its call
  // (the state pointing at its pending draw's copy), clip planes, and its entry in pending_.
  struct QueuedAssembly {
    DrawCall call;
    ClipPlanes planes;
    int varyingCount = 0;
    size_t pending = 0;
    SetupReuse* reuse = nullptr;       // where its setups are kept after assembly (SetupReuse)
    const SetupReuse* kept = nullptr;  // the setups it takes instead of assembling (SetupReuse),
                                       // once verifyQueuedReuse found its contents unchanged
  };
  // Triangles [first, last) of queued draw `draw`, assembled by one group: a group is a run of
  // the pass's triangles, so a large draw (thousands of triangles) is cut between groups
  // rather than holding up one thread.
  struct QueuedPiece {
    size_t draw = 0;
    size_t first = 0, last = 0;
    size_t setupsEnd = 0;     // after assembly: the end of its setups in its group's workspace
    int minY = 0, maxY = -1;  // after assembly: the rows its setups span
    uint64_t culled = 0, clipped = 0;  // after assembly: its triangles culled and clipped
  };
  // SetupReuse: the entry of the call's arrays (made when they are new; nullptr for a draw without
  // a shader or of no triangles, or when another draw of this flush has it); whether the call may take the setups
  // kept in it; takes them (a pending draw without assembly); keeps a pending draw's setups in it
  // (pendingSetups_[first, first + count), in pendingBlocks_[firstBlock, endBlock)).
  SetupReuse* claimReuse(const DrawCall& call);
  bool canReuse(const SetupReuse& reuse, const DrawCall& call) const;
  void drawKeptSetups(const DrawCall& call, const SetupReuse& kept);
  void keepForReuse(const DrawCall& call, SetupReuse& reuse, size_t first, size_t count, uint64_t culled,
                    size_t firstBlock, size_t endBlock);
  void keepQueuedForReuse(size_t groups);
  void queueAssembly(const DrawCall& call, const ClipPlanes& planes, int varyingCount);
  void verifyQueuedReuse();
  void assembleQueued();
  void rasterizeBand(int y0, int y1, RasterStats& stats, SpanScratch& scratch) const;
  int64_t candidatePixels(const PendingDraw& draw) const;
  // A clear waiting for the flush, done before pending_[beforeDraw] (after every draw if there are
  // no more).
  struct PendingClear {
    ClearRequest request;
    Rect region;  // clearRegion of the request: the rows the bands must cover
    size_t beforeDraw = 0;
  };
  void clearsNow();  // the waiting clears, when no draw waits
  void clearRowsBefore(size_t draw, size_t& next, int y0, int y1) const;
  int cacheBands() const;
  void clearPending();  // forgets every pending draw, its setups and what they point into
  void rasterizeOne(const TriangleSetup& t, const Rect& region, FragmentProcessor& fragments) const;

  // A flush of draws that only add to the stencil modulo 256 (the shadow volumes' counting:
  // FragmentProcessor::onlyAddsToStencil), with clears only before them, gives the same bytes in
  // any order of its triangles (countsInAnyOrder). It is counted either by runs of triangles: no
  // triangle is cut between bands, and the threads take the runs as they come (countByTriangles);
  // or by one band of rows a thread, which the threads done with their own help to finish, taking
  // the last of its triangles (countByBands). A thread adds what is not its own band's into a
  // stencil of its own, and those stencils are added up at the end (counting_flush.cpp).
  bool countsInAnyOrder() const;
  bool countsByTriangles() const;
  void countByTriangles();
  void countByBands(int minY, int maxY);
  int cutIntoRuns(size_t runs);
  std::vector<std::vector<uint8_t>>& extraStencils(size_t count, size_t pixels);
  void addExtraStencils(std::vector<std::vector<uint8_t>>& extra, size_t firstTask);
  std::vector<std::vector<uint8_t>> extraStencils_;  // extraStencils' (counting_flush.cpp)
  // A setup of pending_[draw] that meets a band's rows (pendingSetups_[setup]).
  struct CountEntry {
    uint32_t draw, setup;
  };
  // A band of countByBands: the setups meeting its rows, in submission order, which its task
  // claims from the front and others from the back.
  struct CountBand {
    std::vector<CountEntry> entries;
    TwoEndedClaims claims;
  };
  void collectBandEntries(int y0, int y1, std::vector<CountEntry>& entries) const;
  void countEntries(const std::vector<CountEntry>& entries, uint32_t first, uint32_t last, int y0, int y1,
                    uint8_t* target, RasterStats& stats, SpanScratch& scratch) const;
  struct CountPiece {
    size_t draw = 0, first = 0, last = 0;  // setups [first, last) of pending_[draw]
  };
  // A task of countByTriangles: its counters and the rows of the draws it counted, on cache lines
  // of its own.
  struct alignas(128) CountTask {
    RasterStats stats;
    int minY = std::numeric_limits<int>::max(), maxY = -1;
  };
  std::vector<CountPiece> countPieces_;
  std::vector<size_t> countRunFirst_;  // run r: pieces [countRunFirst_[r], countRunFirst_[r + 1])
  std::vector<CountTask> countTasks_;
  std::unique_ptr<CountBand[]> countBands_;  // countByBands's, kept from flush to flush
  size_t countBandCount_ = 0;
  uint64_t trianglesCountedFlushes_ = 0;
  uint64_t bandsCountedFlushes_ = 0;

  Framebuffer& fb_;
  uint64_t flushes_ = 0;   // flushes done (SetupReuse: one draw per flush has an entry)
  // The setups kept for each vertex and index arrays drawn, while this renderer lives (a frame,
  // or a shadow map): what draws of the same arrays in later passes take (SetupReuse).
  std::unordered_map<SetupReuseKey, SetupReuse, SetupReuseKeyHash> reuse_;
  uint64_t drawsReusingSetups_ = 0;
  std::shared_ptr<ThreadPool> pool_;  // nullptr: one thread
  // The span loops' scratch of each thread of the pool (ThreadPool::runOnThreads), or of the one:
  // the executor's, not the threads', so that nothing of a draw outlives the renderer.
  std::vector<SpanScratch> scratch_;
  // Resizes scratch_ to the pool's threads.
  void setPool(std::shared_ptr<ThreadPool> pool);
  // A band's counters, on cache lines of their own: the band's thread adds to them per triangle
  // (per chunk of fragments in a shaded pass), and a line shared with the next band's counters
  // would travel between the threads at every addition.
  struct alignas(128) BandStats {
    RasterStats stats;
  };
  std::vector<BandStats> bandStats_;
  RasterStats stats_;
  PixelWatch watch_;
  uint64_t drawCount_ = 0;
  bool oneFragmentAtATime_;  // oneFragmentAtATime's switch when this renderer was made
  // Per-draw scratch, kept to avoid allocation per call: one assembly workspace per chunk of
  // triangles.
  std::vector<AssemblyWorkspace> assembly_;
  VertexCorners corners_;
  // Draws waiting for rasterization and their setups in submission order.
  std::vector<PendingDraw> pending_;
  // assembleQueued resizes the two lists and fills them on the threads: ConstructLaterAllocator
  // spares the calling thread zeroing them first.
  std::vector<const TriangleSetup*, ConstructLaterAllocator<const TriangleSetup*>> pendingSetups_;
  std::vector<SetupBounds, ConstructLaterAllocator<SetupBounds>> pendingBounds_;  // of each pending setup
  std::vector<std::shared_ptr<const SetupBlock>> pendingBlocks_;  // the setups, as assembly made them (and SetupReuse keeps)
  std::vector<PendingClear> pendingClears_;
  int splitIntoBands(int minY, int maxY, int maxBands, RowWork::Shares shares = RowWork::Shares::Shrinking);
  const StencilFaceState* stencilGate() const;
  RowWork rowWork_;  // the pending draws' and clears' (those counted so far), which the bands share
  std::vector<int> bandFirstRow_;    // band b: rows [bandFirstRow_[b], bandFirstRow_[b + 1])
  int deferDepth_ = 0;
  int keptDepth_ = 0;  // of those, the DeferredDraws whose makers keep every draw's geometry
  std::vector<QueuedAssembly> queued_;
  std::vector<size_t> queuedGroupFirst_;  // group g's setups from pendingSetups_[queuedGroupFirst_[g]]
  std::vector<QueuedPiece> queuedPieces_;
  std::vector<size_t> queuedGroups_;  // assembleQueued's group g: pieces [queuedGroups_[g], queuedGroups_[g + 1])
  std::vector<AssemblyWorkspace> queuedWs_;
  std::vector<size_t> queuedKept_;  // the queued draws that take kept setups
  std::vector<uint8_t> queuedSame_;  // verifyQueuedReuse's: whether each one's contents are the kept ones
  std::vector<size_t> queuedKeptFirst_;  // assembleQueued's run r of them: [queuedKeptFirst_[r], queuedKeptFirst_[r + 1])
  // A queued draw whose setups are to be kept in its SetupReuse, with its pieces' counts and the
  // groups they were assembled in (their blocks).
  struct KeptDraw {
    size_t draw = 0;
    uint64_t culled = 0, clipped = 0;
    size_t firstGroup = SIZE_MAX, endGroup = 0;
  };
  std::vector<KeptDraw> queuedKeep_;
  // Each queued group's setups counted into the rows' work on the group's thread (27k pumpkin
  // triangles a pass were counted on the calling thread), added to rowWork_ when the flush splits.
  struct alignas(128) GroupRowWork {
    RowWork work;
  };
  std::vector<GroupRowWork> queuedRowWork_;
  size_t queuedRowWorkCount_ = 0;  // groups of this flush not yet added to rowWork_
};

// While one of these lives, the renderer's draws are only set up; when the last one ends, all of
// them are rasterized together, every band of rows by one thread replaying the draws in the order
// they were made (the same bytes as drawing them one by one, for any thread count). A pass of many
// small draws — the city's houses and their volumes — then keeps every thread busy.
//
// Whoever makes one keeps, until it ends, every shader handed to those draws, and for shaded
// draws the vertices (their varyings are read when the fragments are shaded). The framebuffer must
// not be read or changed by other means (clears, callbacks) while one lives.
//
// With Geometry::Kept the maker also keeps every draw's vertices and indices until it ends (not
// refilled between draws): the draws are then not even assembled at once, but all together at the
// end, on all threads — many casters' volumes of a few dozen triangles each, or a few large
// meshes, without a pool run per draw.
class DeferredDraws {
 public:
  enum class Geometry { Refilled, Kept };
  explicit DeferredDraws(Renderer& renderer, Geometry geometry = Geometry::Refilled)
      : renderer_(renderer), kept_(geometry == Geometry::Kept) {
    ++renderer_.deferDepth_;
    renderer_.keptDepth_ += kept_;
  }
  ~DeferredDraws() {
    renderer_.keptDepth_ -= kept_;
    if (--renderer_.deferDepth_ == 0) renderer_.flush();
  }
  DeferredDraws(const DeferredDraws&) = delete;
  DeferredDraws& operator=(const DeferredDraws&) = delete;

 private:
  Renderer& renderer_;
  int kept_;
};

// The part of a draw's region in rows [y0, y1]: what a band of those rows rasterizes of the draw.
inline Rect regionInRows(const Rect& region, int y0, int y1) {
  Rect band = region;
  band.y = std::max(y0, region.y);
  band.height = std::min(y1, region.y + region.height - 1) - band.y + 1;
  return band;
}

}  // namespace shadowref
