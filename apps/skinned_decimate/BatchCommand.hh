#pragma once
// skinned-decimate batch IN_DIR -o OUT_DIR: every asset of a folder, each in a process of its own
// (OpenMeshSkinned/Lod/Batch.hh), with the options of a single run passed on to each.

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace skinned_decimate {

class BatchCommand {
public:
  /// Adds the subcommand to \p app, whose own options become the per-asset options.
  explicit BatchCommand(CLI::App& app);
  bool parsed() const { return sub_->parsed(); }
  /** Runs the batch once \p app is parsed; returns the exit code (0: every asset ok or skipped, 1: some
   *  failed). Throws UsageError for an option that has no meaning per asset. */
  int run(const CLI::App& app) const;

private:
  CLI::App* sub_;
  std::string in_dir_, out_dir_;
  int jobs_ = 1;
  bool force_ = false, html_ = false;
  double time_limit_ = 0.0;
};

/// The options given to \p app (not its subcommands'), as arguments again, in the order they are declared.
std::vector<std::string> given_arguments(const CLI::App& app);

}  // namespace skinned_decimate
