#include "OpenMeshSkinned/IO/GltfDecompress.hh"

#include "OpenMeshSkinned/IO/GlbFile.hh"
#include "OpenMeshSkinned/IO/IOError.hh"

#include <draco/compression/decode.h>
#include <meshoptimizer.h>
#include <cereal/external/base64.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <set>

namespace OpenMeshSkinned::detail {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125,
              kFloat = 5126;
const char* const kMeshopt[] = {"EXT_meshopt_compression", "KHR_meshopt_compression"};
const char* const kDraco = "KHR_draco_mesh_compression";
const char* const kQuantization = "KHR_mesh_quantization";

// Required extensions the tool honours: the ones decoded here, and the ones that only change how a
// texture is stored or shaded (kept with the materials, or ignored by the geometry).
bool honoured(const std::string& ext) {
  static const std::set<std::string> known = {kMeshopt[0],
                                              kMeshopt[1],
                                              kDraco,
                                              kQuantization,
                                              "KHR_texture_basisu",
                                              "EXT_texture_webp",
                                              "KHR_texture_transform"};
  return known.count(ext) || ext.rfind("KHR_materials_", 0) == 0;
}

size_t component_size(int type) {
  switch (type) {
    case kByte:
    case kUnsignedByte:
      return 1;
    case kShort:
    case kUnsignedShort:
      return 2;
    case kUnsignedInt:
    case kFloat:
      return 4;
    default:
      return 0;
  }
}

size_t component_count(const std::string& type) {
  static const std::map<std::string, size_t> n = {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4},
                                                  {"MAT2", 4},   {"MAT3", 9}, {"MAT4", 16}};
  const auto it = n.find(type);
  return it == n.end() ? 0 : it->second;
}

