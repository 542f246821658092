#include "MakeLods.hh"

#include <OpenMeshSkinned/Deform/ExampleFrames.hh>
#include <OpenMeshSkinned/Deform/KeyframeGA.hh>
#include <OpenMeshSkinned/Eval/SurfaceDistance.hh>
#include <OpenMeshSkinned/Skin/FrameAnimation.hh>
#include <OpenMeshSkinned/Skin/KeyReduction.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>
#include <OpenMeshSkinned/Solver/EdgeFlipFit.hh>
#include <OpenMeshSkinned/Solver/Refit.hh>
#include <OpenMeshSkinned/Solver/RefitFrames.hh>
#include <OpenMeshSkinned/Solver/SkeletonLodT.hh>

#include <algorithm>
#include <chrono>
#include <sstream>
#include <thread>

namespace OpenMeshSkinned {

namespace {

using Clock = std::chrono::steady_clock;
double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

// At most this many vertices feed the key-frame GA's fitness.
constexpr size_t kMaxFitnessVertices = 5000;

int thread_count(const LodOptions& o) {
  return o.threads > 0 ? o.threads : int(std::max(1u, std::thread::hardware_concurrency()));
}

// A number as a stream prints it by default, as the tool always has in these lines.
std::string plain(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

// max_error after the final fit, which knows nothing of the bound: the fit is kept if the original's
// vertices are still within the limit of the LOD in every example pose (measured, the solver's way: skin
// only), and undone otherwise (positions and skin weights). The LOD's bound is then the measured distance, or the
// decimation's bound.
void keep_bound_after_refit(const SkinnedMesh& original, SkinnedMesh& lmesh, std::vector<Pose> examples,
                            const std::vector<SkinnedMesh::Point>& decimated,
                            const std::vector<Influences>& decimated_skin, LodReport& lod, const LodOptions& opt,
                            const LodCallbacks& cb) {
  for (Pose& p : examples) p.morph_weights.clear();
  const double diagonal = bbox_diagonal(original);
  const double worst = 100.0 * worst_vertex_deviation(original, lmesh, examples) / diagonal;
  if (worst <= opt.max_error) {
    lod.deviation_bound = worst;
    return;
  }
  const auto h = influences_handle(lmesh);
  for (auto vh : lmesh.vertices()) {
    lmesh.set_point(vh, decimated[vh.idx()]);
    lmesh.property(h, vh) = decimated_skin[vh.idx()];
  }
  cb.say("refit " + fixed_number(100.0 * lod.ratio, 1) + "%: undone (a vertex of the input would be " +
         fixed_number(worst, 3) + "% of the diagonal away, over --max-error)");
}

// The edge flips' search costs about a posed original's worth of nearest-point queries per pose and
// sweep; above this size it is a large part of the run for a few percent (bench/README.md).
constexpr size_t kFlipMaxVertices = 20000;
// Passes of the final fit after the flips on those inputs (bench/README.md).
constexpr int kExtraFitPasses = 2;
// Above this size the final fit draws only the LOD's vertices to the original, not points of its faces: on
// the 240k human at 1 % those searches of the posed original cost a third of the fit (bench/README.md).
constexpr size_t kFaceSamplesMaxVertices = 20000;
// Above this size the final fit keeps the decimation's skin weights: on the 240k human fitting them (one more
// search of the LOD per pose) costs more time than its small gain in held-out error is worth to issue 33
// (bench/README.md).
constexpr size_t kWeightFitMaxVertices = 20000;
// A frame animation's stored frames are fitted one by one while vertices times stored frames stay under this:
// each frame is a fit of its own, so the time grows with both (bench/README.md).
constexpr size_t kFrameFitMaxVertexFrames = 2000000;

void refit_chain(const SkinnedMesh& mesh, LodChain& chain, const LodOptions& opt, const LodCallbacks& cb) {
  for (size_t i = 0; i < chain.levels.size(); ++i) {
    cb.report("fitting", double(i) / chain.levels.size());
    auto& [lod, lmesh] = chain.levels[i];
    const auto tr = Clock::now();
    RefitSettings fit;
    fit.threads = thread_count(opt);
    if (mesh.n_vertices() > kFaceSamplesMaxVertices) fit.face_weight = 0.0;
    if (mesh.n_vertices() > kWeightFitMaxVertices) fit.fit_weights = false;
    fit.max_influences = opt.max_influences;
    std::vector<SkinnedMesh::Point> decimated;
    std::vector<Influences> decimated_skin;
    if (lod.deviation_bound >= 0.0) {
      const auto h = influences_handle(lmesh);
      for (auto vh : lmesh.vertices()) {
        decimated.push_back(lmesh.point(vh));
        decimated_skin.push_back(lmesh.property(h, vh));
      }
    }
    RefitReport r = refit_positions(lmesh, mesh, chain.poses.examples, fit);
    // Flips move the surface the deviation bound was proven for: not with one.
    std::string flipped;
    if (lod.deviation_bound < 0.0 && mesh.n_vertices() <= kFlipMaxVertices) {
      FlipFitSettings fs;
      fs.threads = fit.threads;
      const FlipFitReport f = flip_edges_to_fit(lmesh, mesh, chain.poses.examples, fs);
      if (f.flips > 0) flipped = ", " + std::to_string(f.flips) + " edges flipped";
      // Two more passes: each finds the LOD vertices' points on the posed original again, and the pull toward
      // where it starts, from where the last pass left them, so the fit goes on where the first one's anchors
      // held it (and the flipped faces' vertices are fitted to their new faces).
      for (int pass = 0; pass < kExtraFitPasses; ++pass) {
        const RefitReport again = refit_positions(lmesh, mesh, chain.poses.examples, fit);
        r.after = again.after;
        r.rounds += again.rounds;
      }
    }
    // A bound proven in the example poses says nothing of the other stored frames: not with one.
    if (lod.deviation_bound < 0.0 && morph_animated_only(mesh) &&
        mesh.n_vertices() * (morph_targets(mesh).size() + 1) <= kFrameFitMaxVertexFrames) {
      const RefitFramesReport fr = refit_frames(lmesh, mesh, fit);
      if (fr.frames > 0) flipped += ", " + std::to_string(fr.frames) + " frames fitted";
    }
    cb.say("refit " + fixed_number(100.0 * lod.ratio, 1) + "%: residual " + plain(r.before) + " -> " + plain(r.after) +
           " (" + std::to_string(r.rounds) + " rounds" + flipped + ", " + fixed_number(seconds(tr, Clock::now()), 2) +
           " s)");
    if (lod.deviation_bound >= 0.0)
      keep_bound_after_refit(mesh, lmesh, chain.poses.examples, decimated, decimated_skin, lod, opt, cb);
  }
}

// Skeleton LoD (max_joints), then motion LoD (anim_error: clips thinned as far as the LOD's own skinned
// surface allows); returns each LOD's own poses of the held-out frames (empty when nothing was reduced).
std::vector<std::vector<Pose>> reduce_animation(const SkinnedMesh& mesh, LodChain& chain, const LodOptions& opt,
                                                const LodCallbacks& cb) {
  std::vector<std::vector<Pose>> lod_frames;
  const bool animated_lod =
      (!opt.max_joints.empty() || opt.joint_energy > 0.0 || opt.anim_error > 0.0 || opt.keyframes > 0) &&
      !clips(mesh).empty();
  if (!animated_lod) return lod_frames;
  const auto& schedule = chain.poses.schedule;
  const auto& times = schedule.held_out.empty() ? schedule.examples : schedule.held_out;
  // keyframes: the same frames for every LOD, chosen on the original's motion.
  const std::vector<size_t> keys =
      opt.keyframes > 0 ? choose_lod_keyframes(mesh, opt.keyframes, cb) : std::vector<size_t>{};
  for (size_t i = 0; i < chain.levels.size(); ++i) {
    cb.report("reducing the skeleton and clips", double(i) / chain.levels.size());
    SkinnedMesh& lmesh = chain.levels[i].mesh;
    if (!keys.empty()) keep_frames(lmesh, keys);
    if (!opt.max_joints.empty() || opt.joint_energy > 0.0) {
      const int budget =
          opt.max_joints.empty() ? skeleton(lmesh).size() : opt.max_joints[std::min(i, opt.max_joints.size() - 1)];
      reduce_mesh_skeleton(lmesh, budget, opt.max_influences, true, opt.joint_energy);
    }
    if (opt.anim_error > 0.0)
      clips(lmesh) = reduce_clips_to_error(lmesh, opt.anim_error / 100.0 * bbox_diagonal(mesh),
                                           opt.anim_frames ? KeyReductionMethod::Frames : KeyReductionMethod::Channels);
    lod_frames.push_back(poses_at(skeleton(lmesh), clips(lmesh), times));
  }
  return lod_frames;
}

}  // namespace

std::vector<size_t> choose_lod_keyframes(const SkinnedMesh& original, size_t k, const LodCallbacks& cb) {
  const size_t n = frame_times(original).size();
  if (k > n)
    throw LodOptionsError("--keyframes " + std::to_string(k) + " is more than the " + std::to_string(n) + " frames");
  const size_t stride = (original.n_vertices() + kMaxFitnessVertices - 1) / kMaxFitnessVertices;
  std::vector<FramePoints> frames;
  for (size_t f = 0; f < n; ++f) {
    const FramePositions all = frame_positions(original, f);
    FramePoints p;
    for (size_t v = 0; v < all.size(); v += std::max<size_t>(1, stride)) p.push_back(all[v]);
    frames.push_back(std::move(p));
  }
  const InterpolationError err(frames, frame_times(original));
  const KeyframeSelection ga = select_keyframes_ga(err, k);
  if (cb.message) {
    const double even = select_keyframes_even(err, k).error;
    std::string line = "key frames (GA, " + std::to_string(ga.generations) + " generations):";
    for (size_t f : ga.frames) line += " " + std::to_string(f);
    cb.say(line);
    cb.say("  interpolation error over all " + std::to_string(n) + " frames: " + plain(ga.error) +
           " (even spacing: " + plain(even) + ")");
  }
  return ga.frames;
}

LodChain make_lods(const SkinnedMesh& mesh, const LodOptions& opt, const LodCallbacks& cb, const std::string& name) {
  check_lod_options(opt, mesh, name);
  LodChain chain;
  chain.method = lod_method_for(opt, mesh);
  if (morph_animated_only(mesh) && chain.method != "frames" && chain.method != "deform" && chain.method != "static")
    cb.warn("--method " + chain.method +
            " does not see the morph targets of a mesh animated without a skeleton: it decimates the rest shape "
            "(use frames)");
  cb.report("choosing the example poses", 0.0);
  chain.poses = select_lod_poses(mesh, opt, name, cb, opt.poses != LodOptions().poses);
  cb.report("decimating", 0.0);
  std::vector<double> ratios;
  std::vector<size_t> targets;
  lod_targets(opt, mesh, ratios, targets);
  const auto t0 = Clock::now();
  chain.levels = decimate_chain(mesh, chain.poses.examples, targets, ratios, opt, chain.method, cb);
  if (opt.refit) refit_chain(mesh, chain, opt, cb);
  const auto t1 = Clock::now();
  const std::vector<std::vector<Pose>> lod_frames = reduce_animation(mesh, chain, opt, cb);
  const bool frame_animation = !frame_times(mesh).empty();
  for (auto& [lod, lmesh] : chain.levels) {
    // A frame animation's keys are its stored frames.
    lod.keys = frame_animation ? frame_times(lmesh).size() : count_keys(clips(lmesh));
    lod.joints = skeleton(lmesh).size();
    lod.max_influences = max_influences_of(lmesh);
  }
  if (opt.evaluate) {
    cb.report("measuring the held-out error", 0.0);
    std::vector<const SkinnedMesh*> lods;
    for (const auto& level : chain.levels) lods.push_back(&level.mesh);
    EvaluateOptions eo;
    eo.threads = thread_count(opt);
    eo.per_vertex_error = opt.per_vertex_error;
    const auto errors = evaluate_lods(mesh, lods, chain.poses.heldout, lod_frames, eo, cb);
    for (size_t i = 0; i < errors.size(); ++i) {
      LodReport& lod = chain.levels[i].report;
      lod.evaluated = true;
      lod.rms = errors[i].rms;
      lod.hausdorff = errors[i].hausdorff;
      lod.switch_hint = switch_hint(mesh, lod.hausdorff);
      lod.vertex_error = errors[i].vertex_error;
    }
  }
  chain.decimate_seconds = seconds(t0, t1);
  chain.evaluate_seconds = seconds(t1, Clock::now());
  return chain;
}

}  // namespace OpenMeshSkinned
