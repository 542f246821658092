#pragma once
/** \file Batch.hh
 *  LODs for a whole library of assets: each asset is run by the skinned-decimate tool in a process of
 *  its own (a crash, an exhausted memory limit or a hang in one never stops the others), N at a time;
 *  an asset whose outputs are up to date is skipped; one summary (summary.json and index.html) lists
 *  every asset with its numbers or the one-line reason it failed.
 *
 *  run_asset() is the unit of work on its own, for a scheduler that spreads the assets over machines
 *  (each task calls run_asset(); the results come back as JSON, asset_result_json(), and the caller
 *  writes the summary).
 *
 *  Per asset NAME (see BatchInput), in the output folder: NAME.glb (NAME_lod1.glb ... with --lods),
 *  NAME.report.json (the tool's report), NAME.html with BatchOptions::html, NAME.log (what the tool
 *  printed) and NAME.batch.json (the options it was made with and its result, for resuming).
 */

#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace OpenMeshSkinned {

/// One asset of a batch: the file to read and the name its outputs take in the output folder.
struct BatchInput {
  std::string path;
  /// Relative to the output folder, '/'-separated: the input's path below the input folder without its
  /// extension ("chars/hero"), or with it ("chars/hero.fbx") when two inputs would share a name.
  std::string name;
};

struct BatchOptions {
  std::string executable;  ///< the skinned-decimate program
  std::string out_dir;     ///< created when missing
  int jobs = 1;            ///< assets run at the same time
  /// Options for each asset, as on skinned-decimate's command line ("--ratio", "0.5", ...); not -o,
  /// --report, --html, which the batch sets per asset.
  std::vector<std::string> arguments;
  bool html = false;              ///< also write NAME.html, the tool's report page
  bool force = false;             ///< run assets whose outputs are up to date too
  double asset_time_limit = 0.0;  ///< seconds an asset may take before it is killed; 0 = no limit
};

/// One LOD of an asset, from the tool's report. NaN errors: not measured (--no-eval).
struct LodResult {
  double ratio = 0.0;
  size_t triangles = 0;
  double heldout_rms = std::numeric_limits<double>::quiet_NaN();        ///< % of the diagonal
  double heldout_hausdorff = std::numeric_limits<double>::quiet_NaN();  ///< % of the diagonal
  std::string file;
};

enum class AssetStatus { Ok, Failed, Skipped };

/// "ok", "failed", "skipped".
const char* status_name(AssetStatus s);

struct AssetResult {
  std::string input, name;
  AssetStatus status = AssetStatus::Failed;
  /// Why it failed, one line: the tool's error message, "crashed (signal 11: Segmentation fault)" or
  /// "timed out after 60 s"; for a skipped asset, why it was skipped.
  std::string reason;
  double seconds = 0.0;  ///< of the run that made the outputs (a skipped asset: its previous run)
  size_t triangles_in = 0;
  std::vector<LodResult> lods;
  std::string log, report, page;  ///< paths of NAME.log, NAME.report.json and NAME.html ("" when none)
};

/** Every file below \p dir that a reader of the tool takes (the extensions assimp reads, less its
 *  animation-only .md5anim/.md5camera and XML other than .mesh.xml), in the order of their paths;
 *  hidden files and folders, and \p out_dir when it is inside \p dir, are left out. With \p sequences,
 *  a numbered OBJ/PLY/STL/OFF sequence (walk_0001.obj, walk_0002.obj, ...) is one asset, its first
 *  file, as the tool reads it. Throws IOError when \p dir is not a folder. */
std::vector<BatchInput> find_inputs(const std::string& dir, const std::string& out_dir = "", bool sequences = true);

/// Names for a list of files: their paths below the folder they all are in (see BatchInput::name).
std::vector<BatchInput> batch_inputs(const std::vector<std::string>& paths);

/** Runs one asset in a child process (unless its outputs are up to date, see run_batch()) and returns its
 *  result; a failure of the asset is a result, not an exception. Throws IOError when the output folder
 *  cannot be made or the program cannot be started. */
AssetResult run_asset(const BatchInput& input, const BatchOptions& options);

struct BatchProgress {
  size_t total = 0, done = 0, failed = 0, skipped = 0;
  const AssetResult* last = nullptr;  ///< the asset that just finished
};

/// "batch: 7/20 done, 1 failed, 2 skipped".
std::string progress_line(const BatchProgress& p);

/** Runs every input, options.jobs at a time, calling \p progress after each (returning false cancels:
 *  running children are killed and the assets not yet finished are failed, "cancelled"). An asset is
 *  skipped when its NAME.batch.json says it was made by this version of the tool with the same
 *  arguments and html setting and succeeded, and its report, LODs and page exist and are newer than its
 *  input (all files of a numbered sequence): it keeps the numbers of that run. Results are in the order
 *  of \p inputs. Throws IOError as run_asset(), and when two inputs have one name. */
std::vector<AssetResult> run_batch(const std::vector<BatchInput>& inputs, const BatchOptions& options,
                                   const std::function<bool(const BatchProgress&)>& progress = {});

/** Writes summary.json and index.html into options.out_dir, both or neither: a row per asset with its
 *  status, triangles and held-out error per LOD, seconds, its report page and log, or its reason. */
void write_summary(const std::vector<AssetResult>& results, const BatchOptions& options);

/// An AssetResult as JSON, and back (throws IOError when \p json is not one): how a result crosses
/// process and machine boundaries. Paths are kept as they are.
std::string asset_result_json(const AssetResult& result);
AssetResult parse_asset_result(const std::string& json);

/// The program's name and version the outputs are stamped with ("skinned-decimate 0.1.0").
std::string batch_tool_version();

}  // namespace OpenMeshSkinned
