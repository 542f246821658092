#pragma once
/** \file ReaderLog.hh
 *  What assimp's readers say while reading, kept when it means data was lost.
 *
 *  Some readers repair a bad file by dropping part of it and only log it (glTF faces with out-of-range
 *  indices, for one). Nothing may be dropped silently, so those messages become import warnings. The
 *  rest of the log (hundreds of "bone weight sum != 1.0" lines for FBX) is not passed on.
 */

#include <memory>
#include <string>
#include <vector>

namespace OpenMeshSkinned {

/// Listens to assimp's global logger for its lifetime (one at a time: assimp's logger is process-wide).
class ReaderLog {
public:
  ReaderLog();
  ~ReaderLog();
  ReaderLog(const ReaderLog&) = delete;
  ReaderLog& operator=(const ReaderLog&) = delete;

  /// Distinct messages that report dropped, skipped or ignored data, in order, with how often each came;
  /// past kMaxDistinct distinct ones, a last line counts the rest.
  std::vector<std::string> data_loss() const;
  static constexpr size_t kMaxDistinct = 20;

  /// True when \p message says the reader dropped data (the filter data_loss() applies).
  static bool reports_data_loss(const std::string& message);

  struct Sink;  ///< where the logger's stream collects (shared: assimp owns the stream)

private:
  std::shared_ptr<Sink> sink_;
};

}  // namespace OpenMeshSkinned
