#pragma once
// The options of one run of skinned-decimate, declared on a CLI11 app (the batch subcommand passes them on).
#include "Options.hh"

#include <CLI/CLI.hpp>

#include <string>

namespace skinned_decimate {

/// Options given as words, turned into Options' fields once parsed.
struct OptionWords {
  std::string assets = "embed";
  std::string anim_method = "channels";
  std::string pose_select = "even";
  std::string error_measure = "auto";
};

/// Declares every option of a single run on \p app, writing into \p opt and \p c when parsed.
void declare_options(CLI::App& app, Options& opt, OptionWords& c);
/// After parsing: the words into \p opt, and what was given explicitly.
void finish_options(const CLI::App& app, const OptionWords& c, Options& opt);

}  // namespace skinned_decimate
