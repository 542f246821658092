#include "LodMethods.hh"

#include <OpenMeshSkinned/Decimater/Baselines/ModDeformationSensitiveT.hh>
#include <OpenMeshSkinned/Decimater/Baselines/ModPoseIndependentQuadricT.hh>
#include <OpenMeshSkinned/Decimater/Baselines/ModRestPoseQuadricT.hh>
#include <OpenMeshSkinned/Decimater/Baselines/ModTriangleCompactnessT.hh>
#include <OpenMeshSkinned/Decimater/LazyDecimaterT.hh>
#include <OpenMeshSkinned/Decimater/ModDeformationWeightedQuadricT.hh>
#include <OpenMeshSkinned/Decimater/ModDeviationBoundT.hh>
#include <OpenMeshSkinned/Decimater/ModFrameFoldOverT.hh>
#include <OpenMeshSkinned/Decimater/ModFrameQuadricT.hh>
#include <OpenMeshSkinned/Decimater/ModJointGuardT.hh>
#include <OpenMeshSkinned/Decimater/ModSkinnedFoldOverT.hh>
#include <OpenMeshSkinned/Decimater/ModSkinnedQuadricT.hh>
#include <OpenMeshSkinned/Decimater/ModWeightCapT.hh>
#include <OpenMeshSkinned/Eval/SurfaceDistance.hh>
#include <OpenMeshSkinned/Lod/LodAreaExponent.hh>
#include <OpenMeshSkinned/Mesh/SurfaceArea.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#include <OpenMesh/Tools/Decimater/Observer.hh>

#include <algorithm>
#include <chrono>
#include <numeric>
#include <optional>
#include <stdexcept>

