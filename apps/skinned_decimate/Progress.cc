#include "Progress.hh"

#include <unistd.h>

#include <cstdio>
#include <cstring>

namespace skinned_decimate {

TerminalProgress::TerminalProgress(bool show, std::string label, std::atomic<const char*>& stage)
    : show_(show && isatty(2)), label_(std::move(label)), stage_(stage) {}

TerminalProgress::~TerminalProgress() { done(); }

OpenMeshSkinned::LodCallbacks TerminalProgress::callbacks() {
  OpenMeshSkinned::LodCallbacks cb;
  cb.progress = [this](const char* stage, double fraction) { return update(stage, fraction); };
  return cb;
}

bool TerminalProgress::update(const char* stage, double fraction) {
  stage_ = stage;
  if (!show_ || std::strcmp(stage, "decimating") != 0) return true;
  const auto now = std::chrono::steady_clock::now();
  if (!started_) started_ = true, start_ = now;
  if (now - start_ < std::chrono::seconds(1)) return true;
  std::fprintf(stderr, "\r%s: %3d%% of collapses", label_.c_str(), int(100.0 * fraction));
  shown_ = true;
  return true;
}

void TerminalProgress::done() {
  if (shown_) std::fprintf(stderr, "\r%*s\r", int(label_.size()) + 20, "");
  shown_ = false;
}

}  // namespace skinned_decimate
