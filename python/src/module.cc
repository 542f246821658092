// openmeshskinned._core: the package's exceptions, the translation of the library's into them, and the parts.
#include "binding.hh"

#include <OpenMeshSkinned/IO/IOError.hh>
#include <OpenMeshSkinned/IO/PrintableText.hh>
#include <OpenMeshSkinned/Lod/LodOptions.hh>
#include <OpenMeshSkinned/Lod/LodProgress.hh>

#include <Python.h>

namespace omsk_python {

namespace {

Exceptions the_exceptions;

// A new exception class openmeshskinned.NAME with \p bases (a second base makes it catchable as the builtin
// a Python user expects: ValueError for a bad request, OSError for a file).
py::handle new_exception(py::module_& m, const char* name, const char* doc, py::tuple bases) {
  const std::string qualified = std::string("openmeshskinned.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
  if (!type) throw py::error_already_set();
  py::object t = py::reinterpret_steal<py::object>(type);
  m.attr(name) = t;
  return t.release();
}

void add_exceptions(py::module_& m) {
  Exceptions& e = the_exceptions;
  const auto builtin = [](PyObject* t) { return py::reinterpret_borrow<py::object>(t); };
  e.error =
      new_exception(m, "Error", "Base of every error this package raises.", py::make_tuple(builtin(PyExc_Exception)));
  e.options = new_exception(m, "OptionsError",
                            "A request make_lods() cannot carry out (a value out of range, a combination that cannot "
                            "hold); the message is the command line's.",
                            py::make_tuple(e.error, builtin(PyExc_ValueError)));
  e.file = new_exception(m, "FileError",
                         "A file that cannot be used, or data in it that cannot be: \"<file>: <problem>\", one line.",
                         py::make_tuple(e.error, builtin(PyExc_OSError)));
  e.read = new_exception(m, "ReadError",
                         "load() could not read the file (missing, empty, corrupt, unusable skin, the reader crashed "
                         "or went over its memory or time limit).",
                         py::make_tuple(e.file));
  e.write = new_exception(m, "WriteError",
                          "save() wrote nothing: a bad extension, an output that is an input or a clash, a folder "
                          "that is missing or not writable.",
                          py::make_tuple(e.file));
  e.cancelled = new_exception(m, "Cancelled", "The progress callable returned False.", py::make_tuple(e.error));
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const OpenMeshSkinned::LodOptionsError& x) {
      PyErr_SetString(the_exceptions.options.ptr(), OpenMeshSkinned::printable_line(x.what(), 1000).c_str());
    } catch (const OpenMeshSkinned::LodCancelled& x) {
      PyErr_SetString(the_exceptions.cancelled.ptr(), x.what());
    } catch (const OpenMeshSkinned::IOError& x) {
      PyErr_SetString(the_exceptions.file.ptr(), OpenMeshSkinned::printable_line(x.what(), 1000).c_str());
    }
  });
}

}  // namespace

const Exceptions& exceptions() { return the_exceptions; }

void raise(py::handle type, const char* what) {
  PyErr_SetString(type.ptr(), OpenMeshSkinned::printable_line(what, 1000).c_str());
  throw py::error_already_set();
}

}  // namespace omsk_python

PYBIND11_MODULE(_core, m) {
  m.doc() = "The C++ core of openmeshskinned (import openmeshskinned, not this).";
  omsk_python::add_exceptions(m);
  omsk_python::add_mesh(m);
  omsk_python::add_lods(m);
  omsk_python::add_evaluate(m);
  omsk_python::add_batch(m);
}
