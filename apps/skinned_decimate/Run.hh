#pragma once
// One invocation of the tool, once the command line is parsed.

#include "Options.hh"

namespace skinned_decimate {

/// Throws UsageError, or LodOptionsError (exit 2), when the options cannot be right for any input.
void check_arguments(const Options& opt);

/// Returns the exit code; throws UsageError (exit 2) or another exception (exit 1).
int run(const Options& opt);

/// What run() was doing last ("reading the input", "decimating", ...), for a message when memory runs out.
const char* current_stage();

}  // namespace skinned_decimate
