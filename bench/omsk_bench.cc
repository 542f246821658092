// omsk-bench: the papers' workloads, each decimated by OpenMesh's static quadric and by the skinned modules
// in the same process, timed; one JSON object per line per workload.
#include <OpenMeshSkinned/Decimater/LazyDecimaterT.hh>
#include <OpenMeshSkinned/Decimater/ModSkinnedFoldOverT.hh>
#include <OpenMeshSkinned/Decimater/ModSkinnedQuadricT.hh>
#include <OpenMeshSkinned/Decimater/ModWeightCapT.hh>
#include <OpenMeshSkinned/Eval/SurfaceDistance.hh>
#include <OpenMeshSkinned/IO/ExportGltf.hh>
#include <OpenMeshSkinned/IO/Import.hh>
#include <OpenMeshSkinned/Mesh/LoopSubdivision.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>
#include <OpenMeshSkinned/Platform/HugePages.hh>
#include <OpenMeshSkinned/Skin/PoseSchedule.hh>

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <sys/resource.h>

#include <chrono>
#include <iostream>

using Mesh = OpenMeshSkinned::SkinnedMesh;
using json = nlohmann::ordered_json;

namespace {

std::string models_dir = "/usr/share/assimp/models";

double peak_rss_mb() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024.0;
}

