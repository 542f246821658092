#pragma once
// LodOptions from Python keywords, and back.

#include <OpenMeshSkinned/Lod/LodOptions.hh>

#include <pybind11/pybind11.h>

#include <string>

namespace omsk_python {

namespace py = pybind11;

/** The options \p kwargs set over LodOptions' defaults (None keeps a default). Raises TypeError naming
 *  \p function for an unknown keyword or a value of the wrong type; the values' ranges are the library's to
 *  check (LodOptionsError, with the command line's messages). */
OpenMeshSkinned::LodOptions lod_options(const py::kwargs& kwargs, const char* function);

/// Every field of \p options by its keyword.
py::dict options_dict(const OpenMeshSkinned::LodOptions& options);

/// One line per keyword: its type, its default and what it does, for the docstrings.
std::string options_doc();

}  // namespace omsk_python