namespace OpenMeshSkinned {

namespace {

using Clock = std::chrono::steady_clock;
// The lazy driver: verdicts asked right before each collapse, edges solved ahead on --threads threads.
using Mesh = SkinnedMesh;
using Decimater = LazyDecimaterT<Mesh>;

// The modules a chain may use; each method adds its own.
struct Handles {
  ModSkinnedQuadricT<Mesh>::Handle skinned;
  ModSkinnedFoldOverT<Mesh>::Handle fold_over;
  ModWeightCapT<Mesh>::Handle cap;
  ModJointGuardT<Mesh>::Handle guard;
  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle quadric;
  OpenMesh::Decimater::ModNormalFlippingT<Mesh>::Handle normal_flipping;
  ModRestPoseQuadricT<Mesh>::Handle rest;
  ModDeformationSensitiveT<Mesh>::Handle dsd;
  ModPoseIndependentQuadricT<Mesh>::Handle decoro;
  ModTriangleCompactnessT<Mesh>::Handle compact;
  ModFrameQuadricT<Mesh>::Handle frames;
  ModDeformationWeightedQuadricT<Mesh>::Handle deform;
  ModFrameFoldOverT<Mesh>::Handle frame_fold;
  ModDeviationBoundT<Mesh>::Handle bound;
};

struct MethodModules {
  LodMethod method;
  void (*add)(Decimater&, Handles&);  // every method but OpenMesh's own gets the skinned fold-over check
};

const std::vector<MethodModules>& table() {
  static const std::vector<MethodModules> t = {
      {{"skinned", "Landreneau-Schaefer skinned quadric; the default"},
       [](Decimater& d, Handles& h) { d.add(h.skinned), d.add(h.fold_over); }},
      {{"decoro", "DeCoro-Rusinkiewicz pose-independent quadric over the clips"},
       [](Decimater& d, Handles& h) { d.add(h.decoro), d.add(h.fold_over); }},
      {{"dsd", "Mohr-Gleicher deformation-sensitive decimation"},
       [](Decimater& d, Handles& h) { d.add(h.dsd), d.add(h.fold_over); }},
      {{"rest", "rest-pose quadric, distance-interpolated weights"},
       [](Decimater& d, Handles& h) { d.add(h.rest), d.add(h.fold_over); }},
      {{"compact", "Savoye-Meyer triangle compactness, barycentre placement, power skinning"},
       [](Decimater& d, Handles& h) { d.add(h.compact), d.add(h.fold_over); }},
      {{"frames",
        "per-frame quadrics of the vertices' trajectories, placement along the edge; sees "
        "morph-target frames: the default for meshes animated without a skeleton"},
       [](Decimater& d, Handles& h) { d.add(h.frames); }},
      {{"deform", "the deformation-analysis report's importance-weighted quadric, endpoint placement"},
       [](Decimater& d, Handles& h) { d.add(h.deform), d.add(h.frame_fold); }},
      {{"static", "OpenMesh's ModQuadricT and ModNormalFlippingT as they are"},
       [](Decimater& d, Handles& h) { d.add(h.quadric), d.add(h.normal_flipping); }},
  };
  return t;
}

// The share of the chain's collapses done, to the caller; its answer can stop the run.
class Progress : public OpenMesh::Decimater::Observer {
public:
  Progress(const LodCallbacks& callbacks, size_t total)
      : Observer(std::max<size_t>(1, total / 200)), callbacks_(callbacks), total_(std::max<size_t>(1, total)) {}
  void set_done_before(size_t n) { before_ = n; }
  void notify(size_t step) override {
    if (callbacks_.progress && !callbacks_.progress("decimating", std::min(1.0, double(before_ + step) / total_)))
      cancelled_ = true;
  }
  bool abort() const override { return cancelled_; }
  bool cancelled() const { return cancelled_; }

private:
  const LodCallbacks& callbacks_;
  size_t total_, before_ = 0;
  bool cancelled_ = false;
};

// Faces not deleted (n_faces() counts deleted ones until garbage collection).
size_t live_faces(const Mesh& mesh) {
  size_t n = 0;
  for (auto fh : mesh.faces()) (void)fh, ++n;
  return n;
}

// Connected pieces of a mesh without deleted elements.
size_t count_pieces(const Mesh& mesh) {
  std::vector<int> parent(mesh.n_vertices());
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (auto eh : mesh.edges())
    parent[root(mesh.to_vertex_handle(mesh.halfedge_handle(eh, 0)).idx())] =
        root(mesh.from_vertex_handle(mesh.halfedge_handle(eh, 0)).idx());
  size_t n = 0;
  for (auto vh : mesh.vertices()) n += !mesh.is_isolated(vh) && root(vh.idx()) == vh.idx();
  return n;
}

// Collapses the shared solver made at a fallback placement so far (0 without the skinned fold-over check).
size_t fold_fallbacks(Decimater& dec, Handles& h) {
  return h.fold_over.is_valid() ? dec.module(h.fold_over).solver().stats().fold_fallbacks : 0;
}

// The method's modules, then the ones the options add, set up.
void add_modules(Decimater& dec, Handles& h, const MethodModules& m, const LodOptions& opt, const std::string& method,
                 const LodCallbacks& callbacks, double diagonal, double area_exponent, double area_floor) {
  m.add(dec, h);
  // The frame methods' skins were capped up front: the cap module would only bring in the skinned solver.
  if (!h.frame_fold.is_valid() && !h.frames.is_valid()) {
    dec.add(h.cap);
    dec.module(h.cap).set_max_influences(opt.max_influences);
  }
  if (opt.joint_guard > 0.0) {
    dec.add(h.guard);
    dec.module(h.guard).set_tau(opt.joint_guard);
  }
  if (h.frames.is_valid()) {
    dec.module(h.frames).set_area_exponent(area_exponent);
    dec.module(h.frames).set_area_floor(area_floor);
  }
  if (h.skinned.is_valid()) {
    dec.module(h.skinned).set_area_exponent(area_exponent);
    dec.module(h.skinned).set_area_floor(area_floor);
    dec.module(h.skinned).set_normal_weight(opt.normal_weight);
  }
  // The bound needs the shared solver's placement and poses: the frame methods place vertices themselves.
  if (opt.max_error > 0.0) {
    if (!h.frame_fold.is_valid() && !h.frames.is_valid()) {
      dec.add(h.bound);
      dec.module(h.bound).set_max_deviation(opt.max_error / 100.0 * diagonal);
    } else {
      callbacks.warn("--max-error does not apply to --method " + method +
                     " (it places vertices itself); its LODs are not bounded");
    }
  }
  if (opt.threads > 0) dec.set_threads(opt.threads);
}

void set_fold(Decimater& dec, Handles& h, double angle, bool fallback) {
  if (h.fold_over.is_valid()) {
    dec.module(h.fold_over).set_max_angle(angle);
    dec.module(h.fold_over).set_fallback_placement(fallback);
  }
  if (h.frame_fold.is_valid()) dec.module(h.frame_fold).set_max_angle(angle);
  if (h.frames.is_valid()) dec.module(h.frames).set_max_fold_angle(angle);
}

// Reach the requested count: when every collapse left folds a face by more than 90 degrees in some
// pose, make such collapses at the cheapest placement that folds nothing, then allow a larger turn step
// by step (and say so), unless --strict-fold, or --max-error, which puts the bound before the count
// (what stopped may be the bound: folds would buy nothing but folds). Returns the collapses made.
size_t relax_folds(Decimater& dec, Handles& h, Mesh& mesh, size_t target, const LodOptions& opt,
                   const Progress& progress, LodReport& lod) {
  if (opt.strict_fold || h.bound.is_valid() ||
      !(h.fold_over.is_valid() || h.frame_fold.is_valid() || h.frames.is_valid()))
    return 0;
  size_t collapses = 0;
  const size_t fallbacks_before = fold_fallbacks(dec, h);
  for (double angle : {90.0, 120.0, 150.0, 175.0}) {
    const size_t now = live_faces(mesh);
    // Nothing to relax when no collapse at all is left that keeps the mesh manifold.
    if (now <= target || !dec.topology_allows_a_collapse()) break;
    // At 90 degrees only the placements change: the cheapest one that folds nothing.
    if (angle == 90.0 && !h.fold_over.is_valid()) continue;
    set_fold(dec, h, angle, true);
    collapses += dec.decimate_to_faces(0, target + (mesh.n_faces() - now));
    if (progress.cancelled()) throw LodCancelled();
    lod.fold_limit = angle;
  }
  lod.fold_fallbacks = fold_fallbacks(dec, h) - fallbacks_before;
  set_fold(dec, h, 90.0, false);
  return collapses;
}

// A level's mesh without the deleted elements, at its own size, and what the report says of it.
void snapshot(Mesh& snap, LodReport& lod) {
  snap.garbage_collection();
  for (auto vh : snap.vertices()) snap.status(vh).set_locked(false);
  // Garbage collection keeps the arrays' capacity (the full mesh's, 62 MB on the human): a copy holds
  // only the level's size, and clear() frees the arrays before the copy is assigned back.
  {
    const Mesh compact = snap;
    snap.clear();
    snap = compact;
  }
  lod.faces = snap.n_faces();
  if (lod.at_floor) lod.pieces = count_pieces(snap);
  lod.vertices = snap.n_vertices();
  lod.max_influences = max_influences_of(snap);
}

}  // namespace

int max_influences_of(const Mesh& mesh) {
  const auto h = influences_handle(mesh);
  int n = 0;
  for (auto vh : mesh.vertices()) n = std::max(n, mesh.property(h, vh).size());
  return n;
}

const std::vector<LodMethod>& lod_methods() {
  static const std::vector<LodMethod> m = [] {
    std::vector<LodMethod> out;
    for (const auto& t : table()) out.push_back(t.method);
    return out;
  }();
  return m;
}

std::string lod_method_names() {
  const auto& m = lod_methods();
  std::string s;
  for (size_t i = 0; i < m.size(); ++i) s += (i == 0 ? "" : i + 1 == m.size() ? " or " : ", ") + std::string(m[i].name);
  return s;
}

bool is_lod_method(const std::string& name) {
  const auto& m = lod_methods();
  return std::any_of(m.begin(), m.end(), [&](const LodMethod& x) { return name == x.name; });
}

void keep_as_reference_only(Mesh& mesh) {
  // Requested by the traits and again by request_skinned_attributes(): released until gone.
  while (mesh.has_halfedge_normals()) mesh.release_halfedge_normals();
  while (mesh.has_halfedge_texcoords2D()) mesh.release_halfedge_texcoords2D();
  while (mesh.has_face_normals()) mesh.release_face_normals();
}

std::vector<LodLevel> decimate_chain(const Mesh& input, const std::vector<Pose>& examples,
                                     const std::vector<size_t>& targets, const std::vector<double>& ratios,
                                     const LodOptions& opt, const std::string& method, const LodCallbacks& callbacks) {
  const auto it =
      std::find_if(table().begin(), table().end(), [&](const MethodModules& t) { return method == t.method.name; });
  if (it == table().end()) throw std::logic_error("unknown method " + method);
  // OpenMesh's meshes have no move constructor (their kernels declare destructors): a "moved" mesh is
  // copied, and on a large character each copy is ~62 MB at the decimation's peak. So the chain is sized
  // up front and its last level is the working mesh, decimated in place; only earlier levels are copies.
  std::vector<LodLevel> out(targets.size());
  Mesh& mesh = out.back().mesh;
  mesh = input;
  example_poses(mesh) = examples;
  if (callbacks.input_copied) callbacks.input_copied();
  const size_t n_vertices_in = mesh.n_vertices();
  // The frame methods never change a skin, so the cap is applied once, up front: each vertex keeps its
  // heaviest --max-influences bones, renormalised (its trajectories are then those of the capped skin).
  if (method == "frames" || method == "deform") {
    const auto h = influences_handle(mesh);
    for (auto vh : mesh.vertices())
      if (mesh.property(h, vh).size() > opt.max_influences) mesh.property(h, vh).keep_heaviest(opt.max_influences);
  }
  // Held in an optional so that the solver's caches are freed before the last snapshot is taken.
  std::optional<Decimater> dec(std::in_place, mesh);
  Handles h;
  const double diagonal = bbox_diagonal(mesh);
  // In the coarsest level's mean triangles: a feature that level could still show keeps the per-area price.
  const double area_floor = opt.area_floor * surface_area(mesh) / double(std::max<size_t>(targets.back(), 1));
  const double area_exponent =
      method == "frames"
          ? lod_frames_area_exponent(opt, double(targets.back()) / double(std::max<size_t>(mesh.n_faces(), 1)))
          : lod_area_exponent(opt, mesh.n_vertices());
  add_modules(*dec, h, *it, opt, method, callbacks, diagonal, area_exponent, area_floor);
  if (!dec->initialize()) throw std::runtime_error("the decimater did not initialize");
  Progress progress(callbacks, n_vertices_in - targets.back() / 2);
  dec->set_observer(&progress);

  const auto t0 = Clock::now();
  size_t collapses = 0;
  for (size_t i = 0; i < targets.size(); ++i) {
    progress.set_done_before(collapses);
    // decimate_to_faces counts deleted faces too until garbage collection, which would also renumber the
    // vertices under the solver's feet: aim at the target plus the faces already deleted instead.
    collapses += dec->decimate_to_faces(0, targets[i] + (mesh.n_faces() - live_faces(mesh)));
    if (progress.cancelled()) throw LodCancelled();
    LodReport lod;
    collapses += relax_folds(*dec, h, mesh, targets[i], opt, progress, lod);
    lod.at_floor = live_faces(mesh) > targets[i] && !dec->topology_allows_a_collapse();
    lod.ratio = ratios[i];
    lod.target = targets[i];
    lod.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    if (h.bound.is_valid()) lod.deviation_bound = 100.0 * dec->module(h.bound).bound() / diagonal;
    if (h.fold_over.is_valid()) lod.non_finite_weights = dec->module(h.fold_over).solver().stats().weights.non_finite;
    if (i + 1 == targets.size()) dec.reset();
    // Earlier levels are copies, with the deleted elements until garbage collection: the working mesh
    // cannot be renumbered under the solver.
    if (i + 1 < targets.size()) out[i].mesh = mesh;
    snapshot(out[i].mesh, lod);
    out[i].report = lod;
  }
  return out;
}

}  // namespace OpenMeshSkinned