template <typename F>
double seconds(F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

size_t live_faces(const Mesh& m) {
  size_t n = 0;
  for (auto f : m.faces()) (void)f, ++n;
  return n;
}

using Classic = OpenMesh::Decimater::DecimaterT<Mesh>;
using Lazy = OpenMeshSkinned::LazyDecimaterT<Mesh>;

void set_threads(Classic& dec, int n, OpenMeshSkinned::CollapseSolverT<Mesh>& solver) {
  (void)dec;
  solver.set_threads(n);
}
void set_threads(Lazy& dec, int n, OpenMeshSkinned::CollapseSolverT<Mesh>&) { dec.set_threads(n); }
json driver_counts(const Classic&) { return json::object(); }
json driver_counts(const Lazy& dec) {
  const auto& s = dec.stats();
  return {{"priced", s.priced}, {"stale_pops", s.stale}, {"refused_pops", s.refused}, {"collapses", s.collapses}};
}

// The reference: OpenMesh's own static modules. Returns seconds (the mesh copy is not timed).
template <typename Decimater>
double time_static(const Mesh& input, size_t target) {
  Mesh mesh = input;
  return seconds([&] {
    Decimater dec(mesh);
    OpenMesh::Decimater::ModQuadricT<Mesh>::Handle hq;
    OpenMesh::Decimater::ModNormalFlippingT<Mesh>::Handle hn;
    dec.add(hq);
    dec.add(hn);
    dec.initialize();
    dec.decimate_to_faces(0, target);
  });
}

// The skinned modules as the app uses them (fold-over at 90 degrees). Returns the solver's counters.
template <typename Decimater>
json decimate_skinned(Mesh& mesh, size_t target, int cap, OpenMeshSkinned::CapStrategy strategy, int threads = 1) {
  Decimater dec(mesh);
  OpenMeshSkinned::ModSkinnedQuadricT<Mesh>::Handle hq;
  OpenMeshSkinned::ModWeightCapT<Mesh>::Handle hc;
  OpenMeshSkinned::ModSkinnedFoldOverT<Mesh>::Handle hf;
  dec.add(hq);
  dec.add(hc);
  dec.add(hf);
  dec.module(hc).set_max_influences(cap);
  dec.module(hc).set_strategy(strategy);
  set_threads(dec, threads, dec.module(hq).solver());
  dec.initialize();
  dec.decimate_to_faces(0, target);
  const auto& st = dec.module(hq).solver().stats();
  json j = {{"solves", st.solves},
            {"cache_hits", st.cache_hits},
            {"ceres_calls", st.weights.ceres_calls},
            {"weight_solves", st.weights.solves},
            {"deferred", st.deferred},
            {"forced_flips", st.forced_flips}};
  j.update(driver_counts(dec));
  return j;
}

// Mean held-out RMS (% of the diagonal) of a LOD, in frames of the clips between the example poses.
double heldout_rms(const Mesh& original, Mesh lod) {
  if (OpenMeshSkinned::clips(original).empty()) return 0.0;
  lod.garbage_collection();
  const auto sched = OpenMeshSkinned::make_pose_schedule(OpenMeshSkinned::clips(original),
                                                         int(OpenMeshSkinned::example_poses(original).size()), -1);
  const auto frames =
      OpenMeshSkinned::poses_at(OpenMeshSkinned::skeleton(original), OpenMeshSkinned::clips(original), sched.held_out);
  double rms = 0.0;
  for (const auto& pose : frames)
    rms += OpenMeshSkinned::surface_distance(OpenMeshSkinned::posed_soup(original, pose),
                                             OpenMeshSkinned::posed_soup(lod, pose), 20000)
               .rms;
  return 100.0 * rms / std::max<size_t>(1, frames.size()) / OpenMeshSkinned::bbox_diagonal(original);
}

bool g_heldout = true;
bool g_lazy_only = false;
bool g_classic_only = false;
bool g_static_only = false;
int g_threads = 2;

// Each workload is decimated by OpenMesh's DecimaterT and by LazyDecimaterT (one thread, then
// g_threads), with the static and the skinned modules, in the same process.
json run_workload(const std::string& name, const Mesh& input, size_t target, OpenMeshSkinned::CapStrategy strategy) {
  if (g_classic_only) {  // for profiling the skinned modules under DecimaterT alone
    Mesh classic = input;
    json counts;
    const double s = seconds([&] { counts = decimate_skinned<Classic>(classic, target, 4, strategy); });
    json j = {{"workload", name}, {"skinned_s", s}, {"triangles_out", live_faces(classic)}, {"counts", counts}};
    if (g_heldout) j["heldout_rms_decimatert"] = heldout_rms(input, classic);
    return j;
  }
  if (g_static_only)  // for profiling the reference alone
    return {{"workload", name}, {"static_s", time_static<Classic>(input, target)}};
  if (g_lazy_only) {  // for profiling the lazy driver alone
    Mesh lazy = input;
    json counts;
    const double s = seconds([&] { counts = decimate_skinned<Lazy>(lazy, target, 4, strategy, g_threads); });
    json j = {{"workload", name}, {"skinned_lazy_s", s}, {"triangles_out_lazy", live_faces(lazy)}, {"counts", counts}};
    if (g_heldout) j["heldout_rms_lazy"] = heldout_rms(input, lazy);
    return j;
  }
  const double static_s = time_static<Classic>(input, target);
  const double static_lazy_s = time_static<Lazy>(input, target);
  Mesh classic = input, lazy = input, lazy_n = input;
  json counts, lazy_counts;
  const double skinned_s = seconds([&] { counts = decimate_skinned<Classic>(classic, target, 4, strategy); });
  const double lazy_s = seconds([&] { lazy_counts = decimate_skinned<Lazy>(lazy, target, 4, strategy, 1); });
  const double lazy_n_s = seconds([&] { decimate_skinned<Lazy>(lazy_n, target, 4, strategy, g_threads); });
  json j = {{"workload", name},
            {"triangles_in", input.n_faces()},
            {"triangles_out", live_faces(classic)},
            {"triangles_out_lazy", live_faces(lazy)},
            {"target", target},
            {"poses", OpenMeshSkinned::example_poses(input).size()},
            {"static_s", static_s},
            {"static_lazy_s", static_lazy_s},
            {"skinned_s", skinned_s},
            {"skinned_lazy_s", lazy_s},
            {"skinned_lazy_threads", g_threads},
            {"skinned_lazy_threads_s", lazy_n_s},
            {"ratio", skinned_s / static_s},
            {"ratio_lazy", lazy_s / static_s}};
  j.update(counts);
  j["lazy_solves"] = lazy_counts["solves"];
  j["lazy_cache_hits"] = lazy_counts["cache_hits"];
  j["lazy_forced_flips"] = lazy_counts["forced_flips"];
  if (g_heldout) {
    j["heldout_rms_decimatert"] = heldout_rms(input, classic);
    j["heldout_rms_lazy"] = heldout_rms(input, lazy);
  }
  j["peak_rss_mb"] = peak_rss_mb();
  return j;
}

Mesh column(int around, int along, int poses) {
  Mesh m = OpenMeshSkinned::make_square_column(around, along);
  if (poses != 4) {
    const auto& clip = OpenMeshSkinned::clips(m)[0];
    OpenMeshSkinned::example_poses(m) = OpenMeshSkinned::sample_poses_evenly(OpenMeshSkinned::skeleton(m), clip, poses);
  }
  return m;
}

Mesh leg() {
  // DeCoro's leg at a size between the paper's models: 128 x 128 x 2 = 32,768 triangles, knee 0, 45, 90.
  Mesh m = OpenMeshSkinned::make_bending_cylinder(128, 128);
  OpenMeshSkinned::example_poses(m) =
      OpenMeshSkinned::sample_poses_evenly(OpenMeshSkinned::skeleton(m), OpenMeshSkinned::clips(m)[0], 3);
  return m;
}

// Testwuson Loop-subdivided \p rounds times: 3,732 triangles times 4 per round (3: 238,848; 4: 955,392).
Mesh human(int rounds = 3) {
  Mesh m;
  OpenMeshSkinned::import_skinned(models_dir + "/X/Testwuson.X", m);
  for (int i = 0; i < rounds; ++i) m = OpenMeshSkinned::loop_subdivide(m);
  const auto sched = OpenMeshSkinned::make_pose_schedule(OpenMeshSkinned::clips(m), 9, -1);
  OpenMeshSkinned::example_poses(m) =
      OpenMeshSkinned::poses_at(OpenMeshSkinned::skeleton(m), OpenMeshSkinned::clips(m), sched.examples);
  return m;
}

// Which cap strategy keeps the posed surface closer: a real character to 25% with the cap, judged by the
// mean held-out RMS distance (% of the rest bounding-box diagonal).
json cap_strategy(const std::string& file, int cap, OpenMeshSkinned::CapStrategy st) {
  Mesh original;
  OpenMeshSkinned::import_skinned(models_dir + "/" + file, original);
  const auto& clips = OpenMeshSkinned::clips(original);
  const auto sched = OpenMeshSkinned::make_pose_schedule(clips, 8, -1);
  OpenMeshSkinned::example_poses(original) =
      OpenMeshSkinned::poses_at(OpenMeshSkinned::skeleton(original), clips, sched.examples);
  Mesh mesh = original;
  const double secs = seconds([&] { decimate_skinned<Lazy>(mesh, original.n_faces() / 4, cap, st); });
  mesh.garbage_collection();
  const auto frames = OpenMeshSkinned::poses_at(OpenMeshSkinned::skeleton(original), clips, sched.held_out);
  double rms = 0.0;
  for (const auto& pose : frames)
    rms += OpenMeshSkinned::surface_distance(OpenMeshSkinned::posed_soup(original, pose),
                                             OpenMeshSkinned::posed_soup(mesh, pose), 20000)
               .rms;
  rms = 100.0 * rms / frames.size() / OpenMeshSkinned::bbox_diagonal(original);
  return {{"workload", "cap-strategy"},
          {"input", file},
          {"cap", cap},
          {"strategy", st == OpenMeshSkinned::CapStrategy::TopN ? "topn" : "greedy"},
          {"triangles_out", mesh.n_faces()},
          {"heldout_rms", rms},
          {"seconds", secs}};
}

}  // namespace

