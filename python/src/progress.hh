#pragma once
// The library's progress callback, answered by a Python callable with the GIL taken back for the call.

#include <pybind11/pybind11.h>

namespace omsk_python {

namespace py = pybind11;

/** Calls \p fn(stage, fraction) (when it is not None) and checks for Ctrl-C, holding the GIL only for that.
 *  Returns false to stop the library: \p fn returned something false other than None, or it raised (or
 *  Ctrl-C came), in which case the Python error is kept for rethrow_if_raised(). Called by the library on
 *  the thread that released the GIL, so the error indicator it leaves is that thread's. */
class PythonProgress {
public:
  explicit PythonProgress(py::handle fn) : fn_(fn) {}

  bool operator()(const char* stage, double fraction) {
    if (stopped_) return false;  // asked again before the library gets to stop: the same answer, no call
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) return stop();
    if (fn_.is_none()) return true;
    PyObject* r = PyObject_CallFunction(fn_.ptr(), "sd", stage, fraction);
    if (!r) return stop();
    const int go = r == Py_None ? 1 : PyObject_IsTrue(r);
    Py_DECREF(r);
    if (go < 0) return stop();
    stopped_ = go == 0;
    return !stopped_;
  }

  /// With the GIL held: raises what the callable raised, if it did.
  void rethrow_if_raised() const {
    if (raised_) throw py::error_already_set();
  }

private:
  bool stop() {
    raised_ = stopped_ = true;  // the error stays set on this thread until rethrow_if_raised() fetches it
    return false;
  }
  py::handle fn_;
  bool raised_ = false, stopped_ = false;
};

}  // namespace omsk_python
