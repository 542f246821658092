#include "OpenMeshSkinned/IO/DracoDecode.hh"

#include "OpenMeshSkinned/IO/GltfAccessors.hh"
#include "OpenMeshSkinned/IO/GltfJson.hh"
#include "OpenMeshSkinned/IO/IOError.hh"

#include <draco/compression/decode.h>

#include <cstring>
#include <limits>
#include <memory>
#include <set>

namespace OpenMeshSkinned::detail {

using json = nlohmann::json;

const char* const kDracoExtension = "KHR_draco_mesh_compression";

namespace {

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

// The attribute's values in component type \p type; empty for a type the accessor cannot have.
std::string draco_values_as(const draco::PointAttribute& attr, int type, size_t points, size_t n) {
  switch (type) {
    case kByte:
      return draco_values<int8_t>(attr, points, n);
    case kUnsignedByte:
      return draco_values<uint8_t>(attr, points, n);
    case kShort:
      return draco_values<int16_t>(attr, points, n);
    case kUnsignedShort:
      return draco_values<uint16_t>(attr, points, n);
    case kUnsignedInt:
      return draco_values<uint32_t>(attr, points, n);
    case kFloat:
      return draco_values<float>(attr, points, n);
    default:
      return {};
  }
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

// What one primitive's decoding needs besides its JSON.
struct DracoPrimitive {
  json& doc;
  GltfBytes& bytes;
  std::set<size_t>& filled;  // accessors a Draco primitive has written
  const std::string& shown_as;
  std::string what;  // the primitive, in errors
};

std::unique_ptr<draco::Mesh> decode_draco_mesh(DracoPrimitive& d, const json& e) {
  const size_t n_views = d.doc.contains("bufferViews") ? d.doc["bufferViews"].size() : 0;
  const std::string src = d.bytes.view_bytes(index_in(e, "bufferView", n_views, d.what + " (Draco)"));
  draco::DecoderBuffer buffer;
  buffer.Init(src.data(), src.size());
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) throw IOError(d.what + ": its Draco data cannot be decoded: " + decoded.status().error_msg());
  return std::move(decoded).value();
}

void write_draco_indices(DracoPrimitive& d, json& prim, const draco::Mesh& dm) {
  json& accessors = array_of(d.doc, "accessors");
  if (!prim.contains("indices")) {  // the decoded mesh is indexed whatever the primitive said
    accessors.push_back({{"componentType", kUnsignedInt}, {"type", "SCALAR"}, {"count", 0}});
    prim["indices"] = accessors.size() - 1;
  }
  std::string idx(dm.num_faces() * 3 * sizeof(uint32_t), '\0');
  for (draco::FaceIndex f(0); f < dm.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) {
      const uint32_t i = dm.face(f)[c].value();
      std::memcpy(idx.data() + (size_t(f.value()) * 3 + c) * sizeof(uint32_t), &i, sizeof i);
    }
  if (!prim["indices"].is_number_unsigned() || prim["indices"].get<size_t>() >= accessors.size())
    throw IOError(d.what + " has no valid \"indices\"");
  const size_t a = own_accessor(d.doc, prim["indices"], d.filled);
  point_accessor_at(d.doc["accessors"][a], d.bytes.add_view(idx), kUnsignedInt, dm.num_faces() * 3);
  d.doc["accessors"][a].erase("min");
  d.doc["accessors"][a].erase("max");
}

// Draco quantises: the declared bounds are the original's, the decoded values lie a step inside.
void bound_decoded_values(DracoPrimitive& d, size_t a, size_t n) {
  const std::vector<double> v = accessor_values(d.doc, a, d.bytes, d.shown_as, true);
  json lo = json::array(), hi = json::array();
  for (size_t c = 0; c < n; ++c) {
    double l = std::numeric_limits<double>::infinity(), h = -l;
    for (size_t i = c; i < v.size(); i += n) l = std::min(l, v[i]), h = std::max(h, v[i]);
    lo.push_back(l), hi.push_back(h);
  }
  json& bounded = d.doc["accessors"][a];
  if (v.empty()) {
    bounded.erase("min"), bounded.erase("max");
  } else {
    bounded["min"] = lo, bounded["max"] = hi;
  }
}

void write_draco_attribute(DracoPrimitive& d, json& prim, const std::string& name, const json& id,
                           const draco::Mesh& dm) {
  if (!prim.contains("attributes") || !prim["attributes"].contains(name) ||
      !prim["attributes"][name].is_number_unsigned() ||
      prim["attributes"][name].get<size_t>() >= d.doc["accessors"].size())
    throw IOError(d.what + ": Draco attribute " + name + " has no accessor");
  const draco::PointAttribute* attr = id.is_number_unsigned() ? dm.GetAttributeByUniqueId(id.get<uint32_t>()) : nullptr;
  if (!attr) throw IOError(d.what + ": its Draco data has no attribute " + id.dump() + " (" + name + ")");
  const size_t a = own_accessor(d.doc, prim["attributes"][name], d.filled);
  json& acc = d.doc["accessors"][a];
  const size_t n = component_count(acc.value("type", "")), points = dm.num_points();
  const int type = acc.value("componentType", 0);
  const std::string values = draco_values_as(*attr, type, points, n);
  if (n == 0 || (values.empty() && points > 0))
    throw IOError(d.what + ": Draco attribute " + name + " cannot be read as its accessor's type");
  point_accessor_at(acc, d.bytes.add_view(values), type, points);
  if (acc.contains("min") || acc.contains("max")) bound_decoded_values(d, a, n);
}

void decode_draco_primitive(DracoPrimitive& d, json& prim) {
  const json& e = prim["extensions"][kDracoExtension];
  if (prim.value("mode", 4) != 4) throw IOError(d.what + " is Draco-compressed and not made of triangles");
  const std::unique_ptr<draco::Mesh> dm = decode_draco_mesh(d, e);
  write_draco_indices(d, prim, *dm);
  if (!e.contains("attributes") || !e["attributes"].is_object())
    throw IOError(d.what + ": its Draco extension lists no attributes");
  for (const auto& [name, id] : e["attributes"].items()) write_draco_attribute(d, prim, name, id, *dm);
  erase_extension(prim, kDracoExtension);
}

}  // namespace

bool decode_draco(json& doc, GltfBytes& bytes, const std::string& shown_as) {
  if (!doc.contains("meshes") || !doc["meshes"].is_array()) return false;
  bool any = false;
  std::set<size_t> filled;
  for (size_t m = 0; m < doc["meshes"].size(); ++m) {
    json& mesh = doc["meshes"][m];
    if (!mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (size_t p = 0; p < mesh["primitives"].size(); ++p) {
      json& prim = mesh["primitives"][p];
      if (!prim.contains("extensions") || !prim["extensions"].contains(kDracoExtension)) continue;
      DracoPrimitive d{doc, bytes, filled, shown_as,
                       shown_as + ": primitive " + std::to_string(p) + " of mesh " + std::to_string(m)};
      decode_draco_primitive(d, prim);
      any = true;
    }
  }
  return any;
}

}  // namespace OpenMeshSkinned::detail
