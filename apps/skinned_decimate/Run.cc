#include "Run.hh"

#include "Frames.hh"
#include "Html.hh"
#include "Progress.hh"
#include "Report.hh"

#include <OpenMeshSkinned/IO/ExportGltf.hh>
#include <OpenMeshSkinned/IO/Import.hh>
#include <OpenMeshSkinned/IO/ImportFrames.hh>
#include <OpenMeshSkinned/IO/OutputSet.hh>
#include <OpenMeshSkinned/IO/PrintableText.hh>
#include <OpenMeshSkinned/Lod/MakeLods.hh>
#include <OpenMeshSkinned/Lod/SaveLods.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>
#include <OpenMeshSkinned/Skin/FrameAnimation.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>

namespace skinned_decimate {

namespace {

namespace fs = std::filesystem;
using namespace OpenMeshSkinned;

std::atomic<const char*> stage{"starting"};

using Clock = std::chrono::steady_clock;
double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

// What the command line asks of the library. Its checks run there, with the same messages.
LodOptions lod_options(const Options& opt, const std::string& method) {
  LodOptions l;
  l.method = method;
  if (!opt.lods.empty())
    l.ratios = opt.lods;
  else if (opt.faces_given || opt.faces > 0)
    l.ratios.clear(), l.faces = {opt.faces};
  else
    l.ratios = {opt.ratio_given ? opt.ratio : 0.5};
  l.max_influences = opt.max_influences;
  l.poses = opt.poses;
  l.pose_clip = opt.pose_clip;
  l.bind_pose = opt.bind_pose;
  l.pose_select = opt.pose_select;
  l.threads = opt.threads;
  l.evaluate = opt.evaluate;
  l.refit = opt.refit;
  l.strict_fold = opt.strict_fold;
  l.area_exponent = opt.area_exponent;
  l.area_floor = opt.area_floor;
  l.joint_guard = opt.joint_guard;
  l.normal_weight = opt.normal_weight;
  l.max_error = opt.max_error;
  l.max_joints = opt.max_joints;
  l.joint_energy = opt.joint_energy;
  l.anim_error = opt.anim_error;
  l.anim_frames = opt.anim_frames;
  l.keyframes = opt.keyframes;
  l.max_memory_mb = opt.max_memory_mb;
  return l;
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

// Runs one character through one method: the chain (from the library), the table, the files (staged in
// \p outputs; none when it is null), the page's views (when \p html is not null: the original first if the
// section is new). \p last_use is the input itself when nothing copies it after this run: its appearance
// attributes are released once the working copy is made. Returns the report entry.
json run_character(const Mesh& mesh, const std::string& name, const Options& opt, const std::string& method,
                   const std::string& output, OutputSet* outputs, std::vector<HtmlSection>* html = nullptr,
                   const std::string& section_title = "", Mesh* last_use = nullptr) {
  const bool want_html = html != nullptr;
  LodOptions lo = lod_options(opt, method);
  lo.per_vertex_error = want_html;
  TerminalProgress progress(!opt.quiet, name + " (" + lod_method_for(lo, mesh) + ")", stage);
  LodCallbacks cb = progress.callbacks();
  if (!opt.quiet) cb.message = [](const std::string& line) { std::cout << line << "\n"; };
  cb.warning = [](const std::string& line) { std::cerr << "skinned-decimate: warning: " << line << "\n"; };
  // Nothing copies the input after this run: from here on it is only the reference surface.
  if (last_use && !html) cb.input_copied = [last_use] { keep_as_reference_only(*last_use); };
  const LodChain chain = make_lods(mesh, lo, cb, name);
  progress.done();
  const bool animated = !clips(mesh).empty();
  const bool frame_animation = !frame_times(mesh).empty();
  print_table(name + " — " + method + (animated ? "" : ", rest pose only") +
                  (frame_animation ? ", " + std::to_string(frame_times(mesh).size()) + " frames" : "") + ", " +
                  std::to_string(mesh.n_faces()) + " triangles in",
              chain.levels, animated);
  const auto t_export = Clock::now();
  json lods = json::array();
  std::vector<std::string> files;
  for (size_t i = 0; i < chain.levels.size(); ++i) {
    const auto& [lod, lmesh] = chain.levels[i];
    if (outputs) {
      stage = "writing the LODs";
      files.push_back(lod_file_path(output, i, chain.levels.size()));
      export_gltf(lmesh, outputs->staging(files.back()), lod_node_extras(lod));
    }
    lods.push_back(
        lod_json(lod, outputs ? files.back() : "", clips(mesh), chain.poses.schedule, opt.bind_pose && animated));
  }
  for (const auto& file : files) std::cout << "  wrote " << file << "\n";
  if (want_html) {
    if (html->empty() || html->back().title != section_title) {
      html->push_back(new_section(section_title, mesh, chain.poses.schedule));
      add_view(html->back(), "original", mesh, nullptr, {});
    }
    for (const auto& [lod, lmesh] : chain.levels)
      add_view(html->back(), method + " " + fmt(100.0 * lod.ratio, 1) + "%", lmesh, &lod, lod.vertex_error);
  }
  return {{"input", name},
          {"method", method},
          {"triangles_in", mesh.n_faces()},
          {"units", "percent of the rest-pose bounding-box diagonal"},
          {"seconds",
           {{"decimate", chain.decimate_seconds},
            {"evaluate", chain.evaluate_seconds},
            {"export", seconds(t_export, Clock::now())}}},
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
    for (size_t i = 0; i < n; ++i) outputs.add(lod_file_path(name, i, n));
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

// What the command line alone can be wrong about, then what the library refuses (LodOptionsError: exit 2).
void check_arguments(const Options& opt) {
  if (opt.ratio_given && !(opt.ratio > 0.0 && opt.ratio <= 1.0)) throw UsageError("--ratio must be in (0, 1]");
  if (!(opt.time_limit >= 0.0)) throw UsageError("--time-limit must be 0 (none) or more seconds");
  if (!is_lod_method(opt.method)) throw UsageError("--method must be " + lod_method_names());
  check_lod_options(lod_options(opt, opt.method));
}

const char* current_stage() { return stage.load(); }

namespace {

// Every file the run writes, refused before any work when one would clash with an input or another output.
void plan_run_outputs(const Options& opt, OutputSet& outputs) {
  try {
    if (!opt.output.empty()) plan_outputs(opt, {opt.output}, outputs);
    if (!opt.segment.empty()) {
      outputs.add(opt.segment);
      outputs.add(segmentation_json_path(opt.segment));
    }
  } catch (const IOError& e) {
    throw UsageError(e.what());  // a clash or a missing folder is the command line's fault: exit 2
  }
}

ImportReport read_input(const Options& opt, const std::vector<std::string>& frames, Mesh& mesh) {
  ImportOptions io;
  io.isolate = opt.isolate;
  io.memory_limit_mb = opt.max_memory_mb;
  io.time_limit_seconds = opt.time_limit;
  io.show_reader_output = opt.verbose;
  stage = "reading the input";
  const auto rep = frames.empty() ? import_skinned(opt.input, mesh, io)
                                  : import_frame_animation(frames, mesh, io, frame_rate(frames, opt.fps));
  if (!frames.empty() && !opt.quiet && frames.size() > 1)
    std::cout << opt.input << ": one frame of " << frames.size() << " files "
              << fs::path(frames.front()).filename().string() << " .. " << fs::path(frames.back()).filename().string()
              << " (--no-sequence reads it alone)\n";
  return rep;
}

// The LOD chains (every method's with --compare), their page sections, and the report.
json run_methods(Mesh& mesh, const Options& opt, OutputSet& outputs, std::vector<HtmlSection>* sections) {
  Options o = opt;
  // A mesh animated without a skeleton gets the frame quadric by default: only it sees morph-target frames.
  o.method = lod_method_for(lod_options(opt, opt.method_given ? opt.method : ""), mesh);
  const std::string title = fs::path(opt.input).filename().string();
  if (!o.compare) return run_character(mesh, opt.input, o, o.method, opt.output, &outputs, sections, title, &mesh);
  json runs = json::array();
  for (const LodMethod& m : lod_methods()) {
    Options om = o;
    const std::string name = m.name;
    if (om.max_error > 0.0 && (name == "frames" || name == "deform")) {
      std::cerr << "skinned-decimate: warning: --max-error does not apply to --method " << name
                << " (it places vertices itself); its LODs are not bounded\n";
      om.max_error = 0.0;
    }
    runs.push_back(
        run_character(mesh, opt.input, om, name, opt.output, name == o.method ? &outputs : nullptr, sections, title));
    std::cout << "\n";
  }
  print_comparison(runs);
  return {{"input", opt.input}, {"runs", runs}};
}

}  // namespace

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
  plan_run_outputs(opt, outputs);
  Mesh mesh;
  const auto t_import = Clock::now();
  const ImportReport rep = read_input(opt, frames, mesh);
  const double import_s = seconds(t_import, Clock::now());
  // --compare runs every method: whether a method can be bounded is its own run's business.
  check_lod_options(lod_options(opt, opt.compare ? "skinned" : opt.method_given ? opt.method : ""), mesh, opt.input);
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
  const bool page = !opt.html.empty() || !opt.preview.empty();
  std::vector<HtmlSection> sections;
  json report = run_methods(mesh, opt, outputs, page ? &sections : nullptr);
  if (page) write_page(opt, "skinned-decimate: " + fs::path(opt.input).filename().string(), sections, outputs);
  report["import_seconds"] = import_s;
  if (!opt.report.empty()) write_text(outputs.staging(opt.report), report.dump(2) + "\n");
  outputs.commit();
  return 0;
}

}  // namespace skinned_decimate
