// A small pool of persistent worker threads for the rasterizer. Work is handed out as numbered
// tasks (bands of rows); which thread runs which task varies, but tasks touch disjoint pixels and
// each runs its triangles in submission order, so the buffers come out byte-identical for any
// thread count (the llvmpipe idea of STYLE.md: each tile owned by one thread, replayed in order).
#pragma once

#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace shadowref {

class ThreadPool {
 public:
  // threads <= 1: everything runs on the calling thread.
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int threadCount() const { return int(workers_.size()) + 1; }

  // Runs task(i) for i in [0, count), on the workers and the calling thread; returns when all
  // are done.
  void run(int count, const std::function<void(int)>& task);

 private:
  void workerLoop();
  void drain();

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(int)>* task_ = nullptr;
  int count_ = 0;
  std::atomic<int> next_{0};
  int busy_ = 0;
  uint64_t generation_ = 0;
  bool stop_ = false;
};

// The number of threads "0 = all cores" means.
int defaultThreadCount();

}  // namespace shadowref
