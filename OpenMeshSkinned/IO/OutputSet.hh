#pragma once
/** \file OutputSet.hh
 *  The files one run writes, committed all together or not at all, and never on top of an input.
 *
 *  Plan every output first (add()), so that a name clash is refused before any work is done; write each
 *  to its staging path; commit() renames them all into place. Until then nothing the user can see has
 *  changed, and destroying the set without commit() removes every staged file.
 */

#include "OpenMeshSkinned/IO/IOError.hh"

#include <string>
#include <vector>

namespace OpenMeshSkinned {

/// An output path that is an input, or another output of the same run.
class PathConflict : public IOError {
public:
  using IOError::IOError;
};

class OutputSet {
public:
  /// \p inputs: files the run reads; no output may be one of them (by path, symlink or hard link).
  explicit OutputSet(std::vector<std::string> inputs = {});
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  /** Plans \p path; returns where to write it until commit(): a hidden file beside it that keeps its
   *  extension. Throws PathConflict when \p path resolves to an input or to a path already planned,
   *  IOError when its folder does not exist or is not writable. */
  std::string add(const std::string& path);

  /// Staging path of a planned output.
  const std::string& staging(const std::string& path) const;

  /** Renames every staged file to its final name. Throws IOError (and removes what is staged) when one is
   *  missing; a rename that fails part-way undoes the ones made. */
  void commit();

private:
  struct Entry {
    std::string path, resolved, staged;
  };
  std::vector<std::string> inputs_;
  std::vector<Entry> entries_;
  bool committed_ = false;
};

}  // namespace OpenMeshSkinned
