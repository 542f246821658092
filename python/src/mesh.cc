// oms.Mesh (its arrays as NumPy copies), oms.load() and oms.save(mesh, path).
#include "binding.hh"

#include <OpenMeshSkinned/IO/ExportGltf.hh>
#include <OpenMeshSkinned/IO/FrameFiles.hh>
#include <OpenMeshSkinned/IO/Import.hh>
#include <OpenMeshSkinned/IO/ImportFrames.hh>
#include <OpenMeshSkinned/IO/OutputSet.hh>
#include <OpenMeshSkinned/IO/PrintableText.hh>
#include <OpenMeshSkinned/Skin/FrameAnimation.hh>
#include <OpenMeshSkinned/Skin/Morph.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <filesystem>

namespace omsk_python {

namespace {

using namespace OpenMeshSkinned;

template <typename T>
py::array_t<T> zeros(std::vector<py::ssize_t> shape) {
  py::array_t<T> a(shape);
  std::fill(a.mutable_data(), a.mutable_data() + a.size(), T(0));
  return a;
}

py::array_t<double> rest_positions(const Mesh& m) {
  const SkinnedMesh& mesh = *m.mesh;
  auto a = zeros<double>({py::ssize_t(mesh.n_vertices()), 3});
  auto w = a.mutable_unchecked<2>();
  for (auto vh : mesh.vertices())
    for (int c = 0; c < 3; ++c) w(vh.idx(), c) = mesh.point(vh)[c];
  return a;
}

py::array_t<int32_t> faces(const Mesh& m) {
  const SkinnedMesh& mesh = *m.mesh;
  auto a = zeros<int32_t>({py::ssize_t(mesh.n_faces()), 3});
  auto w = a.mutable_unchecked<2>();
  py::ssize_t f = 0;
  for (auto fh : mesh.faces()) {
    int c = 0;
    for (auto vh : mesh.fv_range(fh)) w(f, c++) = vh.idx();
    ++f;
  }
  return a;
}

// The widest skin of any vertex: the columns of joint_indices and joint_weights.
int influence_columns(const SkinnedMesh& mesh) {
  const auto h = influences_handle(mesh);
  int k = 0;
  for (auto vh : mesh.vertices()) k = std::max(k, mesh.property(h, vh).size());
  return k;
}

py::array_t<int32_t> joint_indices(const Mesh& m) {
  const SkinnedMesh& mesh = *m.mesh;
  const auto h = influences_handle(mesh);
  const int k = influence_columns(mesh);
  auto a = zeros<int32_t>({py::ssize_t(mesh.n_vertices()), k});
  auto w = a.mutable_unchecked<2>();
  for (auto vh : mesh.vertices()) {
    const Influences& inf = mesh.property(h, vh);
    for (int i = 0; i < k; ++i) w(vh.idx(), i) = i < inf.size() ? inf[i].joint : -1;
  }
  return a;
}

py::array_t<double> joint_weights(const Mesh& m) {
  const SkinnedMesh& mesh = *m.mesh;
  const auto h = influences_handle(mesh);
  const int k = influence_columns(mesh);
  auto a = zeros<double>({py::ssize_t(mesh.n_vertices()), k});
  auto w = a.mutable_unchecked<2>();
  for (auto vh : mesh.vertices()) {
    const Influences& inf = mesh.property(h, vh);
    for (int i = 0; i < inf.size(); ++i) w(vh.idx(), i) = inf[i].weight;
  }
  return a;
}

py::array_t<double> inverse_binds(const Mesh& m) {
  const Skeleton& skel = skeleton(*m.mesh);
  auto a = zeros<double>({py::ssize_t(skel.size()), 4, 4});
  auto w = a.mutable_unchecked<3>();
  for (int j = 0; j < skel.size(); ++j)
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) w(j, r, c) = skel.joints[j].inverse_bind(r, c);
  return a;
}

py::array_t<int32_t> joint_parents(const Mesh& m) {
  const Skeleton& skel = skeleton(*m.mesh);
  auto a = zeros<int32_t>({py::ssize_t(skel.size())});
  for (int j = 0; j < skel.size(); ++j) a.mutable_at(j) = skel.joints[j].parent;
  return a;
}

std::vector<std::string> joint_names(const Mesh& m) {
  std::vector<std::string> names;
  for (const Joint& j : skeleton(*m.mesh).joints) names.push_back(j.name);
  return names;
}

py::array_t<float> morph_deltas(const Mesh& m) {
  const SkinnedMesh& mesh = *m.mesh;
  const size_t t = morph_targets(mesh).size();
  auto a = zeros<float>({py::ssize_t(t), py::ssize_t(mesh.n_vertices()), 3});
  OpenMesh::VPropHandleT<MorphDeltas> h;
  if (t == 0 || !morph_deltas_handle(mesh, h)) return a;
  auto w = a.mutable_unchecked<3>();
  for (auto vh : mesh.vertices()) {
    const MorphDeltas& d = mesh.property(h, vh);
    for (size_t i = 0; i < std::min(t, d.size()); ++i)
      for (int c = 0; c < 3; ++c) w(i, vh.idx(), c) = d[i][c];
  }
  return a;
}

py::array_t<int32_t> face_materials(const Mesh& m) {
  const SkinnedMesh& mesh = *m.mesh;
  const auto h = face_material_handle(mesh);
  auto a = zeros<int32_t>({py::ssize_t(mesh.n_faces())});
  py::ssize_t f = 0;
  for (auto fh : mesh.faces()) a.mutable_at(f++) = mesh.property(h, fh);
  return a;
}

Mesh load(const std::string& path, bool isolate, size_t max_memory_mb, double time_limit, bool sequence, double fps,
          bool verbose) {
  auto mesh = std::make_shared<SkinnedMesh>();
  ImportReport rep;
  try {
    py::gil_scoped_release nogil;
    ImportOptions io;
    io.isolate = isolate;
    io.memory_limit_mb = max_memory_mb;
    io.time_limit_seconds = time_limit;
    io.show_reader_output = verbose;
    const std::vector<std::string> frames = frame_files(path, sequence);
    rep = frames.empty() ? import_skinned(path, *mesh, io)
                         : import_frame_animation(frames, *mesh, io, frame_rate(frames, fps));
  } catch (const IOError& e) {
    raise(exceptions().read, e.what());
  }
  Mesh m{mesh, path, {}};
  for (const auto& w : rep.warnings) m.warnings.push_back(printable_text(path + ": " + w));
  return m;
}

void save_mesh(const Mesh& m, const std::string& path) {
  try {
    py::gil_scoped_release nogil;
    const std::string ext = std::filesystem::path(path).extension().string();
    if (ext != ".glb" && ext != ".gltf") throw IOError(path + ": output must end in .glb or .gltf");
    OutputSet outputs(m.path.empty() ? std::vector<std::string>{} : std::vector<std::string>{m.path});
    export_gltf(*m.mesh, outputs.add(path));
    outputs.commit();
  } catch (const IOError& e) {
    raise(exceptions().write, e.what());
  }
}

// Mesh: its arrays and figures, read-only.
void add_mesh_class(py::module_& m) {
  py::class_<Mesh>(m, "Mesh",
                   "A skinned (or frame-animated) triangle mesh: rest positions, faces, skin, skeleton, clips, "
                   "morph targets and materials. Made by load() or make_lods(), never changed afterwards; every "
                   "array attribute is a new NumPy copy (writing to it changes nothing here).")
      .def_property_readonly(
          "n_vertices", [](const Mesh& x) { return x.mesh->n_vertices(); }, "Vertices.")
      .def_property_readonly(
          "n_faces", [](const Mesh& x) { return x.mesh->n_faces(); }, "Triangles.")
      .def_property_readonly(
          "n_joints", [](const Mesh& x) { return skeleton(*x.mesh).size(); }, "Joints.")
      .def_property_readonly(
          "path", [](const Mesh& x) { return x.path; },
          "The file it was read from ('' for a LOD); save() never writes over it.")
      .def_property_readonly(
          "warnings", [](const Mesh& x) { return x.warnings; },
          "What the reader changed or could not use, one line each (list of str), as the "
          "command line prints them: \"<file>: <what>\".")
      .def_property_readonly("rest_positions", &rest_positions,
                             "(N, 3) float64 copy: each vertex's rest position (the bind pose).")
      .def_property_readonly("faces", &faces, "(F, 3) int32 copy: each triangle's vertex indices, counter-clockwise.")
      .def_property_readonly("joint_indices", &joint_indices,
                             "(N, K) int32 copy: each vertex's joints, heaviest first; K is the widest skin of any "
                             "vertex, and the rest of a row is -1.")
      .def_property_readonly("joint_weights", &joint_weights,
                             "(N, K) float64 copy: the weights of joint_indices (0 where the index is -1); each row "
                             "sums to 1.")
      .def_property_readonly("inverse_binds", &inverse_binds,
                             "(J, 4, 4) float64 copy: each joint's inverse bind matrix (rest space to the joint's "
                             "space at bind time).")
      .def_property_readonly("joint_names", &joint_names, "Each joint's name (list of str), parents first.")
      .def_property_readonly("joint_parents", &joint_parents,
                             "(J,) int32 copy: each joint's parent index, -1 for a root; a parent comes before its "
                             "children.")
      .def_property_readonly(
          "clip_names",
          [](const Mesh& x) {
            std::vector<std::string> n;
            for (const Clip& c : clips(*x.mesh)) n.push_back(c.name);
            return n;
          },
          "Each animation clip's name (list of str), in the file's order.")
      .def_property_readonly(
          "clip_durations",
          [](const Mesh& x) {
            std::vector<double> n;
            for (const Clip& c : clips(*x.mesh)) n.push_back(c.duration);
            return n;
          },
          "Each clip's length in seconds (list of float).")
      .def_property_readonly(
          "morph_target_names",
          [](const Mesh& x) {
            std::vector<std::string> n;
            for (const MorphTarget& t : morph_targets(*x.mesh)) n.push_back(t.name);
            return n;
          },
          "Each morph target's (blend shape's) name (list of str); a frame animation's frames are morph targets.")
      .def_property_readonly("morph_deltas", &morph_deltas,
                             "(T, N, 3) float32 copy: each morph target's offset of each vertex's rest position.")
      .def_property_readonly(
          "frame_times", [](const Mesh& x) { return frame_times(*x.mesh); },
          "A frame animation's stored frames' times in seconds (empty for a skinned mesh).")
      .def_property_readonly(
          "material_names",
          [](const Mesh& x) {
            std::vector<std::string> n;
            for (const Material& t : materials(*x.mesh)) n.push_back(t.name);
            return n;
          },
          "Each material's name (list of str).")
      .def_property_readonly("face_materials", &face_materials,
                             "(F,) int32 copy: each triangle's index into material_names, -1 for none.")
      .def("__repr__", [](const Mesh& x) {
        return "<openmeshskinned.Mesh " + (x.path.empty() ? std::string("(LOD)") : x.path) + ": " +
               std::to_string(x.mesh->n_vertices()) + " vertices, " + std::to_string(x.mesh->n_faces()) +
               " triangles, " + std::to_string(skeleton(*x.mesh).size()) + " joints, " +
               std::to_string(clips(*x.mesh).size()) + " clips>";
      });
}

}  // namespace

void add_mesh(py::module_& m) {
  add_mesh_class(m);
  const ImportOptions d;
  m.def("load", &load, py::arg("path"), py::kw_only(), py::arg("isolate") = true,
        py::arg("max_memory_mb") = d.memory_limit_mb, py::arg("time_limit") = d.time_limit_seconds,
        py::arg("sequence") = true, py::arg("fps") = 0.0, py::arg("verbose") = false,
        R"(Reads a skinned asset (glTF/GLB, FBX, Collada, X, MD5, ...) or a mesh animated without a skeleton (an
MD2/MD3/MDL file, or one file of a numbered OBJ/PLY/STL/OFF sequence: every file of it is a frame) into a Mesh.

isolate: read it in a child process under max_memory_mb (0: no limit) and time_limit seconds (0: none), so that a
reader crash on a corrupt file is a ReadError, not the end of this process (as the command line does).
sequence: False reads a numbered file as one mesh. fps: a frame animation's rate (0: 10 for Quake's formats, 24
for sequences). verbose: the isolated reader's own output goes to stderr.
The GIL is released while reading. Raises ReadError with the command line's one-line message.)");
  m.def("_save_mesh", &save_mesh, py::arg("mesh"), py::arg("path"));
}

}  // namespace omsk_python
