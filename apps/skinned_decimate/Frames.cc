#include "Frames.hh"

#include <OpenMeshSkinned/Deform/ExampleFrames.hh>
#include <OpenMeshSkinned/Deform/KeyframeGA.hh>
#include <OpenMeshSkinned/Deform/NearRigidSegmentation.hh>
#include <OpenMeshSkinned/Deform/PoseSelection.hh>
#include <OpenMeshSkinned/IO/ExportGltf.hh>
#include <OpenMeshSkinned/IO/IOError.hh>
#include <OpenMeshSkinned/IO/ImportFrames.hh>
#include <OpenMeshSkinned/Skin/FrameAnimation.hh>
#include <OpenMeshSkinned/Skin/LinearBlendSkinning.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>

namespace skinned_decimate {

namespace {

namespace fs = std::filesystem;
using namespace OpenMeshSkinned;

// At most this many frames (evenly thinned) feed the segmentation, which keeps a deformation gradient per
// face and frame (72 bytes each).
constexpr size_t kMaxSegmentFrames = 32;

}  // namespace

std::string segmentation_json_path(const std::string& glb) {
  const fs::path p(glb);
  return (p.parent_path() / (p.stem().string() + ".json")).string();
}

void write_segmentation(const Mesh& mesh, const std::string& out, OutputSet& outputs) {
  std::vector<FramePoints> frames;
  if (const size_t stored = frame_times(mesh).size(); stored > 0) {
    const size_t n = std::min(kMaxSegmentFrames, stored);
    for (size_t i = 0; i < n; ++i) frames.push_back(frame_positions(mesh, i * stored / n));
  } else if (!clips(mesh).empty()) {
    std::vector<PoseTime> times = candidate_frames(mesh, {});
    const size_t n = std::min(kMaxSegmentFrames, times.size());
    for (size_t i = 0; i < n; ++i) {
      const PoseTime& t = times[i * times.size() / n];
      frames.push_back(skin_positions(mesh, sample_pose(skeleton(mesh), clips(mesh)[t.clip], t.time)));
    }
  } else {
    throw UsageError("--segment: the input has no animation; near-rigid parts are found from how it moves");
  }
  const Segmentation seg = segment_near_rigid(mesh, rest_points(mesh), frames);

  Mesh coloured = mesh;
  auto& mats = materials(coloured);
  mats.clear();
  for (int p = 0; p < seg.parts; ++p) {
    Material m;
    m.name = "part" + std::to_string(p);
    // Hues spread by the golden angle, so that neighbouring labels differ.
    const double h = std::fmod(p * 0.618033988749895, 1.0) * 6.0;
    const double x = 1.0 - std::abs(std::fmod(h, 2.0) - 1.0);
    const double rgb[6][3] = {{1, x, 0}, {x, 1, 0}, {0, 1, x}, {0, x, 1}, {x, 0, 1}, {1, 0, x}};
    for (int c = 0; c < 3; ++c) m.base_color[c] = 0.15 + 0.8 * rgb[int(h) % 6][c];
    mats.push_back(m);
  }
  const auto hm = face_material_handle(coloured);
  for (auto fh : coloured.faces()) coloured.property(hm, fh) = seg.part[fh.idx()];
  export_gltf(coloured, outputs.staging(out));

  nlohmann::ordered_json j = {{"parts", seg.parts},
                              {"frames_analysed", frames.size()},
                              {"feature_faces", seg.feature_faces},
                              {"face_order", "the triangles as the tool read them (by mesh, then as stored)"},
                              {"face_part", seg.part},
                              {"method",
                               "Lee et al., near-rigid segmentation: eq. 4-6, feature faces 3.2, "
                               "clustering 3.3 with eq. 7 over sampled faces, min-cut boundary smoothing 3.4"}};
  std::ofstream f(outputs.staging(segmentation_json_path(out)), std::ios::binary);
  f << j.dump(1) << "\n";
  f.close();
  if (!f) throw IOError(segmentation_json_path(out) + ": cannot be written");
  std::cout << "segmented into " << seg.parts << " near-rigid parts over " << frames.size() << " frames ("
            << seg.feature_faces.size() << " feature faces)\n";
}

}  // namespace skinned_decimate
