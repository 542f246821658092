// skinned-decimate: LOD chains from skinned characters, judged in poses the decimater never saw.
#include <OpenMeshSkinned/Decimater/Baselines/ModDeformationSensitiveT.hh>
#include <OpenMeshSkinned/Decimater/Baselines/ModPoseIndependentQuadricT.hh>
#include <OpenMeshSkinned/Decimater/Baselines/ModRestPoseQuadricT.hh>
#include <OpenMeshSkinned/Decimater/ModSkinnedFoldOverT.hh>
#include <OpenMeshSkinned/Decimater/ModSkinnedQuadricT.hh>
#include <OpenMeshSkinned/Decimater/ModWeightCapT.hh>
#include <OpenMeshSkinned/Eval/SurfaceDistance.hh>
#include <OpenMeshSkinned/IO/ExportGltf.hh>
#include <OpenMeshSkinned/IO/Import.hh>
#include <OpenMeshSkinned/IO/OutputSet.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>
#include <OpenMeshSkinned/Skin/PoseSchedule.hh>

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#include <OpenMesh/Tools/Decimater/Observer.hh>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace fs = std::filesystem;
using Mesh = OpenMeshSkinned::SkinnedMesh;
using Clock = std::chrono::steady_clock;
using json = nlohmann::ordered_json;

