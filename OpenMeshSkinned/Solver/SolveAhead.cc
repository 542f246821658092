#include "OpenMeshSkinned/Solver/SolveAhead.hh"

#include <utility>

namespace OpenMeshSkinned {

SolveAhead::SolveAhead(EdgeCache& cache, size_t n_edges, const SolveSettings& settings, const WeightSolver& like,
                       Loader load)
    : cache_(cache),
      settings_(settings),
      load_(std::move(load)),
      ring_(std::make_unique<Job[]>(kRing)),
      mark_(std::make_unique<std::atomic<uint32_t>[]>(n_edges)) {
  for (auto& r : reads_) r = {-1, -1};
  for (size_t e = 0; e < n_edges; ++e) mark_[e].store(kNone, std::memory_order_relaxed);
  weights_.set_regularization(like.regularization());
  weights_.set_force_ceres(like.force_ceres());
  worker_ = std::thread([this] { work(); });
}

SolveAhead::~SolveAhead() { stop(); }

void SolveAhead::stop() {
  stop_.store(true, std::memory_order_release);
  if (worker_.joinable()) worker_.join();
}

void SolveAhead::settle(int e) {
  std::atomic<uint32_t>& m = mark_[e];
  for (;;) {
    uint32_t v = m.load(std::memory_order_acquire);
    const uint32_t state = v & 3u;
    if (state == kWaiting && m.compare_exchange_weak(v, kNone, std::memory_order_acq_rel)) return;
    if (state == kSolving) std::this_thread::yield();
    if (state == kNone || state == kSolved) return;
  }
}

void SolveAhead::release_vertex(int v) {
  // Queued jobs are dropped first, before the worker can reach them while it finishes the one it holds; its
  // edge's mark may stay "waiting": settle() and submit() then find no job behind it, as after a slot came
  // round again. A job the worker holds is then waited for (only the mesh thread queues jobs: a slot it
  // has seen free stays free).
  std::array<size_t, kRing> held;
  size_t n_held = 0;
  for (size_t i = 0; i < kRing; ++i) {
    if (reads_[i][0] != v && reads_[i][1] != v) continue;
    reads_[i] = {-1, -1};
    int s = kQueued;
    while (!ring_[i].slot.compare_exchange_weak(s, kFree, std::memory_order_acq_rel) && s == kQueued) {
    }
    if (s == kRunning) held[n_held++] = i;
  }
  for (size_t k = 0; k < n_held; ++k)
    while (ring_[held[k]].slot.load(std::memory_order_acquire) != kFree) std::this_thread::yield();
}

bool SolveAhead::submit(int e, int a, int b, uint32_t sa, uint32_t sb) {
  const size_t at = head_.load(std::memory_order_relaxed);
  Job& job = ring_[at % kRing];
  // The slot's last job is dropped if the worker has not reached it; if the worker is reading it, or is
  // solving an earlier job of this edge (it would write the cache entry after this one is queued), this
  // job is not submitted: the mesh thread must not wait, and solves the edge itself if it is asked.
  int s = kQueued;
  if (!job.slot.compare_exchange_strong(s, kFree, std::memory_order_acq_rel) && s == kRunning) return false;
  uint32_t m = mark_[e].load(std::memory_order_acquire);
  if ((m & 3u) == kWaiting && !mark_[e].compare_exchange_strong(m, kNone, std::memory_order_acq_rel)) return false;
  if ((m & 3u) == kSolving) return false;
  job.edge = e;
  job.a = a;
  job.b = b;
  job.sa = sa;
  job.sb = sb;
  job.ticket = ++tickets_ & 0x3fffffffu;
  reads_[at % kRing] = {a, b};
  mark_[e].store(job.ticket << 2 | kWaiting, std::memory_order_release);
  job.slot.store(kQueued, std::memory_order_release);
  head_.store(at + 1, std::memory_order_release);
  return true;
}

void SolveAhead::work() {
  size_t tail = 0;
  while (!stop_.load(std::memory_order_acquire)) {
    const size_t head = head_.load(std::memory_order_acquire);
    if (tail >= head) {
      std::this_thread::yield();
      continue;
    }
    if (head - tail > kRing) tail = head - kRing;  // those slots hold later jobs by now
    Job& job = ring_[tail++ % kRing];
    int s = kQueued;
    if (!job.slot.compare_exchange_strong(s, kRunning, std::memory_order_acq_rel)) continue;
    uint32_t waiting = job.ticket << 2 | kWaiting;
    if (mark_[job.edge].compare_exchange_strong(waiting, job.ticket << 2 | kSolving, std::memory_order_acq_rel)) {
      load_(job.a, job.b, job.problem);
      solve_collapse(job.problem, settings_, weights_, answer_);
      cache_.store_solved(job.edge, job.a, job.b, job.sa, job.sb, answer_);
      mark_[job.edge].store(job.ticket << 2 | kSolved, std::memory_order_release);
      solved_.fetch_add(1, std::memory_order_release);
    }
    job.slot.store(kFree, std::memory_order_release);
  }
}

}  // namespace OpenMeshSkinned
