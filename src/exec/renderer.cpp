#include "exec/renderer.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>

#include "exec/band_setups.h"
#include "gl/fragment_ops.h"
#include "exec/rasterizer.h"

namespace shadowref {


namespace {
std::atomic<bool> oneFragmentAtATimeForNewRenderers{false};
}  // namespace

void Renderer::oneFragmentAtATime(bool on) { oneFragmentAtATimeForNewRenderers = on; }

Renderer::Renderer(Framebuffer& framebuffer, int threads)
    : fb_(framebuffer), oneFragmentAtATime_(oneFragmentAtATimeForNewRenderers) {
  setThreads(threads);
  rowWork_.reset(fb_.height());
}

Renderer::Renderer(Framebuffer& framebuffer, std::shared_ptr<ThreadPool> pool)
    : fb_(framebuffer), oneFragmentAtATime_(oneFragmentAtATimeForNewRenderers) {
  setPool(std::move(pool));
  rowWork_.reset(fb_.height());
}

Renderer::~Renderer() {
  // Draws still waiting here were abandoned (an exception left their DeferredDraws): their
  // geometry may be gone, so only clears that wait alone are done.
  if (pending_.empty() && queued_.empty() && !pendingClears_.empty()) clearsNow();
}

void Renderer::clear(const ClearRequest& request) {
  prepareClear(fb_, request);
  pendingClears_.push_back({request, clearRegion(fb_, request.state), pending_.size()});
}

void Renderer::clearsNow() {
  const ParallelFor parallel = [this](int count, const std::function<void(int)>& task) { parallelFor(count, task); };
  for (const PendingClear& c : pendingClears_) fillClear(fb_, c.request, parallel);  // made by clear()
  pendingClears_.clear();
}

void Renderer::setThreads(int threads) {
  if (threads <= 0) threads = defaultThreadCount();
  if (threads != this->threads() || scratch_.empty()) setPool(makeThreadPool(threads));
}

void Renderer::setPool(std::shared_ptr<ThreadPool> pool) {
  pool_ = std::move(pool);
  scratch_.resize(size_t(threads()));
}

void Renderer::addSetup(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c, Facing facing,
                        const RenderState& state, AssemblyWorkspace& ws) const {
  // Set up in place (a setup is a few hundred bytes), taken back if the triangle has no pixels.
  TriangleSetup& t = ws.setups.emplace_back();
  if (!setupTriangle(a, b, c, facing, state, fb_.depthCodec(), t)) {
    ws.setups.pop_back();
    return;
  }
  ws.bounds.push_back({t.minX, t.minY, t.maxX, t.maxY});
}

void Renderer::assembleTriangle(const ClipVertex* a, const ClipVertex* b, const ClipVertex* c, const RenderState& state,
                                const ClipPlanes& planes, int varyingCount, AssemblyWorkspace& ws) const {
  canonicalRotation(a, b, c);
  const ClipVertex* tri[3] = {a, b, c};
  const VertexCorners* cached = ws.corners && ws.corners->base ? ws.corners : nullptr;
  bool inside = true;
  if (cached) {
    for (const ClipVertex* v : tri) inside = inside && cached->inside[size_t(v - cached->base)];
  } else {
    for (const ClipVertex* v : tri) inside = inside && insideAllPlanes(v, 1, planes);
  }

  if (inside) {
    auto window = [&](const ClipVertex* v) {
      return cached ? cached->window[size_t(v - cached->base)] : toWindow(*v, state.viewport);
    };
    const WindowVertex wa = window(a), wb = window(b), wc = window(c);
    const int64_t area2 = signedArea2(wa, wb, wc);
    const Facing facing = facingOf(area2, state.frontFace);
    if (area2 == 0 || isCulled(facing, state.cull)) {
      ++ws.stats.trianglesCulled;
      return;
    }
    addSetup(wa, wb, wc, facing, state, ws);
    return;
  }

  ++ws.stats.trianglesClipped;
  ws.polygon.assign({*a, *b, *c});
  clipPolygon(ws.polygon, planes, varyingCount, ws.clipOut, ws.clipScratch);
  if (ws.clipOut.size() < 3) return;
  ws.windowPolygon.clear();
  for (const ClipVertex& v : ws.clipOut) ws.windowPolygon.push_back(toWindow(ws.clippedVertices.push(v), state.viewport));
  // Facing of the polygon as a whole ([GL 2.1, §2.14.1]: the area of the clipped polygon).
  int64_t area2 = 0;
  for (size_t i = 1; i + 1 < ws.windowPolygon.size(); ++i)
    area2 += signedArea2(ws.windowPolygon[0], ws.windowPolygon[i], ws.windowPolygon[i + 1]);
  const Facing facing = facingOf(area2, state.frontFace);
  if (area2 == 0 || isCulled(facing, state.cull)) {
    ++ws.stats.trianglesCulled;
    return;
  }
  for (size_t i = 1; i + 1 < ws.windowPolygon.size(); ++i)
    addSetup(ws.windowPolygon[0], ws.windowPolygon[i], ws.windowPolygon[i + 1], facing, state, ws);
}

void Renderer::assembleRange(const DrawCall& call, size_t first, size_t last, const ClipPlanes& planes,
                             int varyingCount, AssemblyWorkspace& ws) const {
  startWorkspace(ws, last - first);
  appendTriangles(call, first, last, planes, varyingCount, ws);
}

void Renderer::startWorkspace(AssemblyWorkspace& ws, size_t triangles) {
  ws.setups.clear();
  ws.setups.reserve(triangles);  // the last draw's block was moved out: one allocation, not a doubling series
  ws.bounds.clear();
  ws.bounds.reserve(triangles);  // a new renderer's workspaces (one a frame) would grow it by doubling
  ws.stats = {};  // clippedVertices stay: the draws assembled before still wait
}

void Renderer::appendTriangles(const DrawCall& call, size_t first, size_t last, const ClipPlanes& planes,
                               int varyingCount, AssemblyWorkspace& ws) const {
  for (size_t i = first; i < last; ++i) {
    const ClipVertex* v[3];
    for (int k = 0; k < 3; ++k) {
      const size_t index = call.indices.empty() ? 3 * i + k : call.indices[3 * i + k];  // checked by draw()
      v[k] = &call.vertices[index];
    }
    assembleTriangle(v[0], v[1], v[2], *call.state, planes, varyingCount, ws);
  }
}

namespace {
// Triangle assembly is split into chunks of this many triangles when there are threads; each
// chunk's setups are appended in chunk order, so the list is the same as on one thread.
constexpr size_t kAssemblyChunk = 128;
// Groups of a queued pass's triangles per thread at a flush (assembleQueued).
constexpr size_t kQueuedGroupsPerThread = 4;
// The vertices' clip tests and window transforms, in chunks of this many vertices on threads.
constexpr size_t kCornerChunk = 1024;
// A draw's corners are worked per vertex unless its vertices outnumber them this many times. Per
// vertex costs a few instructions for each of the draw's vertices (marking and scanning) and about
// 85 for each it uses; per corner about 85 for each corner. A volume's side quads share their
// silhouette vertices (about three corners a vertex), so even a piece of a volume draw whose
// vertices outnumber its corners (a volume's sides cut between groups) is cheaper per vertex.
constexpr size_t kVerticesPerCornerForCorners = 8;
}  // namespace

// An indexed mesh has about half as many vertices as triangles, and each triangle three corners:
// the clip test and window transform of each vertex the draw uses, once (the same function of the
// same vertex: the same bits). A volume's draws use part of their vertices each (a cap's near or
// far ones), so the used ones are marked first.
void Renderer::prepareCorners(const DrawCall& call, const ClipPlanes& planes, VertexCorners& corners,
                              ThreadPool* pool, size_t firstTriangle, size_t lastTriangle) {
  const size_t count = call.vertices.size();
  corners.base = nullptr;
  const std::span<const uint32_t> used = call.indices.empty() ? std::span<const uint32_t>()
                                         : std::span(call.indices).subspan(3 * firstTriangle, 3 * (lastTriangle - firstTriangle));
  if (used.empty() || count > kVerticesPerCornerForCorners * used.size()) return;
  if (corners.window.size() < count) {  // grown only: resizing down and up would construct again
    corners.window.resize(count);
    corners.inside.resize(count);
  }
  uint8_t* const inside = corners.inside.data();
  std::fill_n(inside, count, uint8_t(2));  // 2: unused
  for (const uint32_t i : used) inside[i] = 0;  // every index is in range (draw() checked them)
  auto range = [&](size_t first, size_t last) {
    for (size_t i = first; i < last; ++i) {
      if (inside[i] == 2) continue;
      const ClipVertex& v = call.vertices[i];
      inside[i] = insideAllPlanes(&v, 1, planes);
      if (inside[i]) corners.window[i] = toWindow(v, call.state->viewport);  // toWindow needs w > 0
    }
  };
  const size_t chunks = (count + kCornerChunk - 1) / kCornerChunk;
  if (pool && chunks > 1) {
    pool->run(int(chunks), [&](int c) {
      range(size_t(c) * kCornerChunk, std::min(count, size_t(c + 1) * kCornerChunk));
    });
  } else {
    range(0, count);
  }
  corners.base = call.vertices.data();
}

void Renderer::draw(const DrawCall& call) {
  const RenderState& state = *call.state;
  ensureBuffersFor(fb_, call);  // the reference's rule (primitive_assembly.h)

  ++stats_.drawCalls;
  watch_.drawIndex = drawCount_++;
  watch_.drawTag = call.tag;

  const ClipPlanes planes = clipPlanesFor(state);
  const int varyingCount = call.shader ? call.shader->varyingCount() : 0;

  const size_t triangleCount = trianglesOf(call);
  stats_.trianglesIn += triangleCount;
  SetupReuse* const reuse = claimReuse(call);
  const bool queue = pool_ && triangleCount > 0 && deferDepth_ == 1 && keptDepth_ == 1;
  if (queue && reuse && reuse->kept_ && setsUpAlike(reuse->state_, *call.state)) {
    // Its contents are compared at the flush, on the threads (verifyQueuedReuse); its indices are
    // checked now, in case they changed.
    checkIndices(call);
    queueAssembly(call, planes, varyingCount);
    queued_.back().kept = reuse;
    queued_.back().reuse = reuse;  // keeps its setups there if it is assembled after all
    return;
  }
  if (reuse && canReuse(*reuse, call)) {  // its indices are those checked when its setups were kept
    ++drawsReusingSetups_;
    drawKeptSetups(call, *reuse);
    if (deferDepth_ == 0) flush();
    return;
  }
  checkIndices(call);
  if (queue) {
    queueAssembly(call, planes, varyingCount);
    queued_.back().reuse = reuse;  // keeps its setups there after assembly
    return;
  }
  const size_t chunks = pool_ ? std::max<size_t>(1, (triangleCount + kAssemblyChunk - 1) / kAssemblyChunk) : 1;
  if (assembly_.size() < chunks) assembly_.resize(chunks);
  prepareCorners(call, planes, corners_, pool_.get(), 0, triangleCount);
  for (size_t c = 0; c < chunks; ++c) assembly_[c].corners = &corners_;
  if (chunks == 1) {
    assembleRange(call, 0, triangleCount, planes, varyingCount, assembly_[0]);
  } else {
    pool_->run(int(chunks), [&](int c) {
      const size_t first = size_t(c) * kAssemblyChunk;
      assembleRange(call, first, std::min(triangleCount, first + kAssemblyChunk), planes, varyingCount,
                    assembly_[size_t(c)]);
    });
  }
  corners_.base = nullptr;
  PendingDraw pending = pendingDrawFor(call);
  uint64_t culled = 0, clipped = 0;
  for (size_t c = 0; c < chunks; ++c) {
    culled += assembly_[c].stats.trianglesCulled;
    clipped += assembly_[c].stats.trianglesClipped;
  }
  const bool drawn = collectSetups(std::span(assembly_.data(), chunks), pending);
  if (reuse && clipped == 0)
    keepForReuse(call, *reuse, pending.first, pendingSetups_.size() - pending.first, culled,
                 pendingBlocks_.size() - chunks, pendingBlocks_.size());
  if (drawn) pending_.push_back(pending);
  if (deferDepth_ == 0) flush();
}

// The call as a pending draw, before its setups are known: a copy of its state, its region,
// shader and the work of its fragments, and the pixel history's watch.
Renderer::PendingDraw Renderer::pendingDrawFor(const DrawCall& call) const {
  PendingDraw pending;
  pending.region = drawRegion(*call.state, fb_);
  pending.state = *call.state;
  pending.shader = call.shader;
  pending.fragmentWork = fragmentWorkOf(call.shader);
  pending.watch = watch_;
  pending.watch.hasColor = fb_.hasColor();  // the buffers as the draw finds them (PixelWatch)
  pending.watch.hasDepth = fb_.hasDepth();
  pending.watch.hasStencil = fb_.hasStencil();
  return pending;
}

// Moves the setups the workspaces assembled into the pending lists, counts them, and fills in
// the rows `pending` touches; false when it has nothing to rasterize (no setups, or none meets its
// region), as a draw outside the framebuffer or culled whole.
bool Renderer::collectSetups(std::span<AssemblyWorkspace> workspaces, PendingDraw& pending) {
  pending.first = pendingSetups_.size();
  for (AssemblyWorkspace& ws : workspaces) {
    for (const TriangleSetup& t : ws.setups) pendingSetups_.push_back(&t);
    pendingBounds_.insert(pendingBounds_.end(), ws.bounds.begin(), ws.bounds.end());
    keepBlock(ws);
  }
  stats_.trianglesRasterized += pendingSetups_.size() - pending.first;
  return finishPending(pending, pendingSetups_.size() - pending.first);
}

// The workspace's setups move as a block (no copy: 27k pumpkin triangles are 8 MB a pass) — the
// pending list points into it; its counters are added up. The vertices clipping made stay in the
// workspace until the flush.
void Renderer::keepBlock(AssemblyWorkspace& ws) {
  pendingBlocks_.push_back(std::make_shared<const SetupBlock>(std::move(ws.setups)));
  ws.setups = {};
  stats_.trianglesClipped += ws.stats.trianglesClipped;
  stats_.trianglesCulled += ws.stats.trianglesCulled;
}

// `pending`'s setups are the `count` from pendingSetups_[pending.first]: fills in its count and rows;
// false when it has nothing to rasterize.
namespace {
// The rows a run of setups' bounds spans: minY INT_MAX and maxY -1 for none (settleRows' "none").
struct SpannedRows {
  int minY = std::numeric_limits<int>::max(), maxY = -1;
};
template <class Bounds>
SpannedRows rowsSpanned(std::span<const Bounds> bounds) {
  SpannedRows rows;
  for (const Bounds& b : bounds) {
    rows.minY = std::min(rows.minY, b.minY);
    rows.maxY = std::max(rows.maxY, b.maxY);
  }
  return rows;
}
}  // namespace

bool Renderer::finishPending(PendingDraw& pending, size_t count) const {
  const SpannedRows rows = rowsSpanned(std::span(pendingBounds_).subspan(pending.first, count));
  return settleRows(pending, count, rows.minY, rows.maxY);
}

bool Renderer::settleRows(PendingDraw& pending, size_t count, int minY, int maxY) {
  pending.count = count;
  const Rect& region = pending.region;
  if (region.width <= 0 || region.height <= 0 || count == 0) return false;
  pending.minY = std::max(std::min(minY, region.y + region.height), region.y);
  pending.maxY = std::min(maxY, region.y + region.height - 1);
  return pending.minY <= pending.maxY;
}

// Only shaded draws keep or take setups: in the frames drawn here a draw that writes no colour — a
// shadow map's casters, a light's volumes — draws arrays made for its pass, which no later pass
// draws again unchanged, and a copy of their positions and indices would be kept for nothing.
SetupReuse* Renderer::claimReuse(const DrawCall& call) {
  if (!call.shader || trianglesOf(call) == 0) return nullptr;
  SetupReuse& r = reuse_[{call.vertices.data(), call.vertices.size(), call.indices.data(), call.indices.size()}];
  if (r.claimFlush_ == flushes_) return nullptr;
  r.claimFlush_ = flushes_;
  return &r;
}

// The contents last: the state is one comparison, the contents a read of every position.
bool Renderer::canReuse(const SetupReuse& r, const DrawCall& call) const {
  return r.kept_ && setsUpAlike(r.state_, *call.state) && r.sameContents(call.vertices, call.indices);
}

// The kept setups as a pending draw of this call's state: no assembly, and their rows' work is
// counted at the flush.
void Renderer::drawKeptSetups(const DrawCall& call, const SetupReuse& r) {
  PendingDraw pending = pendingDrawFor(call);
  pending.first = pendingSetups_.size();
  pendingSetups_.insert(pendingSetups_.end(), r.setups_.begin(), r.setups_.end());
  pendingBounds_.insert(pendingBounds_.end(), r.bounds_.begin(), r.bounds_.end());
  pendingBlocks_.insert(pendingBlocks_.end(), r.blocks_.begin(), r.blocks_.end());  // alive until the flush
  stats_.trianglesCulled += r.culled_;
  stats_.trianglesRasterized += r.setups_.size();
  if (settleRows(pending, r.setups_.size(), r.minY_, r.maxY_)) pending_.push_back(pending);
}

// Keeps the call's setups — pendingSetups_[first, first + count), in the blocks
// pendingBlocks_[firstBlock, endBlock) — in the entry of its arrays, with a copy of the positions
// and indices they were made from.
void Renderer::keepForReuse(const DrawCall& call, SetupReuse& r, size_t first, size_t count, uint64_t culled,
                            size_t firstBlock, size_t endBlock) {
  r.kept_ = true;
  r.keepContents(call.vertices, call.indices);
  r.state_ = *call.state;
  const auto at = std::ptrdiff_t(first), end = std::ptrdiff_t(first + count);
  r.setups_.assign(pendingSetups_.begin() + at, pendingSetups_.begin() + end);
  r.bounds_.assign(pendingBounds_.begin() + at, pendingBounds_.begin() + end);
  r.blocks_.assign(pendingBlocks_.begin() + std::ptrdiff_t(firstBlock), pendingBlocks_.begin() + std::ptrdiff_t(endBlock));
  r.culled_ = culled;
  const SpannedRows rows = rowsSpanned(std::span<const SetupBounds>(r.bounds_));
  r.minY_ = rows.minY;
  r.maxY_ = rows.maxY;
}

// A draw under a DeferredDraws that keeps the geometry: its assembly waits for the flush, where
// every queued draw is assembled at once on all threads (assembleQueued), and its pending draw
// keeps its place in pending_ meanwhile.
void Renderer::queueAssembly(const DrawCall& call, const ClipPlanes& planes, int varyingCount) {
  QueuedAssembly& q = queued_.emplace_back();
  q.call = call;
  q.planes = planes;
  q.varyingCount = varyingCount;
  q.pending = pending_.size();
  pending_.push_back(pendingDrawFor(call));
}

// The queued draws that would take kept setups, their contents compared with the kept copies on
// the threads (a few hundred kilobytes a pass on the calling thread held the other up): a draw
// whose arrays changed is assembled with the others after all.
void Renderer::verifyQueuedReuse() {
  queuedKept_.clear();
  for (size_t d = 0; d < queued_.size(); ++d)
    if (queued_[d].kept) queuedKept_.push_back(d);
  if (queuedKept_.empty()) return;
  queuedSame_.assign(queuedKept_.size(), 0);
  pool_->run(int(queuedKept_.size()), [&](int k) {
    const QueuedAssembly& q = queued_[queuedKept_[size_t(k)]];
    queuedSame_[size_t(k)] = q.kept->sameContents(q.call.vertices, q.call.indices);
  });
  for (size_t k = 0; k < queuedKept_.size(); ++k) {
    if (queuedSame_[k]) ++drawsReusingSetups_;
    else queued_[queuedKept_[k]].kept = nullptr;
  }
}

void Renderer::assembleQueued() {
  verifyQueuedReuse();
  // The pass's triangles, draw after draw, cut into runs, a few per thread, each assembled into
  // one workspace by one task: one pool run for the whole pass instead of one or two per draw, one
  // block per group (a volume pass may queue hundreds of small draws, or a dozen large ones). The
  // threads take the groups in order, so the runs shrink — shares groups + 1, groups, … 2 of the
  // triangles — and the last ones, small, even out the threads' ends; a draw may be cut between
  // groups (groups of whole draws would wait for the largest draw). A draw that takes kept setups
  // (SetupReuse) is not assembled: its setups are copied in the second run.
  auto assembled = [](const QueuedAssembly& q) { return q.kept ? size_t(0) : trianglesOf(q.call); };
  size_t total = 0;
  for (const QueuedAssembly& q : queued_) total += assembled(q);
  const size_t groups = std::min(total, size_t(pool_->threadCount()) * kQueuedGroupsPerThread);
  const size_t parts = groups * (groups + 3) / 2;
  auto groupStart = [&](size_t g) {  // the parts of groups 0 … g - 1: g (groups + 1) - g (g - 1) / 2
    return g == groups ? total : total * (g * (groups + 1) - g * (g - 1) / 2) / parts;
  };
  queuedPieces_.clear();
  queuedGroups_.assign(1, 0);
  size_t draw = 0, drawStart = 0;  // queued_[draw]'s first triangle in the pass
  for (size_t g = 0; g < groups; ++g) {
    const size_t end = groupStart(g + 1);
    for (size_t at = groupStart(g); at < end;) {
      while (at >= drawStart + assembled(queued_[draw])) drawStart += assembled(queued_[draw++]);
      const size_t stop = std::min(end, drawStart + assembled(queued_[draw]));
      queuedPieces_.push_back({.draw = draw, .first = at - drawStart, .last = stop - drawStart});
      at = stop;
    }
    queuedGroups_.push_back(queuedPieces_.size());
  }
  if (queuedWs_.size() < groups) queuedWs_.resize(groups);
  // The caller's state may have been a temporary: the pending draw's copy stands in for it.
  for (QueuedAssembly& q : queued_) q.call.state = &pending_[q.pending].state;
  const std::span<QueuedPiece> pieces(queuedPieces_);
  auto piecesOf = [&](size_t g) { return pieces.subspan(queuedGroups_[g], queuedGroups_[g + 1] - queuedGroups_[g]); };
  pool_->run(int(groups), [&](int g) {
    AssemblyWorkspace& ws = queuedWs_[size_t(g)];
    startWorkspace(ws, groupStart(size_t(g) + 1) - groupStart(size_t(g)));
    for (QueuedPiece& piece : piecesOf(size_t(g))) {
      const QueuedAssembly& q = queued_[piece.draw];
      // An indexed draw shares its vertices among its triangles: each is worked out once, where
      // the piece has more corners than the draw has vertices (prepareCorners decides, as draw()
      // does on one thread; the city's volume draws are small, and were worked per corner here).
      prepareCorners(q.call, q.planes, ws.ownCorners, nullptr, piece.first, piece.last);
      ws.corners = &ws.ownCorners;
      const RasterStats before = ws.stats;
      appendTriangles(q.call, piece.first, piece.last, q.planes, q.varyingCount, ws);
      piece.setupsEnd = ws.setups.size();
      piece.culled = ws.stats.trianglesCulled - before.trianglesCulled;
      piece.clipped = ws.stats.trianglesClipped - before.trianglesClipped;
    }
    ws.corners = nullptr;
  });
  // Each group's setups take the next slice of the pending lists, then each kept draw's, filled
  // on the threads with the rows each piece spans (27k pumpkin triangles a pass: a serial copy
  // kept the other thread waiting).
  std::vector<size_t>& groupFirst = queuedGroupFirst_;
  groupFirst.assign(groups + 1, pendingSetups_.size());
  for (size_t g = 0; g < groups; ++g) groupFirst[g + 1] = groupFirst[g] + queuedWs_[g].setups.size();
  queuedKept_.clear();
  size_t end = groupFirst[groups];
  for (size_t d = 0; d < queued_.size(); ++d) {
    if (!queued_[d].kept) continue;
    PendingDraw& pending = pending_[queued_[d].pending];
    pending.first = end;
    pending.count = queued_[d].kept->setups_.size();
    end += pending.count;
    queuedKept_.push_back(d);
  }
  pendingSetups_.resize(end);
  pendingBounds_.resize(end);
  // The kept draws in runs of about equal setups, a few per thread: a task and a row count each
  // (the city's lit pass takes 129 kept draws, whose row counts the calling thread added one by
  // one).
  const size_t keptSetups = end - groupFirst[groups];
  const size_t keptTasks = std::min(queuedKept_.size(), size_t(pool_->threadCount()) * kQueuedGroupsPerThread);
  queuedKeptFirst_.assign(1, 0);
  for (size_t k = 0, done = 0; k < queuedKept_.size(); ++k) {
    done += pending_[queued_[queuedKept_[k]].pending].count;
    const size_t upTo = queuedKeptFirst_.size();  // the number of draw k's run, counted from 1
    if (upTo < keptTasks && done * keptTasks >= keptSetups * upTo) queuedKeptFirst_.push_back(k + 1);
  }
  if (queuedKeptFirst_.back() != queuedKept_.size()) queuedKeptFirst_.push_back(queuedKept_.size());
  const size_t tasks = groups + queuedKeptFirst_.size() - 1;
  if (queuedRowWork_.size() < tasks) queuedRowWork_.resize(tasks);
  const bool byShape = RowWork::weighsShapes(end);
  pool_->run(int(tasks), [&](int task) {
    RowWork& work = queuedRowWork_[size_t(task)].work;
    work.reset(fb_.height());
    // Copies, not references: the loops below store to the lists, and what the compiler cannot
    // tell apart from those stores it would load again for every triangle.
    const bool shapes = byShape;
    if (size_t(task) >= groups) {
      const size_t run = size_t(task) - groups;
      for (size_t k = queuedKeptFirst_[run]; k < queuedKeptFirst_[run + 1]; ++k) {
        const QueuedAssembly& q = queued_[queuedKept_[k]];
        const SetupReuse& kept = *q.kept;
        const PendingDraw& pending = pending_[q.pending];
        std::copy(kept.setups_.begin(), kept.setups_.end(), pendingSetups_.begin() + std::ptrdiff_t(pending.first));
        std::copy(kept.bounds_.begin(), kept.bounds_.end(), pendingBounds_.begin() + std::ptrdiff_t(pending.first));
        const Rect region = pending.region;
        const int fragmentWork = pending.fragmentWork;
        for (size_t i = 0; i < kept.bounds_.size(); ++i)
          work.addTriangle(kept.bounds_[i], *kept.setups_[i], region, shapes, fragmentWork);
      }
      return;
    }
    const size_t g = size_t(task);
    const AssemblyWorkspace& ws = queuedWs_[g];
    for (size_t k = 0; k < ws.setups.size(); ++k) pendingSetups_[groupFirst[g] + k] = &ws.setups[k];
    std::copy(ws.bounds.begin(), ws.bounds.end(), pendingBounds_.begin() + std::ptrdiff_t(groupFirst[g]));
    size_t next = 0;
    for (QueuedPiece& piece : piecesOf(g)) {
      const std::span<const SetupBounds> bounds = std::span(ws.bounds).subspan(next, piece.setupsEnd - next);
      const SpannedRows rows = rowsSpanned(bounds);
      piece.minY = rows.minY;
      piece.maxY = rows.maxY;
      const PendingDraw& pending = pending_[queued_[piece.draw].pending];
      const Rect region = pending.region;
      const int fragmentWork = pending.fragmentWork;
      const TriangleSetup* setups = ws.setups.data() + next;
      for (size_t k = 0; k < bounds.size(); ++k) work.addTriangle(bounds[k], setups[k], region, shapes, fragmentWork);
      next = piece.setupsEnd;
    }
  });
  queuedRowWorkCount_ = tasks;
  // Each assembled draw's setups: its pieces', consecutive in the pending lists.
  for (size_t g = 0, last = queued_.size(); g < groups; ++g) {
    size_t next = 0;
    for (const QueuedPiece& piece : piecesOf(g)) {
      PendingDraw& pending = pending_[queued_[piece.draw].pending];
      if (piece.draw != last) {
        pending.first = groupFirst[g] + next;
        pending.count = 0;
        pending.minY = std::numeric_limits<int>::max();
        pending.maxY = -1;
        last = piece.draw;
      }
      pending.count += piece.setupsEnd - next;
      pending.minY = std::min(pending.minY, piece.minY);
      pending.maxY = std::max(pending.maxY, piece.maxY);
      next = piece.setupsEnd;
    }
  }
  for (const size_t d : queuedKept_) {
    const SetupReuse& kept = *queued_[d].kept;
    PendingDraw& pending = pending_[queued_[d].pending];
    pending.minY = kept.minY_;
    pending.maxY = kept.maxY_;
    stats_.trianglesCulled += kept.culled_;
    pendingBlocks_.insert(pendingBlocks_.end(), kept.blocks_.begin(), kept.blocks_.end());  // alive until the flush
  }
  stats_.trianglesRasterized += end - groupFirst[0];
  for (size_t g = 0; g < groups; ++g) keepBlock(queuedWs_[g]);
  keepQueuedForReuse(groups);
  for (const QueuedAssembly& q : queued_) {
    PendingDraw& pending = pending_[q.pending];
    pending.workCounted = true;
    if (!settleRows(pending, pending.count, pending.minY, pending.maxY)) {
      pending.count = 0;  // nothing to rasterize: no band takes it
      pending.minY = std::numeric_limits<int>::max();
      pending.maxY = -1;
    }
  }
  queued_.clear();
}

// The assembled queued draws' setups kept in their SetupReuse (those that clipped no triangle),
// each draw's copied on a thread of its own. The groups' blocks are the last `groups` of
// pendingBlocks_, in order.
void Renderer::keepQueuedForReuse(size_t groups) {
  queuedKeep_.clear();
  for (size_t d = 0; d < queued_.size(); ++d)
    if (queued_[d].reuse && !queued_[d].kept) queuedKeep_.push_back({.draw = d});  // claimed in draw()
  if (queuedKeep_.empty()) return;
  for (size_t g = 0; g < groups; ++g)
    for (size_t p = queuedGroups_[g]; p < queuedGroups_[g + 1]; ++p) {
      const QueuedPiece& piece = queuedPieces_[p];
      auto at = std::lower_bound(queuedKeep_.begin(), queuedKeep_.end(), piece.draw,
                                 [](const KeptDraw& k, size_t draw) { return k.draw < draw; });
      if (at == queuedKeep_.end() || at->draw != piece.draw) continue;
      at->culled += piece.culled;
      at->clipped += piece.clipped;
      at->firstGroup = std::min(at->firstGroup, g);
      at->endGroup = g + 1;
    }
  const size_t firstBlock = pendingBlocks_.size() - groups;
  pool_->run(int(queuedKeep_.size()), [&](int i) {
    const KeptDraw& k = queuedKeep_[size_t(i)];
    const QueuedAssembly& q = queued_[k.draw];
    const PendingDraw& pending = pending_[q.pending];
    if (k.clipped != 0) return;
    const size_t beginGroup = k.firstGroup == SIZE_MAX ? k.endGroup : k.firstGroup;  // no pieces: no blocks
    keepForReuse(q.call, *q.reuse, pending.first, pending.count, k.culled, firstBlock + beginGroup,
                 firstBlock + k.endGroup);
  });
}

namespace {
// Bands per thread when a pass is rasterized: enough for the threads to even out what the
// estimate of each row's work (splitIntoBands) gets wrong, few enough that a large triangle — a shadow
// volume's side reaches across the screen — is not set up again in many bands. At least
// kMinBandRows rows a band.
constexpr int kBandsPerThread = 3;
constexpr int kMinBandRows = 16;
// Below this many candidate pixels a draw is not worth waking the other threads for.
constexpr int64_t kParallelThreshold = 2048;
}  // namespace

// The pixels of the draw's region inside its setups' bounding boxes: an upper bound of its work.
int64_t Renderer::candidatePixels(const PendingDraw& draw) const {
  const Rect& r = draw.region;
  int64_t sum = 0;
  for (size_t i = draw.first; i < draw.first + draw.count; ++i) {
    const SetupBounds& t = pendingBounds_[i];
    const int64_t w = std::min(t.maxX, r.x + r.width - 1) - std::max(t.minX, r.x) + 1;
    const int64_t h = std::min(t.maxY, r.y + r.height - 1) - std::max(t.minY, r.y) + 1;
    if (w > 0 && h > 0) sum += w * h;
  }
  return sum;
}

void Renderer::rasterizeOne(const TriangleSetup& t, const Rect& region, FragmentProcessor& fragments) const {
  if (oneFragmentAtATime_) {
    rasterizeTriangle(t, region, [&](int x, int y, int64_t e0, int64_t e1, int64_t e2) {
      fragments.process(t, x, y, e0, e1, e2);
    });
    return;
  }
  fragments.processTriangle(t, region);
}

// The setups of the pending draws whose rows (inside their draw's region) meet rows [y0, y1],
// in submission order, each rasterized inside those rows with its own draw's state. The band
// picks its setups out of the compact bounds list itself — 16 bytes a setup read on the band's
// thread — rather than every setup being binned on one thread before the bands start, and asks
// for each setup's bytes a few setups before it rasterizes it (BandSetups).
void Renderer::rasterizeBand(int y0, int y1, RasterStats& stats, SpanScratch& scratch) const {
  std::optional<FragmentProcessor> fragments;
  size_t nextClear = 0;
  for (size_t d = 0; d < pending_.size(); ++d) {
    clearRowsBefore(d, nextClear, y0, y1);
    const PendingDraw& draw = pending_[d];
    const int first = std::max(y0, draw.minY), last = std::min(y1, draw.maxY);
    if (first > last) continue;  // also a draw with nothing to rasterize (minY > maxY)
    const Rect band = regionInRows(draw.region, y0, y1);
    bool started = false;
    BandSetups setups{std::span(pendingBounds_).subspan(draw.first, draw.count),
                      std::span<const TriangleSetup* const>(pendingSetups_.data() + draw.first, draw.count), first, last,
                      draw.minY < first || draw.maxY > last};
    for (size_t i; setups.next(i);) {
      if (!started) {
        // The processor writes to fb_ through its own reference: rasterizing changes the
        // framebuffer, not the renderer.
        fragments.emplace(fb_, draw.state, draw.shader, stats, &draw.watch, scratch);
        started = true;
      }
      rasterizeOne(*pendingSetups_[draw.first + i], band, *fragments);
    }
  }
  clearRowsBefore(pending_.size(), nextClear, y0, y1);
}

// The band's rows [y0, y1] of the waiting clears from `next` on that come before draw `draw`.
void Renderer::clearRowsBefore(size_t draw, size_t& next, int y0, int y1) const {
  for (; next < pendingClears_.size() && pendingClears_[next].beforeDraw <= draw; ++next)
    clearRows(fb_, pendingClears_[next].request, y0, y1 + 1);
}

// How many bands the waiting clears ask for: enough that each band's share of the cleared bytes
// fits in a core's own cache (kBandBytes, half of a common 1 MB L2) — cleared whole, a large
// buffer would go out to memory and come back when the draws read it.
int Renderer::cacheBands() const {
  constexpr int64_t kBandBytes = int64_t(1) << 19;
  int64_t bytes = 0;
  for (const PendingClear& c : pendingClears_) {
    const Rect& r = c.region;
    const int64_t perPixel = (c.request.color ? int64_t(sizeof(glm::vec4)) : 0) + (c.request.depth ? 4 : 0) +
                             (c.request.stencil ? 1 : 0) + (c.request.accum ? int64_t(sizeof(glm::vec4)) : 0);
    bytes += int64_t(r.width) * int64_t(r.height) * perPixel;
  }
  return int(std::min<int64_t>(bytes / kBandBytes, 64));
}

void Renderer::parallelFor(int count, const std::function<void(int)>& task) {
  if (pool_) {
    pool_->run(count, task);
    return;
  }
  for (int i = 0; i < count; ++i) task(i);
}

// Cuts rows [minY, maxY] into bands (RowWork::split) by each row's estimated work: its pixels in
// the pending triangles' bounding boxes and a quarter of its cleared pixels, plus a row's and a
// triangle's fixed costs. The queued draws' triangles were counted on the threads
// (assembleQueued); the others are counted here.
int Renderer::splitIntoBands(int minY, int maxY, int maxBands, RowWork::Shares shares) {
  for (size_t g = 0; g < queuedRowWorkCount_; ++g) rowWork_.add(queuedRowWork_[g].work);
  queuedRowWorkCount_ = 0;
  const bool byShape = RowWork::weighsShapes(pendingSetups_.size());
  for (PendingDraw& draw : pending_) {
    if (draw.workCounted) continue;
    for (size_t i = draw.first; i < draw.first + draw.count; ++i) {
      rowWork_.addTriangle(pendingBounds_[i], *pendingSetups_[i], draw.region, byShape, draw.fragmentWork);
    }
    draw.workCounted = true;
  }
  for (const PendingClear& c : pendingClears_) rowWork_.addClear(c.region);
  if (const StencilFaceState* gate = stencilGate()) {
    rowWork_.weighByStencil(fb_.stencil().data(), fb_.width(), minY, maxY, *gate);
  }
  return rowWork_.split(minY, maxY, maxBands, kMinBandRows, bandFirstRow_, shares);
}

namespace {
bool sameTest(const StencilFaceState& a, const StencilFaceState& b) {
  return a.func == b.func && std::clamp(a.ref, 0, 255) == std::clamp(b.ref, 0, 255) && a.mask == b.mask;
}
}  // namespace

// The stencil test every pending draw passes by, for both faces, when it can stop a fragment (its
// function is not "always") and nothing in the flush writes the stencil (no draw, no clear): the
// buffer read before the bands start is the one the draws test against. nullptr otherwise.
const StencilFaceState* Renderer::stencilGate() const {
  if (!fb_.hasStencil() || pending_.empty()) return nullptr;
  for (const PendingClear& c : pendingClears_)
    if (c.request.stencil) return nullptr;
  const StencilFaceState& gate = pending_.front().state.stencil[FrontFacing];
  if (gate.func == CompareFunc::Always) return nullptr;
  for (const PendingDraw& d : pending_) {
    if (!d.state.stencilTest) return nullptr;
    for (const StencilFaceState& face : d.state.stencil)
      if (!sameTest(face, gate) || stencilFaceMayWrite(face)) return nullptr;
  }
  return &gate;
}

void Renderer::flush() {
  if (!queued_.empty()) assembleQueued();
  int minY = fb_.height(), maxY = -1;
  int64_t candidates = 0;
  for (const PendingDraw& d : pending_) {
    minY = std::min(minY, d.minY);
    maxY = std::max(maxY, d.maxY);
    if (candidates < kParallelThreshold) candidates += candidatePixels(d);
  }
  if (maxY < minY) {  // no draw left to rasterize (none made, or all culled or clipped away whole)
    clearsNow();
    clearPending();
    return;
  }
  for (const PendingClear& c : pendingClears_) {  // the bands cover the cleared rows too
    const Rect& r = c.region;
    if (r.width == 0 || r.height == 0) continue;
    minY = std::min(minY, r.y);
    maxY = std::max(maxY, r.y + r.height - 1);
  }
  const bool parallel = pool_ && candidates >= kParallelThreshold;
  const int threadBands = parallel ? pool_->threadCount() * kBandsPerThread : 1;
  if (parallel && countsInAnyOrder()) {
    if (countsByTriangles()) countByTriangles();
    else countByBands(minY, maxY);
    clearPending();
    return;
  }
  const int maxBands = std::min(std::max(threadBands, cacheBands()), (maxY - minY + 1) / kMinBandRows);
  const int bands = maxBands >= 2 ? splitIntoBands(minY, maxY, maxBands) : 1;
  if (bands == 1) {
    rasterizeBand(minY, maxY, stats_, scratch_[0]);
  } else if (!parallel) {  // bands for the caches only, in order on this thread
    for (int b = 0; b < bands; ++b)
      rasterizeBand(bandFirstRow_[size_t(b)], bandFirstRow_[size_t(b) + 1] - 1, stats_, scratch_[0]);
  } else {
    // Each band of rows belongs to one task, which replays its setups in submission order.
    bandStats_.assign(size_t(bands), BandStats{});
    pool_->runOnThreads(bands, [&](int b, int thread) {
      rasterizeBand(bandFirstRow_[size_t(b)], bandFirstRow_[size_t(b) + 1] - 1, bandStats_[size_t(b)].stats,
                    scratch_[size_t(thread)]);
    });
    for (const BandStats& s : bandStats_) stats_ += s.stats;
  }
  clearPending();
}

void Renderer::clearPending() {
  ++flushes_;
  pending_.clear();
  pendingClears_.clear();
  pendingSetups_.clear();
  pendingBounds_.clear();
  pendingBlocks_.clear();
  rowWork_.reset(fb_.height());
  queuedRowWorkCount_ = 0;
  for (AssemblyWorkspace& ws : assembly_) ws.clippedVertices.clear();
  for (AssemblyWorkspace& ws : queuedWs_) ws.clippedVertices.clear();
}

}  // namespace shadowref
