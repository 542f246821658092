#pragma once
// What make_lods() tells its caller while it runs, and how the caller stops it.

#include <functional>
#include <stdexcept>
#include <string>

namespace OpenMeshSkinned {

/// Thrown by make_lods() when its progress callback returned false.
struct LodCancelled : std::runtime_error {
  LodCancelled() : std::runtime_error("cancelled") {}
};

struct LodCallbacks {
  /** Called on the calling thread at each stage ("choosing the example poses", "decimating", "fitting",
   *  "reducing the skeleton and clips", "measuring the held-out error"; a string literal) and as it
   *  advances, with the fraction of that stage done. Return false to cancel: make_lods() stops at the next
   *  check and throws LodCancelled. */
  std::function<bool(const char* stage, double fraction)> progress;
  /// What was chosen or done, one line each (the CLI prints them unless --quiet).
  std::function<void(const std::string&)> message;
  /// What the caller should know was changed or not applied, one line each.
  std::function<void(const std::string&)> warning;
  /// The job has taken its working copy of the input: from here on the input is only the reference surface
  /// (a caller that keeps nothing else of it may release its corner attributes, keep_as_reference_only()).
  std::function<void()> input_copied;

  /// Reports; throws LodCancelled when the callback asks to stop.
  void report(const char* stage, double fraction) const {
    if (progress && !progress(stage, fraction)) throw LodCancelled();
  }
  void say(const std::string& line) const {
    if (message) message(line);
  }
  void warn(const std::string& line) const {
    if (warning) warning(line);
  }
};

}  // namespace OpenMeshSkinned
