// The batch runner (Lod/Batch.hh) for oms.batch(): the assets of a list of files or a folder, run here N at
// a time, or one at a time as the tasks a scheduler (Dask) spreads over machines, and the summary.
#include "binding.hh"
#include "options.hh"

#include <OpenMeshSkinned/IO/IOError.hh>
#include <OpenMeshSkinned/Lod/Batch.hh>
#include <OpenMeshSkinned/Lod/CheckLodOptions.hh>

#include <pybind11/stl.h>

namespace omsk_python {

namespace {

using namespace OpenMeshSkinned;

// The batch's settings, as the Python layer passes them (a dict: it travels to Dask workers as it is).
BatchOptions batch_options(const py::dict& d) {
  BatchOptions o;
  o.executable = d["executable"].cast<std::string>();
  o.out_dir = d["out_dir"].cast<std::string>();
  o.jobs = d["jobs"].cast<int>();
  o.arguments = d["arguments"].cast<std::vector<std::string>>();
  o.html = d["html"].cast<bool>();
  o.force = d["force"].cast<bool>();
  o.asset_time_limit = d["asset_time_limit"].cast<double>();
  return o;
}

std::vector<BatchInput> inputs_of(const std::vector<std::pair<std::string, std::string>>& pairs) {
  std::vector<BatchInput> inputs;
  for (const auto& [path, name] : pairs) inputs.push_back({path, name});
  return inputs;
}

std::vector<std::pair<std::string, std::string>> pairs_of(const std::vector<BatchInput>& inputs) {
  std::vector<std::pair<std::string, std::string>> pairs;
  for (const BatchInput& in : inputs) pairs.emplace_back(in.path, in.name);
  return pairs;
}

template <typename F>
auto file_errors(F&& f) -> decltype(f()) {
  try {
    py::gil_scoped_release nogil;
    return f();
  } catch (const IOError& e) {
    raise(exceptions().file, e.what());
  }
}

std::vector<std::string> run_batch_py(const std::vector<std::pair<std::string, std::string>>& pairs,
                                      const py::dict& settings, const py::object& progress) {
  const BatchOptions o = batch_options(settings);
  const std::vector<BatchInput> inputs = inputs_of(pairs);
  bool stopped = false;
  const auto results = file_errors([&] {
    return run_batch(inputs, o, [&](const BatchProgress& p) {
      if (progress.is_none() || stopped) return !stopped;
      py::gil_scoped_acquire gil;
      PyObject* r = PyObject_CallFunction(progress.ptr(), "nns", py::ssize_t(p.done), py::ssize_t(p.total),
                                          asset_result_json(*p.last).c_str());
      // An exception stays set on this thread for the caller to raise once the batch has stopped.
      const int go = !r ? 0 : r == Py_None ? 1 : PyObject_IsTrue(r);
      Py_XDECREF(r);
      stopped = go != 1;
      return !stopped;
    });
  });
  if (PyErr_Occurred()) throw py::error_already_set();
  std::vector<std::string> out;
  for (const AssetResult& r : results) out.push_back(asset_result_json(r));
  return out;
}

}  // namespace

void add_batch(py::module_& m) {
  m.def(
      "_batch_inputs",
      [](const std::vector<std::string>& paths) { return pairs_of(file_errors([&] { return batch_inputs(paths); })); },
      py::arg("paths"));
  m.def(
      "_find_inputs",
      [](const std::string& dir, const std::string& out_dir, bool sequences) {
        return pairs_of(file_errors([&] { return find_inputs(dir, out_dir, sequences); }));
      },
      py::arg("dir"), py::arg("out_dir"), py::arg("sequences"));
  m.def("_run_batch", &run_batch_py, py::arg("inputs"), py::arg("settings"), py::arg("progress"));
  m.def(
      "_run_asset",
      [](const std::string& path, const std::string& name, const py::dict& settings) {
        const BatchOptions o = batch_options(settings);
        return file_errors([&] { return asset_result_json(run_asset({path, name}, o)); });
      },
      py::arg("path"), py::arg("name"), py::arg("settings"));
  m.def(
      "_write_summary",
      [](const std::vector<std::string>& results, const py::dict& settings) {
        const BatchOptions o = batch_options(settings);
        file_errors([&] {
          std::vector<AssetResult> parsed;
          for (const std::string& r : results) parsed.push_back(parse_asset_result(r));
          write_summary(parsed, o);
        });
      },
      py::arg("results"), py::arg("settings"));
  m.def("_batch_tool_version", &batch_tool_version);
  m.def(
      "_tool_arguments",
      [](const py::kwargs& kwargs) {
        const LodOptions o = lod_options(kwargs, "batch");
        check_lod_options(o);
        return tool_arguments(o);
      },
      "make_lods() keywords as the tool's command-line options (checked first).");
}

}  // namespace omsk_python