namespace {

struct Options {
  std::string input, output, report, pose_clip, method = "skinned";
  double ratio = 0.0;
  size_t faces = 0;
  std::vector<double> lods;
  int max_influences = 4;
  int poses = 8;
  bool quiet = false;
  bool poses_given = false;
  bool ratio_given = false;
  bool compare = false;
  bool bind_pose = true;
  bool faces_given = false;
  bool isolate = true;
  size_t max_memory_mb = 8192;
  double time_limit = 300.0;
};

// Past this many example poses the schedule stops being a sample of the clips and becomes the clips.
constexpr int kMaxPoses = 1000;
// What one example or held-out pose costs per vertex: posed position and pose quadric in the solver,
// posed copies in the evaluation (measured: about 240 KB per pose on a 2,000-vertex character).
constexpr size_t kBytesPerVertexPose = 128;

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Lod {
  double ratio = 0.0;
  size_t target = 0;  // triangles asked for
  size_t faces = 0, vertices = 0;
  double seconds = 0.0;
  int max_influences = 0;
  double rms = 0.0, hausdorff = 0.0;  // % of the rest-pose bounding-box diagonal
  std::string file;
};

// Percent of collapses on a terminal, once the run has taken a second.
class Progress : public OpenMesh::Decimater::Observer {
public:
  Progress(bool on, size_t total, std::string label)
      : Observer(std::max<size_t>(1, total / 200)), on_(on), total_(std::max<size_t>(1, total)), label_(std::move(label)) {}
  void set_done_before(size_t n) { before_ = n; }
  void notify(size_t step) override {
    if (!on_ || Clock::now() - start_ < std::chrono::seconds(1)) return;
    std::fprintf(stderr, "\r%s: %3d%% of collapses", label_.c_str(), int(100.0 * (before_ + step) / total_));
    shown_ = true;
  }
  ~Progress() override {
    if (shown_) std::fprintf(stderr, "\r%*s\r", int(label_.size()) + 20, "");
  }

private:
  bool on_;
  size_t total_, before_ = 0;
  std::string label_;
  Clock::time_point start_ = Clock::now();
  bool shown_ = false;
};

int max_influences_of(const Mesh& mesh) {
  const auto h = OpenMeshSkinned::influences_handle(mesh);
  int n = 0;
  for (auto vh : mesh.vertices()) n = std::max(n, mesh.property(h, vh).size());
  return n;
}

// Decimates a copy of \p input through every target in one pass (the multiresolution hierarchy: each
// level continues from the previous one) and snapshots the mesh as it passes each target.
std::vector<std::pair<Lod, Mesh>> build_chain(const Mesh& input, const std::vector<size_t>& targets,
                                              const std::vector<double>& ratios, const Options& opt,
                                              const std::string& method, const std::string& label) {
  Mesh mesh = input;
  OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
  OpenMeshSkinned::ModSkinnedQuadricT<Mesh>::Handle hq;
  OpenMeshSkinned::ModSkinnedFoldOverT<Mesh>::Handle hf;
  OpenMeshSkinned::ModWeightCapT<Mesh>::Handle hc;
  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle hs;
  OpenMesh::Decimater::ModNormalFlippingT<Mesh>::Handle hn;
  OpenMeshSkinned::ModRestPoseQuadricT<Mesh>::Handle hr;
  OpenMeshSkinned::ModDeformationSensitiveT<Mesh>::Handle hd;
  OpenMeshSkinned::ModPoseIndependentQuadricT<Mesh>::Handle hp;
  if (method == "static") {  // OpenMesh's own: rest-pose quadric, endpoint placement and weights
    dec.add(hs);
    dec.add(hn);
  } else {
    if (method == "skinned") dec.add(hq);
    if (method == "rest") dec.add(hr);
    if (method == "dsd") dec.add(hd);
    if (method == "decoro") dec.add(hp);  // poses drawn from the clips' empirical distribution
    dec.add(hf);  // every method but OpenMesh's own gets the same fold-over check in every example pose
  }
  dec.add(hc);
  dec.module(hc).set_max_influences(opt.max_influences);
  if (!dec.initialize()) throw std::runtime_error("the decimater did not initialize");
  Progress progress(!opt.quiet && isatty(2), input.n_vertices() - targets.back() / 2, label);
  dec.set_observer(&progress);

  std::vector<std::pair<Lod, Mesh>> out;
  const auto t0 = Clock::now();
  size_t collapses = 0;
  for (size_t i = 0; i < targets.size(); ++i) {
    progress.set_done_before(collapses);
    // decimate_to_faces counts deleted faces too until garbage collection, which would also renumber the
    // vertices under the solver's feet: aim at the target plus the faces already deleted instead.
    size_t live = 0;
    for (auto fh : mesh.faces()) (void)fh, ++live;
    collapses += dec.decimate_to_faces(0, targets[i] + (mesh.n_faces() - live));
    if (method != "static") dec.module(hf).release_deferred();  // give every vertex a chance next level
    Lod lod;
    lod.ratio = ratios[i];
    lod.target = targets[i];
    lod.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    Mesh snap = mesh;
    snap.garbage_collection();
    for (auto vh : snap.vertices()) snap.status(vh).set_locked(false);
    lod.faces = snap.n_faces();
    lod.vertices = snap.n_vertices();
    lod.max_influences = max_influences_of(snap);
    out.emplace_back(lod, std::move(snap));
  }
  dec.set_observer(nullptr);
  return out;
}

void evaluate(const Mesh& original, std::vector<std::pair<Lod, Mesh>>& chain, const std::vector<OpenMeshSkinned::Pose>& frames) {
  const double diag = OpenMeshSkinned::bbox_diagonal(original);
  for (auto& [lod, mesh] : chain) {
    double sum_rms = 0.0, max_h = 0.0;
    for (const auto& pose : frames) {
      const auto d = OpenMeshSkinned::surface_distance(OpenMeshSkinned::posed_soup(original, pose),
                                                       OpenMeshSkinned::posed_soup(mesh, pose), 20000);
      sum_rms += d.rms;
      max_h = std::max(max_h, d.hausdorff);
    }
    lod.rms = 100.0 * sum_rms / frames.size() / diag;
    lod.hausdorff = 100.0 * max_h / diag;
  }
}

std::string lod_path(const std::string& output, size_t i, size_t n) {
  if (n == 1) return output;
  const fs::path p(output);
  return (p.parent_path() / (p.stem().string() + "_lod" + std::to_string(i + 1) + p.extension().string())).string();
}

std::string fmt(double v, int prec) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(prec) << v;
  return os.str();
}

