#pragma once
// What the binding's files share: the Python-side mesh (a shared, never-changed SkinnedMesh), the package's
// exception types, and the functions each file adds to the module.

#include <OpenMeshSkinned/Lod/LodReport.hh>
#include <OpenMeshSkinned/Skin/SkinnedMesh.hh>

#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

namespace omsk_python {

namespace py = pybind11;
using OpenMeshSkinned::SkinnedMesh;

/// A mesh as Python sees it: shared (a LOD's mesh keeps its chain alive) and never changed after it is made,
/// so that NumPy copies of it can be taken from any thread.
struct Mesh {
  std::shared_ptr<const SkinnedMesh> mesh;
  std::string path;                   ///< the file it was read from (empty for a LOD): never written over
  std::vector<std::string> warnings;  ///< what the reader changed or could not use, one line each
};

/// A LOD chain as Python sees it, with the file its input came from (never written over by save()).
struct Chain {
  std::shared_ptr<OpenMeshSkinned::LodChain> chain;
  std::string input_path;
  std::vector<std::string> clip_names;  ///< the input's, to name the frames
  std::vector<std::string> messages, warnings;
};

/// The package's exceptions (created in module.cc): Error, and its OptionsError (ValueError), FileError
/// (OSError) with ReadError and WriteError, and Cancelled.
struct Exceptions {
  py::handle error, options, file, read, write, cancelled;  // owned by the module (no teardown at exit)
};
const Exceptions& exceptions();

/// Raises \p type with the library's message \p what as one printable line, as the command line prints it.
/// Call with the GIL held.
[[noreturn]] void raise(py::handle type, const char* what);

void add_mesh(py::module_& m);
void add_lods(py::module_& m);
void add_evaluate(py::module_& m);
void add_batch(py::module_& m);

}  // namespace omsk_python
