#include "OpenMeshSkinned/Solver/SolveAhead.hh"

namespace OpenMeshSkinned {

SolveAhead::SolveAhead(EdgeCache& cache, size_t n_edges, const SolveSettings& settings, const WeightSolver& like)
    : cache_(cache),
      settings_(settings),
      ring_(std::make_unique<Job[]>(kRing)),
      mark_(std::make_unique<std::atomic<uint32_t>[]>(n_edges)) {
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

EdgeProblem* SolveAhead::reserve(int e, int a, int b, uint32_t sa, uint32_t sb) {
  reserved_ = head_.load(std::memory_order_relaxed);
  Job& job = ring_[reserved_ % kRing];
  // The slot's last job is dropped if the worker has not reached it; if the worker is reading it, or is
  // solving an earlier job of this edge (it would write the cache entry after this one is queued), this
  // job is not submitted: the mesh thread must not wait, and solves the edge itself if it is asked.
  int s = kQueued;
  if (!job.slot.compare_exchange_strong(s, kFree, std::memory_order_acq_rel) && s == kRunning) return nullptr;
  uint32_t m = mark_[e].load(std::memory_order_acquire);
  if ((m & 3u) == kWaiting && !mark_[e].compare_exchange_strong(m, kNone, std::memory_order_acq_rel)) return nullptr;
  if ((m & 3u) == kSolving) return nullptr;
  job.edge = e;
  job.a = a;
  job.b = b;
  job.sa = sa;
  job.sb = sb;
  job.ticket = ++tickets_ & 0x3fffffffu;
  job.skins_to_set = false;
  return &job.problem;
}

void SolveAhead::submit(const Influences& wa, const Influences& wb) {
  Job& job = ring_[reserved_ % kRing];
  job.wa = wa;
  job.wb = wb;
  job.skins_to_set = true;
  submit();
}

void SolveAhead::submit() {
  Job& job = ring_[reserved_ % kRing];
  mark_[job.edge].store(job.ticket << 2 | kWaiting, std::memory_order_release);
  job.slot.store(kQueued, std::memory_order_release);
  head_.store(reserved_ + 1, std::memory_order_release);
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
      if (job.skins_to_set) job.problem.set_skins(job.wa, job.wb);
      solve_collapse(job.problem, settings_, weights_, answer_);
      cache_.store_solved(job.edge, job.a, job.b, job.sa, job.sb, answer_);
      mark_[job.edge].store(job.ticket << 2 | kSolved, std::memory_order_release);
      solved_.fetch_add(1, std::memory_order_release);
    }
    job.slot.store(kFree, std::memory_order_release);
  }
}

}  // namespace OpenMeshSkinned