void print_table(const std::string& title, const std::vector<std::pair<Lod, Mesh>>& chain, bool have_heldout) {
  std::cout << title << "\n"
            << "  " << std::left << std::setw(8) << "ratio" << std::right << std::setw(10) << "triangles"
            << std::setw(10) << "vertices" << std::setw(10) << "seconds" << std::setw(10) << "max infl"
            << std::setw(14) << (have_heldout ? "heldout RMS%" : "rest RMS%") << std::setw(15)
            << (have_heldout ? "heldout Haus%" : "rest Haus%") << "\n";
  for (const auto& [lod, mesh] : chain)
    std::cout << "  " << std::left << std::setw(8) << fmt(lod.ratio, 4) << std::right << std::setw(10) << lod.faces
              << std::setw(10) << lod.vertices << std::setw(10) << fmt(lod.seconds, 2) << std::setw(10)
              << lod.max_influences << std::setw(14) << fmt(lod.rms, 4) << std::setw(15) << fmt(lod.hausdorff, 4)
              << "\n";
  for (const auto& [lod, mesh] : chain)
    if (lod.faces > lod.target)
      std::cout << "  ratio " << fmt(lod.ratio, 4) << ": target of " << lod.target << " triangles not reached; stopped at "
                << lod.faces << " (no collapse left that keeps the mesh valid)\n";
}

// --pose-clip as a name or an index; -1 when not given.
int resolve_clip(const std::vector<OpenMeshSkinned::Clip>& clips, const std::string& which, const std::string& name) {
  if (which.empty()) return -1;
  for (size_t c = 0; c < clips.size(); ++c)
    if (clips[c].name == which) return int(c);
  if (std::all_of(which.begin(), which.end(), ::isdigit) && which.size() < 9 && std::stoi(which) < int(clips.size()))
    return std::stoi(which);
  throw UsageError("--pose-clip " + which + ": no such clip in " + name + " (" + std::to_string(clips.size()) + " clips)");
}

json times_json(const std::vector<OpenMeshSkinned::Clip>& clips, const std::vector<OpenMeshSkinned::PoseTime>& t) {
  json a = json::array();
  for (const auto& p : t) a.push_back({{"clip", clips[p.clip].name}, {"time", p.time}});
  return a;
}

// Runs one character through one method; prints the table; returns the report entry.
json run_character(const Mesh& mesh, const std::string& name, const Options& opt, const std::string& method,
                   const std::string& output, OpenMeshSkinned::OutputSet* outputs) {
  const bool write_files = outputs != nullptr;
  using namespace OpenMeshSkinned;
  const auto& clips = OpenMeshSkinned::clips(mesh);
  Mesh work = mesh;
  PoseSchedule sched;
  std::vector<Pose> heldout;
  if (clips.empty()) {
    if (opt.poses_given)
      std::cerr << "skinned-decimate: warning: " << name
                << " has no animation: --poses ignored, decimating and judging in the rest pose only\n";
    example_poses(work) = {Pose::identity(skeleton(work).size())};
    heldout = example_poses(work);
  } else {
    const int clip_index = resolve_clip(clips, opt.pose_clip, name);
    sched = make_pose_schedule(clips, opt.poses, clip_index);
    example_poses(work) = poses_at(skeleton(work), clips, sched.examples);
    // The bind pose too, unless asked not to: it is the pose every other tool judges, and a handful of
    // clip frames can miss the neutral configuration entirely.
    if (opt.bind_pose) example_poses(work).push_back(Pose::identity(skeleton(work).size()));
    heldout = poses_at(skeleton(work), clips, sched.held_out.empty() ? sched.examples : sched.held_out);
    if (!opt.quiet) {
      std::cout << name << ": example poses at";
      for (const auto& t : sched.examples) std::cout << " " << clips[t.clip].name << "@" << fmt(t.time, 3) << "s";
      std::cout << (opt.bind_pose ? " + bind pose" : "") << "\n";
    }
  }

  std::vector<double> ratios = opt.lods;
  if (ratios.empty()) ratios = {opt.faces ? double(opt.faces) / mesh.n_faces() : opt.ratio};
  std::vector<size_t> targets;
  for (double r : ratios) targets.push_back(std::max<size_t>(1, static_cast<size_t>(std::llround(r * mesh.n_faces()))));
  if (opt.faces && opt.lods.empty()) targets = {opt.faces};

  auto chain = build_chain(work, targets, ratios, opt, method, name + " (" + method + ")");
  evaluate(mesh, chain, heldout);
  print_table(name + " — " + method + (clips.empty() ? ", rest pose only" : "") + ", " +
                  std::to_string(mesh.n_faces()) + " triangles in",
              chain, !clips.empty());

  json lods = json::array();
  for (size_t i = 0; i < chain.size(); ++i) {
    auto& [lod, lmesh] = chain[i];
    if (write_files) {
      lod.file = lod_path(output, i, chain.size());
      export_gltf(lmesh, outputs->staging(lod.file));
    }
    json l = {{"ratio", lod.ratio},
              {"target_faces", lod.target},
              {"target_reached", lod.faces <= lod.target},
              {"faces", lod.faces},
              {"vertices", lod.vertices},
              {"seconds", lod.seconds},
              {"max_influences", lod.max_influences},
              {"heldout_rms", lod.rms},
              {"heldout_hausdorff", lod.hausdorff},
              {"example_pose_times", times_json(clips, sched.examples)},
              {"bind_pose_in_examples", opt.bind_pose && !clips.empty()},
              {"heldout_times", times_json(clips, sched.held_out)}};
    if (write_files) l["file"] = lod.file;
    lods.push_back(l);
  }
  if (write_files)
    for (const auto& [lod, m] : chain) std::cout << "  wrote " << lod.file << "\n";
  return {{"input", name}, {"method", method}, {"triangles_in", mesh.n_faces()}, {"units", "percent of the rest-pose bounding-box diagonal"}, {"lods", lods}};
}

