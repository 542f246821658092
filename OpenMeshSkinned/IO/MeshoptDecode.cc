#include "OpenMeshSkinned/IO/MeshoptDecode.hh"

#include "OpenMeshSkinned/IO/GltfJson.hh"
#include "OpenMeshSkinned/IO/IOError.hh"

#include <meshoptimizer.h>

#include <limits>
#include <vector>

namespace OpenMeshSkinned::detail {

using json = nlohmann::json;

const char* const kMeshoptExtensions[2] = {"EXT_meshopt_compression", "KHR_meshopt_compression"};

namespace {

// The stream of \p src decoded into \p dst (\p count elements of \p stride bytes) as \p mode says.
void decode_stream(const std::string& src, const std::string& mode, size_t count, size_t stride, char* dst,
                   const std::string& what) {
  const auto* in = reinterpret_cast<const unsigned char*>(src.data());
  int rc = 0;
  if (mode == "ATTRIBUTES") {
    if (stride % 4) throw IOError(what + ": a vertex stride of " + std::to_string(stride) + " is not a multiple of 4");
    // meshoptimizer 0.18 knows version 0 only; gltfpack writes version 1 for -cz and -ce khr.
    if (!src.empty() && (in[0] & 0xf0) == 0xa0 && (in[0] & 0x0f) != 0)
      throw IOError(what + " uses meshopt vertex codec version " + std::to_string(in[0] & 0x0f) +
                    ", which Debian's meshoptimizer " + std::to_string(MESHOPTIMIZER_VERSION / 1000) + "." +
                    std::to_string(MESHOPTIMIZER_VERSION % 1000 / 10) +
                    " cannot decode (gltfpack -cz or -ce khr writes it; -c and -cc do not)");
    rc = meshopt_decodeVertexBuffer(dst, count, stride, in, src.size());
  } else if (mode == "TRIANGLES" || mode == "INDICES") {
    if (stride != 2 && stride != 4) throw IOError(what + ": an index stride of " + std::to_string(stride));
    if (mode == "TRIANGLES" && count % 3) throw IOError(what + ": " + std::to_string(count) + " triangle indices");
    rc = mode == "TRIANGLES" ? meshopt_decodeIndexBuffer(dst, count, stride, in, src.size())
                             : meshopt_decodeIndexSequence(dst, count, stride, in, src.size());
  } else {
    throw IOError(what + " has the unknown mode \"" + mode + "\"");
  }
  if (rc != 0)
    throw IOError(what + " cannot be decoded (meshoptimizer " + std::to_string(rc) +
                  (rc == -1 ? ": an unknown codec version)" : ": the data is corrupt)"));
}

void apply_filter(const std::string& filter, size_t count, size_t stride, char* dst, const std::string& what) {
  if (filter == "OCTAHEDRAL") {
    if (stride != 4 && stride != 8) throw IOError(what + ": the octahedral filter needs a stride of 4 or 8");
    meshopt_decodeFilterOct(dst, count, stride);
  } else if (filter == "QUATERNION") {
    if (stride != 8) throw IOError(what + ": the quaternion filter needs a stride of 8");
    meshopt_decodeFilterQuat(dst, count, stride);
  } else if (filter == "EXPONENTIAL") {
    meshopt_decodeFilterExp(dst, count, stride);  // stride is a multiple of 4 (checked in decode_stream)
  } else if (filter != "NONE") {
    throw IOError(what + " uses the filter " + filter + ", which Debian's meshoptimizer cannot decode");
  }
}

// Decodes one compressed buffer view in place (it then points at the decoded bytes).
void decode_meshopt_view(json& doc, size_t v, const char* ext, GltfBytes& bytes, const std::string& shown_as) {
  const json e = doc["bufferViews"][v]["extensions"][ext];  // a copy: adding views moves the array
  const std::string what = shown_as + ": buffer view " + std::to_string(v) + " (" + ext + ")";
  if (!e.is_object()) throw IOError(what + " is not an object");
  const size_t buffer = index_in(e, "buffer", doc["buffers"].size(), what);
  const size_t offset = e.value("byteOffset", size_t(0)), length = e.value("byteLength", size_t(0));
  const size_t stride = e.value("byteStride", size_t(0)), count = e.value("count", size_t(0));
  const std::string mode = e.value("mode", ""), filter = e.value("filter", "NONE");
  const std::string src = bytes.range(buffer, offset, length, what);

  if (stride == 0 || count == 0 || stride > 256) throw IOError(what + " has a byteStride of " + std::to_string(stride));
  if (count > std::numeric_limits<size_t>::max() / stride)
    throw IOError(what + " claims " + std::to_string(count) + " elements, more than any buffer holds");
  // The extension makes the view's byteLength the decoded size: anything else is a broken file.
  if (doc["bufferViews"][v].value("byteLength", size_t(0)) != count * stride)
    throw IOError(what + " decodes to " + std::to_string(count) + " x " + std::to_string(stride) +
                  " bytes, not the view's byteLength");
  std::string out(count * stride, '\0');
  decode_stream(src, mode, count, stride, out.data(), what);
  apply_filter(filter, count, stride, out.data(), what);

  const size_t view_stride = doc["bufferViews"][v].value("byteStride", size_t(0));
  const size_t decoded = bytes.add_view(out, view_stride);
  const json placed = doc["bufferViews"][decoded];
  doc["bufferViews"].erase(decoded);
  json& view = doc["bufferViews"][v];
  view["buffer"] = placed["buffer"];
  view["byteOffset"] = placed["byteOffset"];
  view["byteLength"] = out.size();
  erase_extension(view, ext);
}

}  // namespace

bool decode_meshopt(json& doc, GltfBytes& bytes, const std::string& shown_as) {
  if (!doc.contains("bufferViews") || !doc["bufferViews"].is_array()) return false;
  bool any = false;
  for (size_t v = 0; v < doc["bufferViews"].size(); ++v)
    for (const char* ext : kMeshoptExtensions) {
      const json& view = doc["bufferViews"][v];
      if (view.is_object() && view.contains("extensions") && view["extensions"].contains(ext)) {
        decode_meshopt_view(doc, v, ext, bytes, shown_as);
        any = true;
      }
    }
  return any;
}

void drop_fallback_buffers(json& doc) {
  json& buffers = doc["buffers"];
  std::vector<bool> used(buffers.size(), false);
  for (const auto& v : doc["bufferViews"])
    if (v.contains("buffer") && v["buffer"].is_number_unsigned() && v["buffer"].get<size_t>() < used.size())
      used[v["buffer"].get<size_t>()] = true;
  std::vector<size_t> renumber(buffers.size());
  json kept = json::array();
  for (size_t b = 0; b < buffers.size(); ++b) {
    bool fallback = false;
    for (const char* ext : kMeshoptExtensions)
      if (buffers[b].contains("extensions") && buffers[b]["extensions"].contains(ext)) {
        fallback = true;
        erase_extension(buffers[b], ext);
      }
    renumber[b] = kept.size();
    if (!fallback || used[b]) kept.push_back(buffers[b]);
  }
  for (auto& v : doc["bufferViews"])
    if (v.contains("buffer") && v["buffer"].is_number_unsigned() && v["buffer"].get<size_t>() < renumber.size())
      v["buffer"] = renumber[v["buffer"].get<size_t>()];
  buffers = kept;
}

}  // namespace OpenMeshSkinned::detail