// One component as the spec reads it: normalised integers map to [0, 1] or [-1, 1].
double read_component(const char* p, int type, bool normalized) {
  auto get = [p](auto v) {
    std::memcpy(&v, p, sizeof v);
    return v;
  };
  switch (type) {
    case kByte: {
      const double v = get(int8_t());
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case kUnsignedByte: {
      const double v = get(uint8_t());
      return normalized ? v / 255.0 : v;
    }
    case kShort: {
      const double v = get(int16_t());
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case kUnsignedShort: {
      const double v = get(uint16_t());
      return normalized ? v / 65535.0 : v;
    }
    case kUnsignedInt: {
      const double v = get(uint32_t());
      return normalized ? v / 4294967295.0 : v;
    }
    default:
      return get(float());
  }
}

void erase_extension(json& object, const std::string& name) {
  if (!object.contains("extensions") || !object["extensions"].is_object()) return;
  object["extensions"].erase(name);
  if (object["extensions"].empty()) object.erase("extensions");
}

void undeclare(json& doc, const std::string& name) {
  for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
    if (!doc.contains(list) || !doc[list].is_array()) continue;
    auto& a = doc[list];
    a.erase(std::remove(a.begin(), a.end(), json(name)), a.end());
    if (a.empty()) doc.erase(list);
  }
}

bool declared(const json& doc, const std::string& name) {
  for (const char* list : {"extensionsUsed", "extensionsRequired"})
    if (doc.contains(list) && doc[list].is_array())
      for (const auto& e : doc[list])
        if (e == name) return true;
  return false;
}

json& array_of(json& doc, const char* name) {
  if (!doc.contains(name) || !doc[name].is_array()) doc[name] = json::array();
  return doc[name];
}

size_t index_in(const json& object, const char* key, size_t size, const std::string& what) {
  if (!object.contains(key) || !object[key].is_number_unsigned() || object[key].get<size_t>() >= size)
    throw IOError(what + " has no valid \"" + key + "\"");
  return object[key].get<size_t>();
}

// --- EXT_meshopt_compression / KHR_meshopt_compression ------------------------------------------------

// Whether \p count elements of \p elem bytes, \p step apart from byte \p start, lie within \p size bytes;
// in elements, so that no product of numbers from the file can overflow.
bool fits(size_t start, size_t count, size_t step, size_t elem, size_t size) {
  if (count == 0) return start <= size;
  if (start > size || elem > size - start) return false;
  return step == 0 || (count - 1) <= (size - start - elem) / step;
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
  auto* dst = out.data();
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
  if (filter == "OCTAHEDRAL") {
    if (stride != 4 && stride != 8) throw IOError(what + ": the octahedral filter needs a stride of 4 or 8");
    meshopt_decodeFilterOct(dst, count, stride);
  } else if (filter == "QUATERNION") {
    if (stride != 8) throw IOError(what + ": the quaternion filter needs a stride of 8");
    meshopt_decodeFilterQuat(dst, count, stride);
  } else if (filter == "EXPONENTIAL") {
    meshopt_decodeFilterExp(dst, count, stride);  // stride is a multiple of 4 (checked above)
  } else if (filter != "NONE") {
    throw IOError(what + " uses the filter " + filter + ", which Debian's meshoptimizer cannot decode");
  }

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

// Buffers that only stand in for compressed data (no bytes of their own) go once nothing refers to them.
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
    for (const char* ext : kMeshopt)
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

bool decode_meshopt(json& doc, GltfBytes& bytes, const std::string& shown_as) {
  if (!doc.contains("bufferViews") || !doc["bufferViews"].is_array()) return false;
  bool any = false;
  for (size_t v = 0; v < doc["bufferViews"].size(); ++v)
    for (const char* ext : kMeshopt) {
      const json& view = doc["bufferViews"][v];
      if (view.is_object() && view.contains("extensions") && view["extensions"].contains(ext)) {
        decode_meshopt_view(doc, v, ext, bytes, shown_as);
        any = true;
      }
    }
  return any;
}

std::vector<double> accessor_values(json& doc, size_t a, GltfBytes& bytes, const std::string& shown_as,
                                    bool as_stored = false);

// --- KHR_draco_mesh_compression ----------------------------------------------------------------------

// Writes one Draco attribute as the accessor declares it (the spec keeps the accessor's type).
template <typename T>
std::string draco_values(const draco::PointAttribute& attr, size_t points, size_t n) {
  std::string out(points * n * sizeof(T), '\0');
  std::vector<T> value(n);
  for (size_t p = 0; p < points; ++p) {
    if (!attr.ConvertValue<T>(attr.mapped_index(draco::PointIndex(uint32_t(p))), int8_t(n), value.data())) return {};
    std::memcpy(out.data() + p * n * sizeof(T), value.data(), n * sizeof(T));
  }
  return out;
}

// The accessor a primitive's decoded data goes to: its own, or a copy when another Draco primitive filled it.
size_t own_accessor(json& doc, json& ref, std::set<size_t>& filled) {
  size_t a = ref.get<size_t>();
  if (filled.count(a)) {
    doc["accessors"].push_back(doc["accessors"][a]);
    a = doc["accessors"].size() - 1;
    ref = a;
  }
  filled.insert(a);
  return a;
}

void point_accessor_at(json& accessor, size_t view, int component_type, size_t count) {
  accessor["bufferView"] = view;
  accessor.erase("byteOffset");
  accessor.erase("sparse");
  accessor["componentType"] = component_type;
  accessor["count"] = count;
}

bool decode_draco(json& doc, GltfBytes& bytes, const std::string& shown_as) {
  if (!doc.contains("meshes") || !doc["meshes"].is_array()) return false;
  bool any = false;
  std::set<size_t> filled;
  for (size_t m = 0; m < doc["meshes"].size(); ++m) {
    json& mesh = doc["meshes"][m];
    if (!mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (size_t p = 0; p < mesh["primitives"].size(); ++p) {
      json& prim = mesh["primitives"][p];
      if (!prim.contains("extensions") || !prim["extensions"].contains(kDraco)) continue;
      const std::string what = shown_as + ": primitive " + std::to_string(p) + " of mesh " + std::to_string(m);
      const json& e = prim["extensions"][kDraco];
      if (prim.value("mode", 4) != 4) throw IOError(what + " is Draco-compressed and not made of triangles");
      const size_t n_views = doc.contains("bufferViews") ? doc["bufferViews"].size() : 0;
      const std::string src = bytes.view_bytes(index_in(e, "bufferView", n_views, what + " (Draco)"));
      draco::DecoderBuffer buffer;
      buffer.Init(src.data(), src.size());
      draco::Decoder decoder;
      auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
      if (!decoded.ok()) throw IOError(what + ": its Draco data cannot be decoded: " + decoded.status().error_msg());
      const std::unique_ptr<draco::Mesh> dm = std::move(decoded).value();
      const size_t points = dm->num_points();
      json& accessors = array_of(doc, "accessors");
      if (!prim.contains("indices")) {  // the decoded mesh is indexed whatever the primitive said
        accessors.push_back({{"componentType", kUnsignedInt}, {"type", "SCALAR"}, {"count", 0}});
        prim["indices"] = accessors.size() - 1;
      }
      {
        std::string idx(dm->num_faces() * 3 * sizeof(uint32_t), '\0');
        for (draco::FaceIndex f(0); f < dm->num_faces(); ++f)
          for (int c = 0; c < 3; ++c) {
            const uint32_t i = dm->face(f)[c].value();
            std::memcpy(idx.data() + (size_t(f.value()) * 3 + c) * sizeof(uint32_t), &i, sizeof i);
          }
        if (!prim["indices"].is_number_unsigned() || prim["indices"].get<size_t>() >= accessors.size())
          throw IOError(what + " has no valid \"indices\"");
        const size_t a = own_accessor(doc, prim["indices"], filled);
        point_accessor_at(doc["accessors"][a], bytes.add_view(idx), kUnsignedInt, dm->num_faces() * 3);
        doc["accessors"][a].erase("min");
        doc["accessors"][a].erase("max");
      }
      if (!e.contains("attributes") || !e["attributes"].is_object())
        throw IOError(what + ": its Draco extension lists no attributes");
      for (const auto& [name, id] : e["attributes"].items()) {
        if (!prim.contains("attributes") || !prim["attributes"].contains(name) ||
            !prim["attributes"][name].is_number_unsigned() ||
            prim["attributes"][name].get<size_t>() >= doc["accessors"].size())
          throw IOError(what + ": Draco attribute " + name + " has no accessor");
        const draco::PointAttribute* attr =
            id.is_number_unsigned() ? dm->GetAttributeByUniqueId(id.get<uint32_t>()) : nullptr;
        if (!attr) throw IOError(what + ": its Draco data has no attribute " + id.dump() + " (" + name + ")");
        const size_t a = own_accessor(doc, prim["attributes"][name], filled);
        json& acc = doc["accessors"][a];
        const size_t n = component_count(acc.value("type", ""));
        const int type = acc.value("componentType", 0);
        std::string values;
        switch (type) {
          case kByte:
            values = draco_values<int8_t>(*attr, points, n);
            break;
          case kUnsignedByte:
            values = draco_values<uint8_t>(*attr, points, n);
            break;
          case kShort:
            values = draco_values<int16_t>(*attr, points, n);
            break;
          case kUnsignedShort:
            values = draco_values<uint16_t>(*attr, points, n);
            break;
          case kUnsignedInt:
            values = draco_values<uint32_t>(*attr, points, n);
            break;
          case kFloat:
            values = draco_values<float>(*attr, points, n);
            break;
          default:
            break;
        }
        if (n == 0 || (values.empty() && points > 0))
          throw IOError(what + ": Draco attribute " + name + " cannot be read as its accessor's type");
        point_accessor_at(acc, bytes.add_view(values), type, points);
        // Draco quantises: the declared bounds are the original's, the decoded values lie a step inside.
        if (acc.contains("min") || acc.contains("max")) {
          const std::vector<double> v = accessor_values(doc, a, bytes, shown_as, true);
          json lo = json::array(), hi = json::array();
          for (size_t c = 0; c < n; ++c) {
            double l = std::numeric_limits<double>::infinity(), h = -l;
            for (size_t i = c; i < v.size(); i += n) l = std::min(l, v[i]), h = std::max(h, v[i]);
            lo.push_back(l), hi.push_back(h);
          }
          json& bounded = doc["accessors"][a];
          if (v.empty()) {
            bounded.erase("min"), bounded.erase("max");
          } else {
            bounded["min"] = lo, bounded["max"] = hi;
          }
        }
      }
      erase_extension(prim, kDraco);
      any = true;
    }
  }
  return any;
}

// --- KHR_mesh_quantization and integer animation outputs -----------------------------------------------

// Every value of an accessor as the spec gives it (or, \p as_stored, as integers before normalisation),
// sparse substitutions included.
std::vector<double> accessor_values(json& doc, size_t a, GltfBytes& bytes, const std::string& shown_as,
                                    bool as_stored) {
  const json& acc = doc["accessors"][a];
  const std::string what = shown_as + ": accessor " + std::to_string(a);
  const size_t n = component_count(acc.value("type", "")), count = acc.value("count", size_t(0));
  const int type = acc.value("componentType", 0);
  const size_t cs = component_size(type);
  if (n == 0 || cs == 0) throw IOError(what + " has an unknown type");
  const bool normalized = !as_stored && acc.value("normalized", false);
  if (count > (size_t(1) << 32))
    throw IOError(what + " claims " + std::to_string(count) + " elements, more than any buffer holds");
  std::vector<double> out(count * n, 0.0);
  if (acc.contains("bufferView")) {
    const size_t view = index_in(acc, "bufferView", doc["bufferViews"].size(), what);
    const std::string data = bytes.view_bytes(view);
    const size_t stride = doc["bufferViews"][view].value("byteStride", size_t(0));
    const size_t step = stride ? stride : n * cs, start = acc.value("byteOffset", size_t(0));
    if (!fits(start, count, step, n * cs, data.size())) throw IOError(what + " runs past its buffer view");
    for (size_t i = 0; i < count; ++i)
      for (size_t c = 0; c < n; ++c)
        out[i * n + c] = read_component(data.data() + start + i * step + c * cs, type, normalized);
  }
  if (acc.contains("sparse")) {
    const json& sp = acc["sparse"];
    const size_t k = sp.value("count", size_t(0));
    if (!sp.contains("indices") || !sp.contains("values")) throw IOError(what + " has an incomplete sparse part");
    const json &si = sp["indices"], &sv = sp["values"];
    const int itype = si.value("componentType", 0);
    const size_t ics = component_size(itype);
    const std::string idata = bytes.view_bytes(index_in(si, "bufferView", doc["bufferViews"].size(), what));
    const std::string vdata = bytes.view_bytes(index_in(sv, "bufferView", doc["bufferViews"].size(), what));
    const size_t ioff = si.value("byteOffset", size_t(0)), voff = sv.value("byteOffset", size_t(0));
    if (ics == 0 || !fits(ioff, k, ics, ics, idata.size()) || !fits(voff, k, n * cs, n * cs, vdata.size()))
      throw IOError(what + ": its sparse part runs past its buffer views");
    for (size_t j = 0; j < k; ++j) {
      const auto i = size_t(read_component(idata.data() + ioff + j * ics, itype, false));
      if (i >= count) throw IOError(what + ": a sparse index is out of range");
      for (size_t c = 0; c < n; ++c)
        out[i * n + c] = read_component(vdata.data() + voff + (j * n + c) * cs, type, normalized);
    }
  }
  return out;
}

void write_float_accessor(json& doc, size_t a, const std::vector<double>& values, GltfBytes& bytes) {
  json& acc = doc["accessors"][a];
  const size_t n = component_count(acc.value("type", ""));
  std::string data(values.size() * sizeof(float), '\0');
  std::vector<double> lo(n, std::numeric_limits<double>::infinity()), hi(n, -std::numeric_limits<double>::infinity());
  for (size_t i = 0; i < values.size(); ++i) {
    const float f = float(values[i]);
    std::memcpy(data.data() + i * sizeof(float), &f, sizeof f);
    lo[i % n] = std::min(lo[i % n], double(f));
    hi[i % n] = std::max(hi[i % n], double(f));
  }
  point_accessor_at(acc, bytes.add_view(data), kFloat, acc.value("count", size_t(0)));
  acc.erase("normalized");
  if (acc.contains("min") || acc.contains("max")) {
    if (values.empty()) {
      acc.erase("min");
      acc.erase("max");
    } else {
      acc["min"] = lo;
      acc["max"] = hi;
    }
  }
}

// KHR_texture_transform on every texture of a material that reads set \p set, when they all carry the
// same one with neither rotation nor a texCoord override: the affine map gltfpack adds to dequantise.
bool common_uv_transform(json& material, size_t set, double offset[2], double scale[2]) {
  std::vector<json*> infos;
  std::function<void(json&, const std::string&)> walk = [&](json& j, const std::string& key) {
    if (j.is_object()) {
      if (key.size() >= 7 && key.compare(key.size() - 7, 7, "Texture") == 0 && j.contains("index") &&
          j.value("texCoord", size_t(0)) == set)
        infos.push_back(&j);
      for (auto& [k, v] : j.items()) walk(v, k);
    } else if (j.is_array()) {
      for (auto& v : j) walk(v, key);
    }
  };
  walk(material, "");
  if (infos.empty()) return false;
  json first;
  for (json* info : infos) {
    if (!info->contains("extensions") || !(*info)["extensions"].contains("KHR_texture_transform")) return false;
    const json& t = (*info)["extensions"]["KHR_texture_transform"];
    if (t.value("rotation", 0.0) != 0.0 || t.contains("texCoord")) return false;
    if (first.is_null()) first = t;
    if (t != first) return false;
  }
  const json o = first.value("offset", json::array({0.0, 0.0})), s = first.value("scale", json::array({1.0, 1.0}));
  if (!o.is_array() || o.size() != 2 || !s.is_array() || s.size() != 2) return false;
  for (int c = 0; c < 2; ++c) offset[c] = o[c].get<double>(), scale[c] = s[c].get<double>();
  for (json* info : infos) erase_extension(*info, "KHR_texture_transform");
  return true;
}

bool dequantize(json& doc, GltfBytes& bytes, const std::string& shown_as) {
  if (!doc.contains("accessors") || !doc["accessors"].is_array()) return false;
  const size_t n_accessors = doc["accessors"].size();
  std::set<size_t> to_float;
  auto consider = [&](const json& ref) {
    if (ref.is_number_unsigned() && ref.get<size_t>() < n_accessors &&
        doc["accessors"][ref.get<size_t>()].value("componentType", kFloat) != kFloat)
      to_float.insert(ref.get<size_t>());
  };
  // Quantised texture coordinates of each primitive, with its material: their transform is folded below.
  std::vector<std::pair<size_t, std::pair<size_t, size_t>>> quantized_uvs;  // accessor, (material, set)
  const json meshes = doc.value("meshes", json::array()), animations = doc.value("animations", json::array());
  for (const auto& mesh : meshes)
    for (const auto& prim : mesh.value("primitives", json::array())) {
      const json attributes = prim.value("attributes", json::object()), targets = prim.value("targets", json::array());
      for (const auto& [name, ref] : attributes.items()) {
        if (name.rfind("JOINTS_", 0) == 0) continue;  // integers by definition
        consider(ref);
        if (name.rfind("TEXCOORD_", 0) == 0 && to_float.count(ref.get<size_t>()) && prim.contains("material"))
          quantized_uvs.push_back({ref.get<size_t>(), {prim["material"].get<size_t>(), std::stoul(name.substr(9))}});
      }
      for (const auto& target : targets)
        for (const auto& [name, ref] : target.items()) consider(ref);
    }
  for (const auto& anim : animations)
    for (const auto& sampler : anim.value("samplers", json::array()))
      if (sampler.contains("output")) consider(sampler["output"]);
  if (to_float.empty()) return false;
  for (size_t a : to_float) write_float_accessor(doc, a, accessor_values(doc, a, bytes, shown_as), bytes);

  // The accessor meshes refer to is rewritten, so each (material, set) with a transform is folded into the
  // accessor of its primitives once; primitives of two materials sharing coordinates get a copy each.
  std::map<std::pair<size_t, size_t>, std::pair<std::vector<double>, std::vector<double>>> folded;
  std::map<size_t, std::pair<size_t, size_t>> accessor_owner;
  if (quantized_uvs.empty() || !doc.contains("materials") || !doc["materials"].is_array()) return true;
  auto& materials = doc["materials"];
  for (auto& mesh : doc["meshes"])
    for (auto& prim : mesh["primitives"]) {
      if (!prim.contains("material") || !prim["material"].is_number_unsigned()) continue;
      const size_t mat = prim["material"].get<size_t>();
      if (mat >= materials.size()) continue;
      for (auto& [name, ref] : prim["attributes"].items()) {
        if (name.rfind("TEXCOORD_", 0) != 0) continue;
        const size_t set = std::stoul(name.substr(9)), a = ref.get<size_t>();
        if (std::find(quantized_uvs.begin(), quantized_uvs.end(), std::make_pair(a, std::make_pair(mat, set))) ==
            quantized_uvs.end())
          continue;
        const auto key = std::make_pair(mat, set);
        if (!folded.count(key)) {
          double o[2], s[2];
          if (!common_uv_transform(materials[mat], set, o, s)) continue;
          folded[key] = {{o[0], o[1]}, {s[0], s[1]}};
        }
        auto owner = accessor_owner.find(a);
        if (owner != accessor_owner.end() && owner->second == key) continue;  // already folded
        size_t target = a;
        if (owner != accessor_owner.end()) {
          doc["accessors"].push_back(doc["accessors"][a]);
          target = doc["accessors"].size() - 1;
          ref = target;
        }
        std::vector<double> uv = accessor_values(doc, target, bytes, shown_as);
        const auto& [o, s] = folded[key];
        for (size_t i = 0; i < uv.size(); ++i) uv[i] = o[i % 2] + s[i % 2] * uv[i];
        write_float_accessor(doc, target, uv, bytes);
        accessor_owner[target] = key;
      }
    }
  if (!folded.empty() && materials.dump().find("\"KHR_texture_transform\"") == std::string::npos)
    undeclare(doc, "KHR_texture_transform");
  return true;
}

}  // namespace

GltfBytes::GltfBytes(json& doc, std::string* bin, fs::path dir, std::string shown_as)
    : doc_(doc), bin_(bin), dir_(std::move(dir)), shown_as_(std::move(shown_as)) {}

const std::string& GltfBytes::buffer(size_t index) {
  json& buffers = array_of(doc_, "buffers");
  if (index >= buffers.size()) throw IOError(shown_as_ + ": buffer " + std::to_string(index) + " does not exist");
  if (long(index) == target_ && !bin_) return added_;
  const json& b = buffers[index];
  if (!b.contains("uri")) {
    if (index == 0 && bin_) return *bin_;
    throw IOError(shown_as_ + ": buffer " + std::to_string(index) + " has no data (no \"uri\" and no binary chunk)");
  }
  if (loaded_.size() <= index) loaded_.resize(buffers.size()), is_loaded_.resize(buffers.size(), false);
  if (is_loaded_[index]) return loaded_[index];
  const std::string uri = b["uri"].is_string() ? b["uri"].get<std::string>() : "";
  if (uri.rfind("data:", 0) == 0) {
    const size_t comma = uri.find(',');
    if (comma == std::string::npos || uri.rfind(";base64", comma) == std::string::npos)
      throw IOError(shown_as_ + ": buffer " + std::to_string(index) + " has a data URI that is not base64");
    loaded_[index] = cereal::base64::decode(uri.substr(comma + 1));
  } else {
    if (!read_file_bytes(dir_ / percent_decoded(uri), loaded_[index]))
      throw IOError(shown_as_ + ": buffer " + std::to_string(index) + " (\"" + uri + "\") cannot be read");
  }
  is_loaded_[index] = true;
  return loaded_[index];
}

std::string GltfBytes::range(size_t buffer_index, size_t offset, size_t length, const std::string& what) {
  const std::string& data = buffer(buffer_index);
  if (offset > data.size() || length > data.size() - offset) throw IOError(what + " runs past its buffer");
  return data.substr(offset, length);
}

std::string GltfBytes::view_bytes(size_t index) {
  json& views = array_of(doc_, "bufferViews");
  const std::string what = shown_as_ + ": buffer view " + std::to_string(index);
  if (index >= views.size()) throw IOError(what + " does not exist");
  const json& v = views[index];
  return range(index_in(v, "buffer", array_of(doc_, "buffers").size(), what), v.value("byteOffset", size_t(0)),
               v.value("byteLength", size_t(0)), what);
}

size_t GltfBytes::add_view(const std::string& bytes, size_t stride) {
  json& buffers = array_of(doc_, "buffers");
  if (target_ < 0) {
    if (bin_ && !buffers.empty() && !buffers[0].contains("uri")) {
      target_ = 0;
    } else {
      bin_ = nullptr;  // a GLB whose chunk is not buffer 0 gets a file too
      target_ = long(buffers.size());
      buffers.push_back({{"byteLength", 0}, {"uri", added_uri}});
    }
  }
  std::string& out = bin_ ? *bin_ : added_;
  while (out.size() % 4) out += '\0';
  const size_t offset = out.size();
  out += bytes;
  buffers[size_t(target_)]["byteLength"] = out.size();
  json view = {{"buffer", size_t(target_)}, {"byteOffset", offset}, {"byteLength", bytes.size()}};
  if (stride) view["byteStride"] = stride;
  array_of(doc_, "bufferViews").push_back(view);
  return doc_["bufferViews"].size() - 1;
}

void check_required_extensions(const json& doc, const std::string& shown_as) {
  if (!doc.contains("extensionsRequired") || !doc["extensionsRequired"].is_array()) return;
  for (const auto& e : doc["extensionsRequired"]) {
    const std::string name = e.is_string() ? e.get<std::string>() : e.dump();
    if (!honoured(name))
      throw IOError(shown_as + ": requires the glTF extension " + name + ", which this tool cannot read");
  }
}

std::vector<std::string> decompress_gltf(json& doc, GltfBytes& bytes, const std::string& shown_as) {
  std::vector<std::string> done;
  const bool meshopt = decode_meshopt(doc, bytes, shown_as);
  if (meshopt) {
    for (const char* ext : kMeshopt)
      if (declared(doc, ext)) done.push_back(ext), undeclare(doc, ext);
  }
  if (decode_draco(doc, bytes, shown_as)) done.push_back(kDraco);
  undeclare(doc, kDraco);
  if (dequantize(doc, bytes, shown_as) || declared(doc, kQuantization)) {
    if (declared(doc, kQuantization)) done.push_back(kQuantization);
    undeclare(doc, kQuantization);
  }
  // Last: it renumbers the buffers, which \p bytes knows by their numbers until every view is decoded.
  if (meshopt) drop_fallback_buffers(doc);
  return done;
}

}  // namespace OpenMeshSkinned::detail
