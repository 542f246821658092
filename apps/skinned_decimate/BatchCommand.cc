#include "BatchCommand.hh"

#include "Options.hh"

#include <OpenMeshSkinned/Lod/Batch.hh>

#include <unistd.h>

#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace skinned_decimate {

namespace {

namespace fs = std::filesystem;
using namespace OpenMeshSkinned;

// Options of a single run that name its files: the batch names each asset's files itself.
struct Refused {
  const char* option;
  const char* why;
};
const Refused kRefused[] = {
    {"input", "takes a folder (IN_DIR after batch), not an INPUT file"},
    {"--output", "needs -o OUT_DIR after batch, the folder every asset's files go to"},
    {"--report", "writes each asset's report as OUT_DIR/NAME.report.json: drop --report"},
    {"--html", "writes each asset's page as OUT_DIR/NAME.html with --html after batch, with no file name"},
    {"--preview", "has no contact sheets (--preview): each asset's page (--html) shows its LODs"},
    {"--segment", "does not segment: run --segment on one file"},
};

std::string self_executable() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw std::runtime_error("batch: cannot find this program's own file: " + ec.message());
  return p.string();
}

std::string describe(const AssetResult& r) {
  std::ostringstream os;
  os << r.name << ": " << status_name(r.status);
  if (r.status == AssetStatus::Failed) os << ": " << r.reason;
  if (r.status == AssetStatus::Ok) os << ", " << std::fixed << std::setprecision(1) << r.seconds << " s";
  return os.str();
}

}  // namespace

std::vector<std::string> given_arguments(const CLI::App& app) {
  std::vector<std::string> args;
  for (const CLI::Option* o : app.get_options()) {
    if (o->count() == 0 || o->get_positional() || o->get_lnames().empty() || o == app.get_help_ptr() ||
        o == app.get_help_all_ptr())
      continue;
    const std::string name = "--" + o->get_lnames().front();
    if (o->get_expected_max() == 0) {  // a flag
      args.push_back(name);
      continue;
    }
    const std::vector<std::string> values = o->reduced_results();
    if (o->get_delimiter() != '\0') {
      std::string joined;
      for (const std::string& v : values) joined += (joined.empty() ? "" : std::string(1, o->get_delimiter())) + v;
      args.insert(args.end(), {name, joined});
    } else {
      for (const std::string& v : values) args.insert(args.end(), {name, v});
    }
  }
  return args;
}

BatchCommand::BatchCommand(CLI::App& app) {
  sub_ = app.add_subcommand(
      "batch",
      "Every asset below IN_DIR (each file a reader takes; a numbered OBJ/PLY/STL/OFF sequence is one), each "
      "run by this program in a process of its own, so that a file that crashes or exhausts its limits "
      "fails alone. The options of a single run (--ratio, --lods, --poses, --max-influences, ...) apply to "
      "each asset; those naming one run's files (-o FILE, --report, --html PAGE, --preview, --segment) are "
      "refused. Per asset NAME (its path below IN_DIR without the extension) OUT_DIR gets NAME.glb "
      "(NAME_lod1.glb ... with --lods), NAME.report.json, NAME.log and NAME.batch.json; and for all of them "
      "summary.json and index.html. An asset whose outputs are newer than it and were made by this version "
      "with the same options is skipped. Exit 0 when every asset is ok or skipped, 1 when any failed.");
  sub_->fallthrough();
  sub_->add_option("in_dir", in_dir_, "Folder of assets (searched recursively; hidden files left out)")
      ->required()
      ->check(CLI::ExistingDirectory);
  sub_->add_option("-o,--output", out_dir_, "Folder for the outputs (made when missing)")->required();
  sub_->add_option("--jobs", jobs_, "Assets run at the same time (default 1; each uses --threads, or all cores)")
      ->check(CLI::Range(1, 256));
  sub_->add_flag("--force", force_, "Run every asset, also those whose outputs are up to date");
  sub_->add_flag("--html", html_, "Also write each asset's report page, OUT_DIR/NAME.html, linked from index.html");
  sub_->add_option("--asset-time-limit", time_limit_,
                   "Seconds one asset may take before it is stopped and failed (default 0: none)")
      ->check(CLI::NonNegativeNumber);
}

int BatchCommand::run(const CLI::App& app) const {
  for (const Refused& r : kRefused) {
    const CLI::Option* o = app.get_option_no_throw(r.option);
    if (o && o->count() > 0)
      throw UsageError(std::string("batch ") + r.why + " (" + (o->get_positional() ? "INPUT" : r.option) +
                       " given before batch)");
  }
  std::error_code ec;
  if (fs::exists(out_dir_, ec) && !fs::is_directory(out_dir_, ec))
    throw UsageError("batch: " + out_dir_ + ": is a file, not a folder");
  if (fs::exists(out_dir_, ec) && fs::equivalent(in_dir_, out_dir_, ec))
    throw UsageError("batch: -o " + out_dir_ + " is IN_DIR itself: the LODs would be read as assets next time");
  BatchOptions options;
  options.executable = self_executable();
  options.out_dir = out_dir_;
  options.jobs = jobs_;
  options.arguments = given_arguments(app);
  options.html = html_;
  options.force = force_;
  options.asset_time_limit = time_limit_;
  const bool sequences =
      std::find(options.arguments.begin(), options.arguments.end(), "--no-sequence") == options.arguments.end();
  const std::vector<BatchInput> inputs = find_inputs(in_dir_, out_dir_, sequences);
  if (inputs.empty())
    throw UsageError("batch: " + in_dir_ + " holds no file a reader takes (glTF/GLB, FBX, Collada, X, OBJ, ...)");
  fs::create_directories(out_dir_, ec);
  if (ec) throw std::runtime_error("batch: " + out_dir_ + ": cannot be made: " + ec.message());
  const auto results = run_batch(inputs, options, [](const BatchProgress& p) {
    std::cout << progress_line(p) << " (" << describe(*p.last) << ")" << std::endl;
    return true;
  });
  write_summary(results, options);
  size_t failed = 0, skipped = 0;
  for (const AssetResult& r : results) {
    failed += r.status == AssetStatus::Failed;
    skipped += r.status == AssetStatus::Skipped;
  }
  const std::string index = (fs::path(out_dir_) / "index.html").string();
  if (failed > 0) {
    std::cout << "batch: " << failed << " of " << results.size() << " assets failed; summary: " << index << "\n";
    return 1;
  }
  std::cout << "batch: all " << results.size() << " assets ok (" << skipped
            << " skipped, up to date); summary: " << index << "\n";
  return 0;
}

}  // namespace skinned_decimate
