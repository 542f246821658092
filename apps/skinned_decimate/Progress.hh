#pragma once
// The library's progress as the tool shows it: the stage for the out-of-memory message, and the share of
// collapses on the terminal once the decimation has taken a second.

#include <OpenMeshSkinned/Lod/LodProgress.hh>

#include <atomic>
#include <chrono>
#include <string>

namespace skinned_decimate {

class TerminalProgress {
public:
  /// \p show: the percentage on stderr when it is a terminal; \p stage: where the current stage is kept.
  TerminalProgress(bool show, std::string label, std::atomic<const char*>& stage);
  ~TerminalProgress();
  TerminalProgress(const TerminalProgress&) = delete;
  TerminalProgress& operator=(const TerminalProgress&) = delete;

  /// Callbacks whose progress is this object (messages and warnings left to the caller).
  OpenMeshSkinned::LodCallbacks callbacks();
  /// Clears the line, if one was shown.
  void done();

private:
  bool update(const char* stage, double fraction);

  bool show_;
  std::string label_;
  std::atomic<const char*>& stage_;
  std::chrono::steady_clock::time_point start_{};
  bool started_ = false, shown_ = false;
};

}  // namespace skinned_decimate
