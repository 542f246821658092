#include "Run.hh"

#include "Frames.hh"
#include "Html.hh"
#include "Methods.hh"
#include "Report.hh"

#include <OpenMeshSkinned/Deform/PoseSelection.hh>
#include <OpenMeshSkinned/Eval/SurfaceDistance.hh>
#include <OpenMeshSkinned/IO/ExportGltf.hh>
#include <OpenMeshSkinned/IO/Import.hh>
#include <OpenMeshSkinned/IO/ImportFrames.hh>
#include <OpenMeshSkinned/IO/OutputSet.hh>
#include <OpenMeshSkinned/IO/PrintableText.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>
#include <OpenMeshSkinned/Skin/FrameAnimation.hh>
#include <OpenMeshSkinned/Skin/KeyReduction.hh>
#include <OpenMeshSkinned/Skin/PoseSchedule.hh>
#include <OpenMeshSkinned/Solver/Refit.hh>
#include <OpenMeshSkinned/Solver/SkeletonLodT.hh>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <thread>

namespace skinned_decimate {

namespace {

namespace fs = std::filesystem;
using namespace OpenMeshSkinned;

// Area samples per surface and frame for the held-out error (plus every vertex).
constexpr size_t kEvalSamples = 20000;

std::atomic<const char*> stage{"starting"};

using Clock = std::chrono::steady_clock;
double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

int hardware_threads() { return std::max(1u, std::thread::hardware_concurrency()); }

// The example poses the decimater sees and the held-out frames the result is judged in.
struct Poses {
  PoseSchedule schedule;
  std::vector<Pose> examples, heldout;
};

// --pose-clip as a name or an index; -1 when not given.
int resolve_clip(const std::vector<Clip>& clips, const std::string& which, const std::string& name) {
  if (which.empty()) return -1;
  for (size_t c = 0; c < clips.size(); ++c)
    if (clips[c].name == which) return int(c);
  if (std::all_of(which.begin(), which.end(), ::isdigit) && which.size() < 9 && std::stoi(which) < int(clips.size()))
    return std::stoi(which);
  throw UsageError("--pose-clip " + which + ": no such clip in " + name + " (" + std::to_string(clips.size()) +
                   " clips)");
}

Poses choose_poses(const Mesh& mesh, const std::string& name, const Options& opt) {
  const auto& all = clips(mesh);
  const Skeleton& skel = skeleton(mesh);
  Poses p;
  if (all.empty()) {
    if (opt.poses_given)
      std::cerr << "skinned-decimate: warning: " << name
                << " has no animation: --poses ignored, decimating and judging in the rest pose only\n";
    p.examples = p.heldout = {Pose::identity(skel.size())};
    return p;
  }
  // A frame animation learns from, and is judged on, stored frames, never the blend of two; with few of
  // them, half are kept back to judge on.
  const size_t stored = frame_times(mesh).size();
  const int k = stored > 0 ? std::min<int>(opt.poses, int((stored + 1) / 2)) : opt.poses;
  p.schedule = make_pose_schedule(all, k, resolve_clip(all, opt.pose_clip, name));
  snap_to_frames(p.schedule, frame_times(mesh));
  if (opt.pose_select_ga) {
    const auto candidates = candidate_frames(mesh, p.schedule.held_out);
    if (candidates.size() >= 2) p.schedule.examples = select_poses_ga(mesh, candidates, size_t(k));
  }
  p.examples = poses_at(skel, all, p.schedule.examples);
  // The bind pose too, unless asked not to: it is the pose every other tool judges, and a handful of
  // clip frames can miss the neutral configuration entirely.
  if (opt.bind_pose) p.examples.push_back(Pose::identity(skel.size()));
  p.heldout = poses_at(skel, all, p.schedule.held_out.empty() ? p.schedule.examples : p.schedule.held_out);
  if (!opt.quiet) {
    std::cout << name << ": example poses" << (opt.pose_select_ga ? " (chosen by the key-frame GA)" : "") << " at";
    for (const auto& t : p.schedule.examples) std::cout << " " << all[t.clip].name << "@" << fmt(t.time, 3) << "s";
    std::cout << (opt.bind_pose ? " + bind pose" : "") << "\n";
  }
  return p;
}

// The triangle counts asked for, and the ratio each stands for.
void choose_targets(const Mesh& mesh, const Options& opt, std::vector<double>& ratios, std::vector<size_t>& targets) {
  ratios = opt.lods;
  if (ratios.empty()) ratios = {opt.faces ? double(opt.faces) / mesh.n_faces() : opt.ratio};
  targets.clear();
  for (double r : ratios) targets.push_back(std::max<size_t>(1, static_cast<size_t>(std::llround(r * mesh.n_faces()))));
  if (opt.faces && opt.lods.empty()) targets = {opt.faces};
}

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

// Frame by frame, threads taking frames in turn: the posed original's surface (tree and samples) is built
// once per frame and measured against every LOD; sums are taken in frame order, so the numbers do not
// depend on the thread count.
// \p lod_frames[i], when not empty, are LOD i's own poses of the same frames (its clips were reduced).
void evaluate(const Mesh& original, std::vector<std::pair<Lod, Mesh>>& chain, const std::vector<Pose>& frames,
              const std::vector<std::vector<Pose>>& lod_frames, int threads, bool per_vertex) {
  const double diag = bbox_diagonal(original);
  const size_t n_lods = chain.size();
  std::vector<SurfaceDistance> d(frames.size() * n_lods);
  // --html: each LOD vertex's distance to the posed original, per frame (the max is taken below).
  std::vector<std::vector<float>> vd(per_vertex ? frames.size() * n_lods : 0);
  std::atomic<size_t> next{0};
  std::exception_ptr failure;
  std::mutex failure_lock;
  auto work = [&] {
    try {
      for (size_t f = next++; f < frames.size(); f = next++) {
        const TriangleSoup original_soup = posed_soup(original, frames[f]);
        const MeasuredSurface posed(original_soup, kEvalSamples, 1);
        for (size_t i = 0; i < n_lods; ++i) {
          const TriangleSoup lod =
              posed_soup(chain[i].second, lod_frames.empty() || lod_frames[i].empty() ? frames[f] : lod_frames[i][f]);
          const MeasuredSurface lod_surface(lod, kEvalSamples, 0x9E3779B97F4A7C16ull);
          d[f * n_lods + i] = surface_distance(posed, lod_surface);
          if (per_vertex) vd[f * n_lods + i] = vertex_errors(original_soup, posed, lod, lod_surface, diag);
        }
      }
    } catch (...) {
      std::lock_guard<std::mutex> g(failure_lock);
      if (!failure) failure = std::current_exception();
      next = frames.size();
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::min<int>(threads, int(frames.size())); ++t) pool.emplace_back(work);
  work();
  for (auto& th : pool) th.join();
  if (failure) std::rethrow_exception(failure);
  for (size_t i = 0; i < n_lods; ++i) {
    double sum_rms = 0.0, max_h = 0.0;
    for (size_t f = 0; f < frames.size(); ++f) {
      sum_rms += d[f * n_lods + i].rms;
      max_h = std::max(max_h, d[f * n_lods + i].hausdorff);
    }
    Lod& lod = chain[i].first;
    lod.evaluated = true;
    lod.rms = 100.0 * sum_rms / frames.size() / diag;
    lod.hausdorff = 100.0 * max_h / diag;
    if (!per_vertex) continue;
    lod.vertex_error.assign(chain[i].second.n_vertices(), 0.0f);
    for (size_t f = 0; f < frames.size(); ++f)
      for (size_t v = 0; v < lod.vertex_error.size(); ++v)
        lod.vertex_error[v] = std::max(lod.vertex_error[v], vd[f * n_lods + i][v]);
  }
}

std::string lod_path(const std::string& output, size_t i, size_t n) {
  if (n == 1) return output;
  const fs::path p(output);
  return (p.parent_path() / (p.stem().string() + "_lod" + std::to_string(i + 1) + p.extension().string())).string();
}

// The page's section for a character: its clips, and up to four of its held-out frames, spread over all of
// them, for the contact sheet.
HtmlSection new_section(const std::string& title, const Mesh& mesh, const PoseSchedule& schedule) {
  HtmlSection s;
  s.title = title;
  const auto& all = clips(mesh);
  for (const Clip& c : all) s.clips.push_back({{"name", c.name}, {"duration", c.duration}});
  const auto& held = schedule.held_out;
  const size_t n = std::min<size_t>(4, held.size());
  for (size_t i = 0; i < n; ++i) {
    const PoseTime& t = held[i * held.size() / n];
    s.preview.push_back({{"clip", all[t.clip].name}, {"time", t.time}});
  }
  return s;
}

// --max-error after the final fit, which knows nothing of the bound: the fit is kept if the original's
// vertices are still within the limit of the LOD in every example pose (measured, the solver's way: skin
// only), and undone otherwise. The LOD's bound is then the measured distance, or the decimation's bound.
void keep_bound_after_refit(const Mesh& original, Mesh& lmesh, std::vector<Pose> examples,
                            const std::vector<SkinnedMesh::Point>& decimated, Lod& lod, const Options& opt) {
  for (Pose& p : examples) p.morph_weights.clear();
  const double diagonal = bbox_diagonal(original);
  const double worst = 100.0 * worst_vertex_deviation(original, lmesh, examples) / diagonal;
  if (worst <= opt.max_error) {
    lod.deviation_bound = worst;
    return;
  }
  for (auto vh : lmesh.vertices()) lmesh.set_point(vh, decimated[vh.idx()]);
  if (!opt.quiet)
    std::cout << "refit " << fmt(100.0 * lod.ratio, 1) << "%: undone (a vertex of the input would be " << fmt(worst, 3)
              << "% of the diagonal away, over --max-error)\n";
}

// Runs one character through one method: poses, targets, the chain, its error, the table, the files
// (staged in \p outputs; none when it is null), the page's views (when \p html is not null: the original
// first if the section is new). \p last_use is the input itself when nothing copies it after this run:
// its appearance attributes are released once the working copy is made. Returns the report entry.
json run_character(const Mesh& mesh, const std::string& name, const Options& opt, const std::string& method,
                   const std::string& output, OutputSet* outputs, std::vector<HtmlSection>* html = nullptr,
                   const std::string& section_title = "", Mesh* last_use = nullptr) {
  stage = "choosing the example poses";
  const Poses poses = choose_poses(mesh, name, opt);
  // Keys of huge but finite values can still overflow once composed down a chain of joints.
  for (const auto* set : {&poses.examples, &poses.heldout})
    for (const Pose& p : *set)
      if (!p.finite())
        throw IOError(name + ": pose \"" + p.label +
                      "\" is not finite: its keys' translations or scales are too large to compose");
  stage = "decimating";
  std::vector<double> ratios;
  std::vector<size_t> targets;
  choose_targets(mesh, opt, ratios, targets);
  const auto t0 = Clock::now();
  auto chain = build_chain(mesh, poses.examples, targets, ratios, opt, method, name + " (" + method + ")", [&] {
    // Nothing copies the input after this run: from here on it is only the reference surface.
    if (last_use && !html) keep_as_reference_only(*last_use);
  });
  if (opt.refit)
    for (auto& [lod, lmesh] : chain) {
      const auto tr = Clock::now();
      RefitSettings fit;
      fit.threads = opt.threads > 0 ? opt.threads : hardware_threads();
      std::vector<SkinnedMesh::Point> decimated;
      if (lod.deviation_bound >= 0.0)
        for (auto vh : lmesh.vertices()) decimated.push_back(lmesh.point(vh));
      const RefitReport r = refit_positions(lmesh, mesh, poses.examples, fit);
      if (!opt.quiet)
        std::cout << "refit " << fmt(100.0 * lod.ratio, 1) << "%: residual " << r.before << " -> " << r.after << " ("
                  << r.rounds << " rounds, " << fmt(seconds(tr, Clock::now()), 2) << " s)\n";
      if (lod.deviation_bound >= 0.0) keep_bound_after_refit(mesh, lmesh, poses.examples, decimated, lod, opt);
    }
  const auto t1 = Clock::now();
  const bool want_html = html != nullptr;
  // Skeleton LoD (--max-joints), then motion LoD (--anim-error: clips thinned as far as the LOD's own skinned
  // surface allows); the LOD is then judged with its own skeleton and clips.
  std::vector<std::vector<Pose>> lod_frames;
  const bool animated_lod =
      (!opt.max_joints.empty() || opt.joint_energy > 0.0 || opt.anim_error > 0.0 || opt.keyframes > 0) &&
      !clips(mesh).empty();
  if (animated_lod) {
    const auto& times = poses.schedule.held_out.empty() ? poses.schedule.examples : poses.schedule.held_out;
    // --keyframes: the same frames for every LOD, chosen on the original's motion.
    const std::vector<size_t> keys =
        opt.keyframes > 0 ? choose_keyframes(mesh, opt.keyframes, opt.quiet) : std::vector<size_t>{};
    for (size_t i = 0; i < chain.size(); ++i) {
      Mesh& lmesh = chain[i].second;
      if (!keys.empty()) keep_frames(lmesh, keys);
      if (!opt.max_joints.empty() || opt.joint_energy > 0.0) {
        const int budget =
            opt.max_joints.empty() ? skeleton(lmesh).size() : opt.max_joints[std::min(i, opt.max_joints.size() - 1)];
        reduce_mesh_skeleton(lmesh, budget, opt.max_influences, true, opt.joint_energy);
      }
      if (opt.anim_error > 0.0)
        clips(lmesh) =
            reduce_clips_to_error(lmesh, opt.anim_error / 100.0 * bbox_diagonal(mesh),
                                  opt.anim_frames ? KeyReductionMethod::Frames : KeyReductionMethod::Channels);
      lod_frames.push_back(poses_at(skeleton(lmesh), clips(lmesh), times));
    }
  }
  const bool frame_animation = !frame_times(mesh).empty();
  for (auto& [lod, lmesh] : chain) {
    // A frame animation's keys are its stored frames.
    lod.keys = frame_animation ? frame_times(lmesh).size() : count_keys(clips(lmesh));
    lod.joints = skeleton(lmesh).size();
    lod.max_influences = max_influences_of(lmesh);
  }
  stage = "measuring the held-out error";
  if (opt.evaluate)
    evaluate(mesh, chain, poses.heldout, lod_frames, opt.threads > 0 ? opt.threads : hardware_threads(), want_html);
  const auto t2 = Clock::now();
  const bool animated = !clips(mesh).empty();
  print_table(name + " — " + method + (animated ? "" : ", rest pose only") +
                  (frame_animation ? ", " + std::to_string(frame_times(mesh).size()) + " frames" : "") + ", " +
                  std::to_string(mesh.n_faces()) + " triangles in",
              chain, animated);
  json lods = json::array();
  for (size_t i = 0; i < chain.size(); ++i) {
    auto& [lod, lmesh] = chain[i];
    if (outputs) {
      stage = "writing the LODs";
      lod.file = lod_path(output, i, chain.size());
      export_gltf(lmesh, outputs->staging(lod.file));
    }
    lods.push_back(lod_json(lod, clips(mesh), poses.schedule, opt.bind_pose && animated));
  }
  if (outputs)
    for (const auto& [lod, m] : chain) std::cout << "  wrote " << lod.file << "\n";
  if (want_html) {
    if (html->empty() || html->back().title != section_title) {
      html->push_back(new_section(section_title, mesh, poses.schedule));
      add_view(html->back(), "original", mesh, nullptr, {});
    }
    for (const auto& [lod, lmesh] : chain)
      add_view(html->back(), method + " " + fmt(100.0 * lod.ratio, 1) + "%", lmesh, &lod, lod.vertex_error);
  }
  return {{"input", name},
          {"method", method},
          {"triangles_in", mesh.n_faces()},
          {"units", "percent of the rest-pose bounding-box diagonal"},
          {"seconds",
           {{"decimate", seconds(t0, t1)}, {"evaluate", seconds(t1, t2)}, {"export", seconds(t2, Clock::now())}}},
          {"lods", lods}};
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
  f.close();
  if (!f) throw IOError(path + ": cannot be written");
}

// --html-assets beside: PAGE.assets.js next to PAGE.html.
std::string assets_path(const std::string& html) {
  const fs::path p(html);
  return (p.parent_path() / (p.stem().string() + ".assets.js")).string();
}

// Every file this run will write, planned before any work so that a clash costs nothing.
void plan_outputs(const Options& opt, const std::vector<std::string>& names, OutputSet& outputs) {
  const size_t n = std::max<size_t>(1, opt.lods.size());
  for (const std::string& name : names)
    for (size_t i = 0; i < n; ++i) outputs.add(lod_path(name, i, n));
  if (!opt.report.empty()) outputs.add(opt.report);
  if (!opt.html.empty()) {
    outputs.add(opt.html);
    if (opt.html_beside) outputs.add(assets_path(opt.html));
  }
  if (!opt.preview.empty()) outputs.add(opt.preview);
}

// The page (--html, its assets script beside it with --html-assets beside) and the contact sheet
// (--preview, rendered from an embedded copy of the page in a temporary folder), staged in \p outputs.
void write_page(const Options& opt, const std::string& title, const std::vector<HtmlSection>& sections,
                OutputSet& outputs) {
  if (!opt.html.empty()) {
    std::string assets;
    write_text(outputs.staging(opt.html), html_page(title, sections, opt.html_beside,
                                                    fs::path(assets_path(opt.html)).filename().string(), &assets));
    if (opt.html_beside) write_text(outputs.staging(assets_path(opt.html)), assets);
  }
  if (!opt.preview.empty()) {
    const fs::path page = fs::temp_directory_path() / ("omsk-preview-" + std::to_string(::getpid()) + ".html");
    write_text(page.string(), html_page(title, sections, false, "", nullptr));
    try {
      render_preview(page.string(), outputs.staging(opt.preview));
    } catch (...) {
      fs::remove(page);
      throw;
    }
    fs::remove(page);
  }
}

void check_arguments(const Options& opt) {
  if (opt.ratio_given && !(opt.ratio > 0.0 && opt.ratio <= 1.0)) throw UsageError("--ratio must be in (0, 1]");
  if (opt.faces_given && opt.faces == 0) throw UsageError("--faces must be at least 1");
  for (double r : opt.lods)
    if (!(r > 0.0 && r <= 1.0)) throw UsageError("--lods: every ratio must be in (0, 1], got " + fmt(r, 4));
  if (opt.max_influences < 1 || opt.max_influences > Influences::kCapacity)
    throw UsageError("--max-influences must be 1 to " + std::to_string(Influences::kCapacity));
  if (opt.poses < 1 || opt.poses > kMaxPoses) throw UsageError("--poses must be 1 to " + std::to_string(kMaxPoses));
  if (!(opt.time_limit >= 0.0)) throw UsageError("--time-limit must be 0 (none) or more seconds");
  if (!is_method(opt.method)) throw UsageError("--method must be " + method_names());
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

// No INPUT: the papers' own characters, skinned next to static, files in one folder.
int run_builtin(const Options& opt) {
  const std::string dir = opt.output.empty() ? "skinned-decimate-demo" : opt.output;
  fs::create_directories(dir);
  Options o = opt;
  if (o.lods.empty()) o.lods = {0.5, 0.1, 0.02};
  OutputSet outputs;
  plan_outputs(o, {(fs::path(dir) / "leg.glb").string(), (fs::path(dir) / "column.glb").string()}, outputs);
  std::cout << "No INPUT: running the papers' test characters; output in " << dir << "/\n\n";
  json runs = json::array();
  const std::pair<std::string, Mesh> characters[] = {{"leg", make_bending_cylinder(32, 64)},
                                                     {"column", make_square_column()}};
  const bool page = !opt.html.empty() || !opt.preview.empty();
  std::vector<HtmlSection> sections;
  for (const auto& [name, mesh] : characters) {
    o.poses = name == "leg" ? 2 : 4;  // the papers' example poses: knee at 0 and 90; the column's four bends
    o.pose_clip = "";
    runs.push_back(run_character(mesh, name, o, "skinned", (fs::path(dir) / (name + ".glb")).string(), &outputs,
                                 page ? &sections : nullptr, name));
    runs.push_back(run_character(mesh, name, o, "static", "", nullptr, page ? &sections : nullptr, name));
    std::cout << "\n";
  }
  const json report = {{"input", "built-in"}, {"runs", runs}};
  if (!opt.report.empty()) write_text(outputs.staging(opt.report), report.dump(2) + "\n");
  if (page) write_page(opt, "skinned-decimate: the papers' characters", sections, outputs);
  outputs.commit();
  if (!opt.html.empty()) std::cout << "page: " << opt.html << "\n";
  if (!opt.preview.empty()) std::cout << "preview: " << opt.preview << "\n";
  std::cout << "Static = OpenMesh's rest-pose quadric with endpoint weights; skinned = this library. The error\n"
               "columns are measured in frames the decimater never saw.\n";
  return 0;
}

}  // namespace

const char* current_stage() { return stage.load(); }

int run(const Options& opt) {
  check_arguments(opt);
  if (opt.input.empty()) return run_builtin(opt);
  if (opt.output.empty() && opt.segment.empty()) throw UsageError("-o OUTPUT.glb is required with an INPUT");
  for (const std::string& out : {opt.output, opt.segment}) {
    const std::string ext = fs::path(out).extension().string();
    if (!out.empty() && ext != ".glb" && ext != ".gltf") throw UsageError(out + ": output must end in .glb or .gltf");
  }
  const std::vector<std::string> frames = frame_files(opt.input, opt.sequences);
  if (opt.keyframes > 0 && frames.empty())
    throw UsageError("--keyframes: " + opt.input +
                     " is not animated without a skeleton (an MD2/MD3/MDL file or a numbered sequence); for a "
                     "skinned clip's keys use --anim-error");
  OutputSet outputs(frames.empty() ? std::vector<std::string>{opt.input} : frames);
  try {
    if (!opt.output.empty()) plan_outputs(opt, {opt.output}, outputs);
    if (!opt.segment.empty()) {
      outputs.add(opt.segment);
      outputs.add(segmentation_json_path(opt.segment));
    }
  } catch (const IOError& e) {
    throw UsageError(e.what());  // a clash or a missing folder is the command line's fault: exit 2
  }
  Mesh mesh;
  ImportOptions io;
  io.isolate = opt.isolate;
  io.memory_limit_mb = opt.max_memory_mb;
  io.time_limit_seconds = opt.time_limit;
  io.show_reader_output = opt.verbose;
  stage = "reading the input";
  const auto t_import = Clock::now();
  const auto rep = frames.empty() ? import_skinned(opt.input, mesh, io)
                                  : import_frame_animation(frames, mesh, io, frame_rate(frames, opt.fps));
  const double import_s = seconds(t_import, Clock::now());
  if (!frames.empty() && !opt.quiet && frames.size() > 1)
    std::cout << opt.input << ": one frame of " << frames.size() << " files "
              << fs::path(frames.front()).filename().string() << " .. " << fs::path(frames.back()).filename().string()
              << " (--no-sequence reads it alone)\n";
  if (opt.faces > mesh.n_faces())
    throw UsageError("--faces " + std::to_string(opt.faces) + " is more than the input's " +
                     std::to_string(mesh.n_faces()) + " triangles");
  if (!clips(mesh).empty()) resolve_clip(clips(mesh), opt.pose_clip, opt.input);
  check_pose_budget(mesh, opt);
  if (opt.keyframes > 0 && frame_times(mesh).empty())
    throw UsageError("--keyframes: " + opt.input + " reads as a still mesh (its stored frames all have one shape)");
  // After the checks, so that a bad argument is one line. Always shown: they say what was changed or lost.
  for (const auto& w : rep.warnings)
    std::cerr << "skinned-decimate: warning: " << printable_text(opt.input + ": " + w) << "\n";
  if (!opt.segment.empty()) {
    write_segmentation(mesh, opt.segment, outputs);
    if (opt.output.empty()) {
      outputs.commit();
      std::cout << "  wrote " << opt.segment << " and " << segmentation_json_path(opt.segment) << "\n";
      return 0;
    }
  }
  Options o = opt;
  if (o.lods.empty() && o.faces == 0 && !o.ratio_given) o.ratio = 0.5;
  // Only the frame quadric sees morph-target frames; the skinned solver's methods decimate them in the rest
  // shape (their morph offsets carried along). So a mesh animated without a skeleton (stored frames, or
  // glTF clips that move morph targets and no joint) gets it by default.
  const auto& all_clips = clips(mesh);
  const bool morph_only =
      std::any_of(all_clips.begin(), all_clips.end(), [](const Clip& c) { return !c.morph_channels.empty(); }) &&
      std::all_of(all_clips.begin(), all_clips.end(), [](const Clip& c) { return c.channels.empty(); });
  if (morph_only) {
    if (!opt.method_given)
      o.method = "frames";
    else if (o.method != "frames" && o.method != "deform" && o.method != "static" && !opt.compare)
      std::cerr << "skinned-decimate: warning: --method " << o.method
                << " does not see the morph targets of a mesh animated without a skeleton: it decimates the rest "
                   "shape (use frames)\n";
  }
  if (o.max_error > 0.0 && (!o.max_joints.empty() || o.joint_energy > 0.0))
    throw UsageError(
        "--max-error cannot be combined with --max-joints or --joint-energy: the skeleton LoD re-solves the skins "
        "after the decimation, and the bound would no longer hold");
  if (o.max_error > 0.0 && !o.compare && (o.method == "frames" || o.method == "deform"))
    throw UsageError(
        "--max-error bounds the methods whose vertices the skinned solver places (skinned, decoro, "
        "dsd, rest, compact, static); --method " +
        o.method + " places them itself");
  json report;
  const bool page = !opt.html.empty() || !opt.preview.empty();
  std::vector<HtmlSection> sections;
  const std::string title = fs::path(opt.input).filename().string();
  if (o.compare) {
    json runs = json::array();
    for (const Method& m : methods()) {
      runs.push_back(run_character(mesh, opt.input, o, m.name, opt.output, m.name == o.method ? &outputs : nullptr,
                                   page ? &sections : nullptr, title));
      std::cout << "\n";
    }
    print_comparison(runs);
    report = {{"input", opt.input}, {"runs", runs}};
  } else {
    report =
        run_character(mesh, opt.input, o, o.method, opt.output, &outputs, page ? &sections : nullptr, title, &mesh);
  }
  if (page) write_page(opt, "skinned-decimate: " + title, sections, outputs);
  report["import_seconds"] = import_s;
  if (!opt.report.empty()) write_text(outputs.staging(opt.report), report.dump(2) + "\n");
  outputs.commit();
  return 0;
}

}  // namespace skinned_decimate