int main(int argc, char** argv) {
  // As the CLI runs (every run in this process alike, the static reference too);
  // GLIBC_TUNABLES=glibc.malloc.hugetlb=0 measures without.
  OpenMeshSkinned::relaunch_with_huge_pages(argv);
  CLI::App app{"omsk-bench: skinned vs static decimation on the papers' workloads (JSON lines on stdout)"};
  std::string workload;
  bool all = false;
  std::string strategy = "topn";
  app.add_option("--workload", workload, "column | leg | human | sweep-triangles | sweep-poses | cap-strategy");
  app.add_flag("--all", all, "Every workload");
  app.add_option("--strategy", strategy, "Weight-cap strategy: topn (default) or greedy");
  app.add_option("--models", models_dir, "Folder of assimp's test models");
  app.add_option("--threads", g_threads, "Threads of the second LazyDecimaterT run (default 2)");
  app.add_flag("!--no-heldout", g_heldout, "Skip the held-out error of the skinned LODs");
  app.add_flag("--lazy-only", g_lazy_only, "Only the skinned modules under LazyDecimaterT on --threads (profiling)");
  app.add_flag("--classic-only", g_classic_only, "Only the skinned modules under OpenMesh's DecimaterT (profiling)");
  app.add_flag("--static-only", g_static_only, "Only OpenMesh's static modules under its DecimaterT (profiling)");
  std::vector<std::string> write;
  app.add_option("--write", write,
                 "NAME FILE: write a benchmark character as GLB and exit. human (Testwuson subdivided three "
                 "times), human1, human2, human4 (once, twice, four times: 14,928, 59,712, 955,392 triangles), leg, "
                 "column, wuson8 (Testwuson with its skin diffused "
                 "over 8 bones)")
      ->expected(2);
  CLI11_PARSE(app, argc, argv);
  if (!write.empty()) {
    try {
      const std::string& name = write[0];
      Mesh m;
      if (name == "human") {
        m = human();
      } else if (name == "human1" || name == "human2" || name == "human4") {
        m = human(name[5] - '0');
      } else if (name == "leg") {
        m = OpenMeshSkinned::make_bending_cylinder();
      } else if (name == "column") {
        m = OpenMeshSkinned::make_square_column();
      } else if (name == "wuson8") {
        // 3 rounds of smoothing the weight field, 8 bones kept: every vertex near a joint gets 5-8 bones.
        OpenMeshSkinned::import_skinned(models_dir + "/X/Testwuson.X", m);
        OpenMeshSkinned::diffuse_skin_weights(m, 3, 8);
      } else {
        std::cerr << "omsk-bench: --write: unknown character " << name << "\n";
        return 2;
      }
      OpenMeshSkinned::export_gltf(m, write[1]);
    } catch (const std::exception& e) {
      std::cerr << "omsk-bench: " << e.what() << "\n";
      return 1;
    }
    return 0;
  }
  if (!all && workload.empty()) {
    std::cerr << "omsk-bench: give --workload NAME or --all\n";
    return 2;
  }
  const auto strat = strategy == "greedy" ? OpenMeshSkinned::CapStrategy::Greedy : OpenMeshSkinned::CapStrategy::TopN;
  auto want = [&](const char* w) { return all || workload == w; };
  bool ran = false;
  try {
    if (want("column")) {
      std::cout << run_workload("column", column(128, 448, 4), 70, strat).dump() << std::endl;
      ran = true;
    }
    if (want("leg")) {
      std::cout << run_workload("leg", leg(), 70, strat).dump() << std::endl;
      ran = true;
    }
    if (want("human")) {
      std::cout << run_workload("human", human(), 70, strat).dump() << std::endl;
      ran = true;
    }
    if (want("sweep-triangles")) {
      // x4 per step: 15,360 / 61,440 / 245,760 / 983,040 triangles, 4 poses, down to 1%.
      for (auto [a, l] : {std::pair{64, 120}, {128, 240}, {256, 480}, {512, 960}}) {
        const Mesh m = column(a, l, 4);
        std::cout << run_workload("sweep-triangles", m, m.n_faces() / 100, strat).dump() << std::endl;
      }
      ran = true;
    }
    if (want("sweep-poses")) {
      for (int p : {1, 2, 4, 8, 16, 32}) {
        const Mesh m = column(128, 240, p);
        std::cout << run_workload("sweep-poses", m, m.n_faces() / 100, strat).dump() << std::endl;
      }
      ran = true;
    }
    if (want("cap-strategy")) {
      for (const char* file : {"X/Testwuson.X", "FBX/animation_with_skeleton.fbx"})
        for (int cap : {1, 2, 3})
          for (auto st : {OpenMeshSkinned::CapStrategy::TopN, OpenMeshSkinned::CapStrategy::Greedy})
            std::cout << cap_strategy(file, cap, st).dump() << std::endl;
      ran = true;
    }
  } catch (const std::exception& e) {
    std::cerr << "omsk-bench: " << e.what() << "\n";
    return 1;
  }
  if (!ran) {
    std::cerr << "omsk-bench: unknown workload " << workload << "\n";
    return 2;
  }
  return 0;
}