// One table: method x LOD.
void print_comparison(const json& runs) {
  std::cout << "comparison (held-out error, % of the rest-pose bounding-box diagonal)\n  " << std::left << std::setw(9)
            << "method" << std::setw(8) << "ratio" << std::right << std::setw(10) << "triangles" << std::setw(10)
            << "seconds" << std::setw(14) << "mean RMS%" << std::setw(15) << "max Haus%" << "\n";
  for (const auto& r : runs)
    for (const auto& l : r["lods"])
      std::cout << "  " << std::left << std::setw(9) << r["method"].get<std::string>() << std::setw(8)
                << fmt(l["ratio"].get<double>(), 4) << std::right << std::setw(10) << l["faces"].get<size_t>()
                << std::setw(10) << fmt(l["seconds"].get<double>(), 2) << std::setw(14)
                << fmt(l["heldout_rms"].get<double>(), 4) << std::setw(15) << fmt(l["heldout_hausdorff"].get<double>(), 4)
                << "\n";
}

// Every file this run will write, planned before any work so that a clash costs nothing.
void plan_outputs(const Options& opt, const std::vector<std::string>& names, OpenMeshSkinned::OutputSet& outputs) {
  const size_t n = std::max<size_t>(1, opt.lods.size());
  for (const std::string& name : names)
    for (size_t i = 0; i < n; ++i) outputs.add(lod_path(name, i, n));
  if (!opt.report.empty()) outputs.add(opt.report);
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
  f.close();
  if (!f) throw OpenMeshSkinned::IOError(path + ": cannot be written");
}

// The memory the example and held-out poses will take, checked before the decimater allocates it.
void check_pose_budget(const Mesh& mesh, const Options& opt) {
  const size_t poses = 2 * size_t(opt.poses) + 2;  // examples + bind, held-out frames in between
  const size_t need_mb = (poses * mesh.n_vertices() * kBytesPerVertexPose >> 20) + 1;
  if (opt.max_memory_mb > 0 && need_mb > opt.max_memory_mb)
    throw UsageError("--poses " + std::to_string(opt.poses) + ": needs about " + std::to_string(need_mb) +
                     " MB for this mesh (" + std::to_string(mesh.n_vertices()) + " vertices), over --max-memory " +
                     std::to_string(opt.max_memory_mb) + " MB");
}

