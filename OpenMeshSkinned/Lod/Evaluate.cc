#include "Evaluate.hh"

#include <OpenMeshSkinned/Eval/SurfaceDistance.hh>

#include <algorithm>
#include <atomic>
#include <exception>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace OpenMeshSkinned {

namespace {

// Per LOD vertex, in % of the diagonal: its distance to the original surface, and the distance to the LOD of
// every original vertex whose nearest LOD point lies on one of its triangles (a LOD whose vertices all sit
// on the original can still cut through it between them: a collapsed knee).
std::vector<float> vertex_errors(const TriangleSoup& original, const MeasuredSurface& original_surface,
                                 const TriangleSoup& lod, const MeasuredSurface& lod_surface, double diag) {
  std::vector<float> e(lod.points.size(), 0.0f);
  for (size_t v = 0; v < lod.points.size(); ++v) e[v] = float(original_surface.distance(lod.points[v]));
  for (const auto& p : original.points) {
    int t = -1;
    const float d = float(lod_surface.distance(p, t));
    if (t >= 0)
      for (int k : lod.triangles[t]) e[k] = std::max(e[k], d);
  }
  for (float& x : e) x = float(100.0 * x / diag);
  return e;
}

}  // namespace

// Frame by frame, threads taking frames in turn: the posed original's surface (hierarchy and samples) is
// posed once per frame and measured against every LOD; sums are taken in frame order, so the numbers do not
// depend on the thread count. Only the calling thread reports progress (callbacks may not be thread-safe).
std::vector<HeldOutError> evaluate_lods(const SkinnedMesh& original, const std::vector<const SkinnedMesh*>& lods,
                                        const std::vector<Pose>& frames,
                                        const std::vector<std::vector<Pose>>& lod_frames,
                                        const EvaluateOptions& options, const LodCallbacks& callbacks) {
  if (frames.empty()) throw std::invalid_argument("evaluate: no frames to judge in");
  if (!lod_frames.empty() && lod_frames.size() != lods.size())
    throw std::invalid_argument("evaluate: lod_frames must have one entry per LOD");
  for (const auto& f : lod_frames)
    if (!f.empty() && f.size() != frames.size())
      throw std::invalid_argument("evaluate: each LOD's own frames must be as many as the frames");
  const double diag = bbox_diagonal(original);
  const size_t n_lods = lods.size();
  const bool per_vertex = options.per_vertex_error;
  std::vector<SurfaceDistance> d(frames.size() * n_lods);
  std::vector<std::vector<float>> vd(per_vertex ? frames.size() * n_lods : 0);
  std::atomic<size_t> next{0}, done{0};
  std::exception_ptr failure;
  std::mutex failure_lock;
  auto work = [&](bool caller) {
    // Per LOD, each vertex's nearest triangle in this thread's previous frame: the next frame's query starts
    // there (the same answers, found faster: a vertex moves little against the other surface between frames).
    try {
      std::vector<std::vector<int>> original_hints(n_lods), lod_hints(n_lods);
      // This thread's surfaces, built in the first frame whichever frame it takes first, then posed again
      // frame by frame (without building the original's hierarchy again every frame). Which of a dense
      // surface's vertices count toward the RMS follows its hierarchy's leaf order: a hierarchy built in
      // another frame would count others, and the numbers would change with the threads' timing.
      std::unique_ptr<MeasuredSurface> posed;
      std::vector<std::unique_ptr<MeasuredSurface>> lod_surfaces(n_lods);
      const auto lod_pose = [&](size_t i, size_t f) -> const Pose& {
        return lod_frames.empty() || lod_frames[i].empty() ? frames[f] : lod_frames[i][f];
      };
      for (size_t f = next++; f < frames.size(); f = next++) {
        const TriangleSoup original_soup = posed_soup(original, frames[f]);
        if (!posed && f != 0)
          posed = std::make_unique<MeasuredSurface>(posed_soup(original, frames[0]), options.samples, 1);
        const MeasuredSurface& original_surface = posed_surface(posed, original_soup, options.samples, 1);
        for (size_t i = 0; i < n_lods; ++i) {
          const TriangleSoup lod = posed_soup(*lods[i], lod_pose(i, f));
          if (!lod_surfaces[i] && f != 0)
            lod_surfaces[i] = std::make_unique<MeasuredSurface>(posed_soup(*lods[i], lod_pose(i, 0)), options.samples,
                                                                0x9E3779B97F4A7C16ull);
          const MeasuredSurface& lod_surface =
              posed_surface(lod_surfaces[i], lod, options.samples, 0x9E3779B97F4A7C16ull);
          d[f * n_lods + i] = surface_distance(original_surface, lod_surface, original_hints[i], lod_hints[i],
                                               options.counted_vertices);
          if (per_vertex) vd[f * n_lods + i] = vertex_errors(original_soup, original_surface, lod, lod_surface, diag);
        }
        ++done;
        if (caller) callbacks.report("measuring the held-out error", double(done) / frames.size());
      }
    } catch (...) {
      std::lock_guard<std::mutex> g(failure_lock);
      if (!failure) failure = std::current_exception();
      next = frames.size();
    }
  };
  const int threads = options.threads > 0 ? options.threads : int(std::max(1u, std::thread::hardware_concurrency()));
  std::vector<std::thread> pool;
  for (int t = 1; t < std::min<int>(threads, int(frames.size())); ++t) pool.emplace_back(work, false);
  work(true);
  for (auto& th : pool) th.join();
  if (failure) std::rethrow_exception(failure);
  std::vector<HeldOutError> out(n_lods);
  for (size_t i = 0; i < n_lods; ++i) {
    double sum_rms = 0.0, max_h = 0.0;
    for (size_t f = 0; f < frames.size(); ++f) {
      sum_rms += d[f * n_lods + i].rms;
      max_h = std::max(max_h, d[f * n_lods + i].hausdorff);
    }
    out[i].rms = 100.0 * sum_rms / frames.size() / diag;
    out[i].hausdorff = 100.0 * max_h / diag;
    if (!per_vertex) continue;
    out[i].vertex_error.assign(lods[i]->n_vertices(), 0.0f);
    for (size_t f = 0; f < frames.size(); ++f)
      for (size_t v = 0; v < out[i].vertex_error.size(); ++v)
        out[i].vertex_error[v] = std::max(out[i].vertex_error[v], vd[f * n_lods + i][v]);
  }
  return out;
}

HeldOutError evaluate(const SkinnedMesh& original, const SkinnedMesh& lod, const std::vector<Pose>& frames,
                      const EvaluateOptions& options) {
  return evaluate_lods(original, {&lod}, frames, {}, options).front();
}

}  // namespace OpenMeshSkinned
