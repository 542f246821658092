#pragma once
// LodOptions from Python keywords, and back.

#include <OpenMeshSkinned/Lod/LodOptions.hh>

#include <pybind11/pybind11.h>

#include <string>
#include <vector>

namespace omsk_python {

namespace py = pybind11;

/** The options \p kwargs set over LodOptions' defaults (None keeps a default). Raises TypeError naming
 *  \p function for an unknown keyword or a value of the wrong type; the values' ranges are the library's to
 *  check (LodOptionsError, with the command line's messages). */
OpenMeshSkinned::LodOptions lod_options(const py::kwargs& kwargs, const char* function);

/// Every field of \p options by its keyword.
py::dict options_dict(const OpenMeshSkinned::LodOptions& options);

/** The tool's command-line options for \p options: a flag for every field that is not its default, so that
 *  a batch run of one asset makes what make_lods() with the same keywords makes. Raises TypeError for
 *  per_vertex_error (no option of the tool's: its page has it), LodOptionsError for more than one face count. */
std::vector<std::string> tool_arguments(const OpenMeshSkinned::LodOptions& options);

/// One line per keyword: its type, its default and what it does, for the docstrings.
std::string options_doc();

}  // namespace omsk_python