int run(const Options& opt) {
  if (opt.ratio_given && !(opt.ratio > 0.0 && opt.ratio <= 1.0)) throw UsageError("--ratio must be in (0, 1]");
  if (opt.faces_given && opt.faces == 0) throw UsageError("--faces must be at least 1");
  for (double r : opt.lods)
    if (!(r > 0.0 && r <= 1.0)) throw UsageError("--lods: every ratio must be in (0, 1], got " + fmt(r, 4));
  if (opt.max_influences < 1 || opt.max_influences > OpenMeshSkinned::Influences::kCapacity)
    throw UsageError("--max-influences must be 1 to " + std::to_string(OpenMeshSkinned::Influences::kCapacity));
  if (opt.poses < 1 || opt.poses > kMaxPoses) throw UsageError("--poses must be 1 to " + std::to_string(kMaxPoses));
  if (!(opt.time_limit >= 0.0)) throw UsageError("--time-limit must be 0 (none) or more seconds");
  if (opt.method != "skinned" && opt.method != "static" && opt.method != "rest" && opt.method != "dsd" &&
      opt.method != "decoro")
    throw UsageError("--method must be skinned, decoro, dsd, rest or static");

  json report;
  if (opt.input.empty()) {
    // Built-in default: the papers' own characters, skinned next to static, files in one folder.
    const std::string dir = opt.output.empty() ? "skinned-decimate-demo" : opt.output;
    fs::create_directories(dir);
    Options o = opt;
    if (o.lods.empty()) o.lods = {0.5, 0.1, 0.02};
    OpenMeshSkinned::OutputSet outputs;
    plan_outputs(o, {(fs::path(dir) / "leg.glb").string(), (fs::path(dir) / "column.glb").string()}, outputs);
    std::cout << "No INPUT: running the papers' test characters; output in " << dir << "/\n\n";
    json runs = json::array();
    const std::pair<std::string, Mesh> characters[] = {
        {"leg", OpenMeshSkinned::make_bending_cylinder(32, 64)},
        {"column", OpenMeshSkinned::make_square_column()}};
    for (const auto& [name, mesh] : characters) {
      o.poses = name == "leg" ? 2 : 4;  // the papers' example poses: knee at 0 and 90; the column's four bends
      o.pose_clip = "";
      Mesh m = mesh;
      runs.push_back(run_character(m, name, o, "skinned", (fs::path(dir) / (name + ".glb")).string(), &outputs));
      runs.push_back(run_character(m, name, o, "static", "", nullptr));
      std::cout << "\n";
    }
    report = {{"input", "built-in"}, {"runs", runs}};
    if (!opt.report.empty()) write_text(outputs.staging(opt.report), report.dump(2) + "\n");
    outputs.commit();
    std::cout << "Static = OpenMesh's rest-pose quadric with endpoint weights; skinned = this library. The error\n"
                 "columns are measured in frames the decimater never saw.\n";
    return 0;
  }

  if (opt.output.empty()) throw UsageError("-o OUTPUT.glb is required with an INPUT");
  const std::string ext = fs::path(opt.output).extension().string();
  if (ext != ".glb" && ext != ".gltf") throw UsageError(opt.output + ": output must end in .glb or .gltf");
  OpenMeshSkinned::OutputSet outputs({opt.input});
  try {
    plan_outputs(opt, {opt.output}, outputs);
  } catch (const OpenMeshSkinned::IOError& e) {
    throw UsageError(e.what());  // a clash or a missing folder is the command line's fault: exit 2
  }
  Mesh mesh;
  OpenMeshSkinned::ImportOptions io;
  io.isolate = opt.isolate;
  io.memory_limit_mb = opt.max_memory_mb;
  io.time_limit_seconds = opt.time_limit;
  const auto rep = OpenMeshSkinned::import_skinned(opt.input, mesh, io);
  if (opt.faces > mesh.n_faces())
    throw UsageError("--faces " + std::to_string(opt.faces) + " is more than the input's " +
                     std::to_string(mesh.n_faces()) + " triangles");
  if (!OpenMeshSkinned::clips(mesh).empty()) resolve_clip(OpenMeshSkinned::clips(mesh), opt.pose_clip, opt.input);
  check_pose_budget(mesh, opt);
  // After the checks, so that a bad argument is one line. Always shown: they say what was changed or lost.
  for (const auto& w : rep.warnings) std::cerr << "skinned-decimate: warning: " << opt.input << ": " << w << "\n";
  Options o = opt;
  if (o.lods.empty() && o.faces == 0 && !o.ratio_given) o.ratio = 0.5;
  if (o.compare) {
    json runs = json::array();
    for (const char* m : {"skinned", "decoro", "dsd", "rest", "static"}) {
      runs.push_back(run_character(mesh, opt.input, o, m, opt.output, std::string(m) == opt.method ? &outputs : nullptr));
      std::cout << "\n";
    }
    print_comparison(runs);
    report = {{"input", opt.input}, {"runs", runs}};
  } else {
    report = run_character(mesh, opt.input, o, opt.method, opt.output, &outputs);
  }
  if (!opt.report.empty()) write_text(outputs.staging(opt.report), report.dump(2) + "\n");
  outputs.commit();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"skinned-decimate: LODs of a skinned character that stay right in poses never seen.\n"
               "With no INPUT, runs the papers' test characters (DeCoro's leg, Landreneau-Schaefer's column)."};
  Options opt;
  app.add_option("input", opt.input, "Skinned asset (glTF/GLB, FBX, Collada, X, MD5, ...)")->check(CLI::ExistingFile);
  app.add_option("-o,--output", opt.output,
                 "Output .glb/.gltf; with --lods, NAME_lod1.glb, NAME_lod2.glb ... in the order of decreasing ratio "
                 "(with no INPUT: the output folder). Never the input: all files of a run appear together at the end, or none");
  auto* r = app.add_option("--ratio", opt.ratio, "Keep this fraction of the triangles, in (0,1] (default 0.5)");
  auto* f = app.add_option("--faces", opt.faces, "Keep this many triangles");
  auto* l = app.add_option("--lods", opt.lods, "A chain of ratios, built in one pass, e.g. 0.5,0.25,0.1")->delimiter(',');
  r->excludes(f)->excludes(l);
  f->excludes(l);
  app.add_option("--max-influences", opt.max_influences, "Bone influences per vertex at most (1-8, default 4)");
  app.add_option("--poses", opt.poses, "Example poses: K evenly spaced times over the clip, both ends included, plus the bind pose (1-1000, default 8)");
  app.add_option("--pose-clip", opt.pose_clip, "Clip (name or index) for the example poses; default: all clips end to end");
  app.add_option("--method", opt.method,
                 "Priority module: skinned (default, Landreneau-Schaefer), decoro (DeCoro-Rusinkiewicz pose-"
                 "independent quadric over the clips), dsd (Mohr-Gleicher), rest (rest-pose quadric, distance-"
                 "interpolated weights), static (OpenMesh's ModQuadricT as it is)");
  app.add_flag("--compare", opt.compare, "Run every method on the same input and print one table");
  app.add_option("--report", opt.report, "Write the summary as JSON");
  app.add_flag("--quiet", opt.quiet, "No progress and no pose list (warnings are still printed)");
  app.add_flag("!--no-bind-pose", opt.bind_pose, "Do not add the bind pose to the example poses");
  app.add_flag("!--no-isolate", opt.isolate,
               "Read the input in this process (by default a child process reads it, so that a reader crash on a "
               "corrupt file is a clean error)");
  app.add_option("--max-memory", opt.max_memory_mb,
                 "Memory limit in MB for reading the input and for the example poses (default 8192; 0 = none)");
  app.add_option("--time-limit", opt.time_limit, "Seconds the input's reader may take (default 300; 0 = none)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "skinned-decimate: " << e.what() << "\n";
    return 2;
  }
  opt.poses_given = app.count("--poses") > 0;
  opt.ratio_given = app.count("--ratio") > 0;
  opt.faces_given = app.count("--faces") > 0;
  std::vector<double> lods = opt.lods;
  std::sort(lods.rbegin(), lods.rend());
  opt.lods = lods;
  try {
    return run(opt);
  } catch (const UsageError& e) {
    std::cerr << "skinned-decimate: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "skinned-decimate: " << e.what() << "\n";
    return 1;
  }
}
