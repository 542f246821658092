#include "CommandLine.hh"

#include <OpenMeshSkinned/Lod/LodAreaExponent.hh>
#include <OpenMeshSkinned/Lod/LodMethods.hh>
#include <OpenMeshSkinned/Lod/LodOptions.hh>
#include <OpenMeshSkinned/Lod/LodPoseCount.hh>
#include <OpenMeshSkinned/Lod/LodPoses.hh>

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace skinned_decimate {

namespace {

std::string method_help() {
  std::string s = "Priority module:";
  for (const auto& m : OpenMeshSkinned::lod_methods()) s += std::string(" ") + m.name + " (" + m.help + "),";
  s.back() = '.';
  return s;
}

// Input, output, the decimation and the report.
void declare_run_options(CLI::App& app, Options& opt, OptionWords& c) {
  app.add_option("input", opt.input,
                 "Skinned asset (glTF/GLB, FBX, Collada, X, MD5, ...), or a mesh animated without a skeleton: an "
                 "MD2/MD3/MDL file (every stored frame is read) or one file of a numbered OBJ/PLY/STL/OFF sequence "
                 "(walk_0001.obj, walk_0002.obj, ...: every file of it is a frame)")
      ->check(CLI::ExistingFile);
  app.add_option(
      "-o,--output", opt.output,
      "Output .glb/.gltf; with --lods, NAME_lod1.glb, NAME_lod2.glb ... in the order of decreasing ratio "
      "(with no INPUT: the output folder). Never the input: all files of a run appear together at the end, or none");
  auto* r = app.add_option("--ratio", opt.ratio, "Keep this fraction of the triangles, in (0,1] (default 0.5)");
  auto* f = app.add_option("--faces", opt.faces, "Keep this many triangles");
  auto* l =
      app.add_option("--lods", opt.lods, "A chain of ratios, built in one pass, e.g. 0.5,0.25,0.1")->delimiter(',');
  r->excludes(f)->excludes(l);
  f->excludes(l);
  app.add_option("--max-influences", opt.max_influences, "Bone influences per vertex at most (1-8, default 4)");
  app.add_option("--poses", opt.poses,
                 "Example poses: K evenly spaced times over the clip, both ends included, plus the bind pose (1-" +
                     std::to_string(OpenMeshSkinned::kMaxLodPoses) +
                     "; default 0: " + OpenMeshSkinned::lod_pose_count_rule() + ")");
  app.add_option("--pose-clip", opt.pose_clip,
                 "Clip (name or index) for the example poses; default: all clips end to end");
  app.add_option("--method", opt.method, method_help());
  app.add_flag("--compare", opt.compare, "Run every method on the same input and print one table");
  app.add_option("--report", opt.report, "Write the summary as JSON");
  app.add_flag("--quiet", opt.quiet, "No progress and no pose list (warnings are still printed)");
  app.add_flag("--verbose", opt.verbose,
               "Also show what the input's reader printed (by default collected and dropped, so that a failure is "
               "one line)");
  app.add_flag("!--no-bind-pose", opt.bind_pose, "Do not add the bind pose to the example poses");
  app.add_flag("!--no-isolate", opt.isolate,
               "Read the input in this process (by default a child process reads it, so that a reader crash on a "
               "corrupt file is a clean error)");
  app.add_option("--max-memory", opt.max_memory_mb,
                 "Memory limit in MB for reading the input and for the example poses (default 8192; 0 = none)");
  app.add_option("--time-limit", opt.time_limit, "Seconds the input's reader may take (default 300; 0 = none)");
  app.add_option("--threads", opt.threads, "Threads for solving edges and measuring error (default: all cores)")
      ->check(CLI::Range(1, 256));
  app.add_option("--html", opt.html,
                 "Write a self-contained page playing the original and every LOD side by side, with the held-out "
                 "error per vertex as colours");
  app.add_option("--html-assets", c.assets, "embed (default: the GLBs inside the page) or beside (in PAGE.assets.js)")
      ->check(CLI::IsMember({"embed", "beside"}));
  app.add_option("--preview", opt.preview,
                 "Write a PNG contact sheet of the page (rows: original and LODs; columns: held-out frames), "
                 "rendered by headless Chromium");
}

// --error's word or number as the area exponent (its range is checked with the other LOD options); NaN for
// anything else.
double area_exponent_of(const std::string& s) {
  if (s == "auto") return OpenMeshSkinned::kAutoAreaExponent;
  if (s == "balanced") return 0.5;
  if (s == "per-area") return 1.0;
  if (s == "energy") return 0.0;
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  return !s.empty() && *end == '\0' ? v : std::nan("");
}

// The layers beyond the mesh (skeleton and motion LoD), the worst-case bound, frame animations, pricing.
void declare_layer_options(CLI::App& app, Options& opt, OptionWords& c) {
  app.add_option("--joint-guard", opt.joint_guard,
                 "Savoye & Meyer's joint-region guard: vertices with a weight of at least TAU times their joint's "
                 "average weight may not disappear (the paper's TAU is 1; default off)")
      ->check(CLI::PositiveNumber);
  app.add_option("--normal-weight", opt.normal_weight,
                 "Weight of the shading-normal term in the collapse cost: how far a collapse spreads a bent normal "
                 "over faces that showed another (0: geometry only; default 0.03)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--max-joints", opt.max_joints,
                 "Skeleton LoD: remove minor joints (Savoye & Meyer) until N remain, baking their motion into their "
                 "children and re-solving the skins; one value, or one per LOD (N1,N2,...; the last repeats)")
      ->delimiter(',')
      ->check(CLI::PositiveNumber);
  app.add_option("--joint-energy", opt.joint_energy,
                 "Skeleton LoD by the paper's threshold: remove every minor joint whose joint energy over the clips "
                 "is under E (with or without --max-joints)")
      ->check(CLI::PositiveNumber);
  app.add_option("--anim-error", opt.anim_error,
                 "Motion LoD: drop every key frame whose loss moves no vertex of the LOD by more than E % of the "
                 "diagonal, in any frame of the clips (default: clips kept whole)")
      ->check(CLI::PositiveNumber);
  app.add_option("--anim-method", c.anim_method,
                 "How --anim-error drops keys: channels (each channel where interpolation reproduces it; default) "
                 "or frames (the paper's merge of whole key frames by joint energy)")
      ->check(CLI::IsMember({"channels", "frames"}));
  app.add_flag("--strict-fold", opt.strict_fold,
               "Stop where every collapse would turn a face by more than 90 degrees in some pose (by default, to "
               "reach the target, such a collapse is first made at the midpoint or an endpoint where that folds "
               "nothing, then the limit is relaxed to 120, 150, then 175 degrees, and the table says so)");
  app.add_option("--max-error", opt.max_error,
                 "Bound the worst case: no vertex of the input may end up further than E % of the diagonal from the "
                 "LOD in any example pose (a collapse that would break it waits; a LOD may stop above its target, "
                 "and the table says so; the fold-over limit is not relaxed; a final fit that would break it is "
                 "undone)")
      ->check(CLI::PositiveNumber);
  app.add_flag("!--no-sequence", opt.sequences,
               "Read a numbered file as one mesh, not as a frame of the sequence its siblings make");
  app.add_option("--fps", opt.fps,
                 "Frame rate of a mesh animated without a skeleton (default 10 for MD2/MD3/MDL, 24 for sequences)")
      ->check(CLI::PositiveNumber);
  app.add_option("--keyframes", opt.keyframes,
                 "Meshes animated without a skeleton: keep K of the frames in the LODs, chosen by a genetic "
                 "algorithm (the deformation-analysis report) so that interpolation rebuilds the others best")
      ->check(CLI::Range(2, 100000));
  app.add_option("--pose-select", c.pose_select,
                 "How the example poses are chosen: even (evenly spaced times; default), or among the frames that "
                 "are not held out: motion (evenly spaced over the motion, so that a short, fast clip gets its "
                 "share), spread (farthest first over the motion) or ga (the key-frame genetic algorithm)")
      ->check(CLI::IsMember(OpenMeshSkinned::pose_selections()));
  app.add_option("--segment", opt.segment,
                 "Write the input cut into near-rigid parts (Lee et al.) as OUT.glb, one colour per part, and "
                 "the parts of its faces as OUT.json; without -o nothing is decimated");
  app.add_option("--error", c.error_measure,
                 "How the skinned and frames methods price a collapse: its energy over a power of the area it "
                 "stands for. balanced (over its square root), per-area (over the area, a mean squared "
                 "distance), energy (the energy as it is), the power as a number in [0, 1], or auto (default: "
                 "skinned, balanced up to 20000 vertices, where it measured the lower RMS, per-area above; "
                 "frames, 0.25 when the coarsest LOD keeps at most half of the triangles, energy otherwise)")
      ->check(CLI::Validator(
          [](std::string& s) -> std::string {
            return std::isnan(area_exponent_of(s)) ? "must be auto, balanced, per-area, energy or a number in [0, 1]"
                                                   : "";
          },
          "MEASURE"));
  app.add_option("--area-floor", opt.area_floor,
                 "Collapses standing for less than N of the coarsest LOD's mean triangles are priced per area "
                 "whatever --error says, so a small sharp feature stays as dear as its distance (0: no floor; "
                 "default 2)");
  app.add_flag("!--no-refit", opt.refit,
               "Skip the final fit (by default every LOD vertex's rest position is refitted against the original "
               "surface in all example poses: sparse least squares, three rounds; on inputs of up to 20000 "
               "vertices points of the LOD's faces are drawn to the original too, each pass ends by fitting the skin "
               "weights over each vertex's and its neighbours' joints, and edges whose other diagonal "
               "lies closer to the original are then flipped and the fit run twice more, each pass from where the "
               "last left the LOD; a frame animation's stored frames are then each fitted on their own)");
  app.add_flag("!--no-eval", opt.evaluate,
               "Skip measuring the error in held-out frames (batch use: the table shows triangles and time only)");
}

}  // namespace

void declare_options(CLI::App& app, Options& opt, OptionWords& c) {
  declare_run_options(app, opt, c);
  declare_layer_options(app, opt, c);
}

void finish_options(const CLI::App& app, const OptionWords& c, Options& opt) {
  opt.html_beside = c.assets == "beside";
  opt.anim_frames = c.anim_method == "frames";
  opt.pose_select = c.pose_select;
  opt.area_exponent = area_exponent_of(c.error_measure);
  opt.method_given = app.count("--method") > 0;
  opt.poses_given = app.count("--poses") > 0;
  opt.ratio_given = app.count("--ratio") > 0;
  opt.faces_given = app.count("--faces") > 0;
  std::sort(opt.lods.rbegin(), opt.lods.rend());
}

}  // namespace skinned_decimate
