#include "asset/gltf_loader.h"

#include <charconv>
#include <filesystem>
#include <fstream>
#include <map>

#include <draco/compression/decode.h>
#include <tiny_gltf.h>

#include "base/errors.h"
#include "asset/gltf_accessor.h"
#include "asset/gltf_container.h"
#include "asset/gltf_convert.h"
#include "base/json_assert.h"

namespace crowdprof {
namespace fs = std::filesystem;

namespace {

// tiny_gltf's file callbacks, narrowed: no wordexp expansion, and no read outside
// the asset's folder (preflight already refused such URIs; this is the backstop).
bool file_exists(const std::string& path, void* user) {
  const auto* c = static_cast<const GltfContainer*>(user);
  std::error_code ec;
  fs::path base = fs::weakly_canonical(c->base_dir, ec);
  fs::path full = fs::weakly_canonical(path, ec);
  auto [b, f] = std::mismatch(base.begin(), base.end(), full.begin(), full.end());
  return !ec && b == base.end() && fs::is_regular_file(full, ec);
}
std::string expand_nothing(const std::string& path, void*) {
  return path;
}
bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  if (!file_exists(path, user)) {
    if (err) *err += "cannot read " + path + "\n";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  out->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return static_cast<bool>(in) || in.eof();
}
bool write_nothing(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "crowdprof never writes through the loader\n";
  return false;
}
// Images are never decoded: crowdprof draws untextured meshes.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

std::string first_line(const std::string& text) {
  size_t start = text.find_first_not_of(" \n\r\t");
  if (start == std::string::npos) return "tiny_gltf could not load it";
  size_t end = text.find('\n', start);
  return printable(text.substr(start, end == std::string::npos ? std::string::npos : end - start), 200);
}

void put_u32(std::vector<unsigned char>& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
}

// `text` is the container's own JSON text (or a document made from it): tiny_gltf
// parses it with the same nlohmann as the container did, so it reads the
// document the preflight checked, without a dump and copy of it first.
tinygltf::Model run_tinygltf(const GltfContainer& c, const std::string& text) {
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks(
      {&file_exists, &expand_nothing, &read_whole_file, &write_nothing, const_cast<GltfContainer*>(&c)});
  loader.SetImageLoader(&skip_image, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  bool ok;
  if (c.binary) {
    // Re-packed with the BIN chunk the container kept: tiny_gltf sees the chunks
    // crowdprof read, whatever else the file holds.
    size_t text_padded = (text.size() + 3) & ~size_t(3);
    size_t bin_padded = (c.bin.size() + 3) & ~size_t(3);
    std::vector<unsigned char> glb;
    glb.reserve(28 + text_padded + bin_padded);
    glb.insert(glb.end(), {'g', 'l', 'T', 'F'});
    put_u32(glb, 2);
    put_u32(glb, static_cast<uint32_t>(12 + 8 + text_padded + (c.bin.empty() ? 0 : 8 + bin_padded)));
    put_u32(glb, static_cast<uint32_t>(text_padded));
    put_u32(glb, 0x4E4F534Au);
    glb.insert(glb.end(), text.begin(), text.end());
    glb.resize(glb.size() + text_padded - text.size(), ' ');
    if (!c.bin.empty()) {
      put_u32(glb, static_cast<uint32_t>(bin_padded));
      put_u32(glb, 0x004E4942u);
      glb.insert(glb.end(), c.bin.begin(), c.bin.end());
      glb.resize(glb.size() + bin_padded - c.bin.size(), 0);
    }
    ok = loader.LoadBinaryFromMemory(&model, &err, &warn, glb.data(), static_cast<unsigned>(glb.size()), c.base_dir);
  } else {
    ok = loader.LoadASCIIFromString(&model, &err, &warn, text.data(), static_cast<unsigned>(text.size()), c.base_dir);
  }
  if (!ok) throw InputError(c.path, first_line(err));
  return model;
}

// The bytes a data: URI holds, as tiny_gltf decodes it: base64 after one of the
// headers it knows, up to the first character that is not base64. -1 for a data:
// URI tiny_gltf would not decode (it would look for a file of that name instead).
int64_t data_uri_bytes(const std::string& uri) {
  static const char* headers[] = {"data:application/octet-stream;base64,",
                                  "data:application/gltf-buffer;base64,",
                                  "data:image/jpeg;base64,",
                                  "data:image/png;base64,",
                                  "data:image/bmp;base64,",
                                  "data:image/gif;base64,",
                                  "data:text/plain;base64,"};
  for (const char* header : headers) {
    if (uri.rfind(header, 0) != 0) continue;
    size_t n = 0;
    for (size_t i = std::strlen(header); i < uri.size(); ++i, ++n) {
      unsigned char ch = static_cast<unsigned char>(uri[i]);
      if (!(std::isalnum(ch) || ch == '+' || ch == '/')) break;
    }
    return static_cast<int64_t>(n / 4 * 3 + (n % 4 ? n % 4 - 1 : 0));
  }
  return -1;
}

// Every buffer must hold exactly the bytes it declares (tiny_gltf checks too, but
// would name the whole data URI in its message), and all of them together must
// stay under kMaxAssetBytes.
void check_buffer_sizes(const GltfContainer& c) {
  if (!c.json.contains("buffers")) return;
  const auto& buffers = c.json["buffers"];
  uint64_t total = 0;
  for (size_t b = 0; b < buffers.size(); ++b) {
    const auto& buffer = buffers[b];
    std::string name = "buffer " + std::to_string(b);
    uint64_t declared = buffer["byteLength"].get<uint64_t>();
    total += std::min(declared, kMaxAssetBytes + 1);
    if (total > kMaxAssetBytes)
      throw InputError(c.path, name + ": the buffers declare more than " + std::to_string(kMaxAssetBytes) +
                                   " bytes; refused as absurd");
    uint64_t actual = 0;
    std::string where;
    if (!buffer.contains("uri")) {
      if (!c.binary || b != 0) throw InputError(c.path, name + " has no uri");
      actual = c.bin.size();
      where = "the GLB's BIN chunk";
    } else {
      std::string uri = buffer["uri"].get<std::string>();
      if (uri.rfind("data:", 0) == 0) {
        int64_t bytes = data_uri_bytes(uri);
        if (bytes < 0) throw InputError(c.path, name + " has a data: URI that is not base64 of a known type");
        actual = static_cast<uint64_t>(bytes);
        where = "its data: URI";
        if (actual > declared)
          throw InputError(c.path, name + "'s data: URI holds " + std::to_string(actual) + " bytes, not the " +
                                       std::to_string(declared) + " declared");
      } else {
        std::error_code ec;
        actual = fs::file_size(resolve_inside(c, uri, name), ec);
        if (ec) throw InputError(c.path, name + " file \"" + printable(uri, 80) + "\" cannot be read: " + ec.message());
        where = "\"" + printable(uri, 80) + "\"";
        if (actual > kMaxAssetBytes)
          throw InputError(c.path, name + " file " + where + " is " + std::to_string(actual) +
                                       " bytes; crowdprof reads at most " + std::to_string(kMaxAssetBytes));
      }
    }
    if (actual < declared)
      throw InputError(c.path, name + " is shorter than declared: " + where + " has " + std::to_string(actual) +
                                   " of " + std::to_string(declared) + " bytes");
  }
}

struct DracoPrimitive {
  size_t mesh, primitive;
  std::vector<int> accessors;  // the attribute accessors tiny_gltf must point at decoded data
};

bool has_draco(const nlohmann::json& prim) {
  return prim.is_object() && prim.contains("extensions") && prim["extensions"].is_object() &&
         prim["extensions"].contains("KHR_draco_mesh_compression");
}

int type_components(const nlohmann::json& accessor) {
  static const std::map<std::string, int> components = {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4},
                                                        {"MAT2", 4},   {"MAT3", 9}, {"MAT4", 16}};
  auto it = accessor.contains("type") && accessor["type"].is_string()
                ? components.find(accessor["type"].get<std::string>())
                : components.end();
  return it == components.end() ? 0 : it->second;
}

// The Draco data type a glTF component type is stored as.
draco::DataType draco_type_of(int64_t component_type) {
  switch (component_type) {
    case 5120:
      return draco::DT_INT8;
    case 5121:
      return draco::DT_UINT8;
    case 5122:
      return draco::DT_INT16;
    case 5123:
      return draco::DT_UINT16;
    case 5125:
      return draco::DT_UINT32;
    case 5126:
      return draco::DT_FLOAT32;
    default:
      return draco::DT_INVALID;
  }
}

std::string draco_type_name(draco::DataType type) {
  switch (type) {
    case draco::DT_INT8:
      return "8-bit integers";
    case draco::DT_UINT8:
      return "unsigned 8-bit integers";
    case draco::DT_INT16:
      return "16-bit integers";
    case draco::DT_UINT16:
      return "unsigned 16-bit integers";
    case draco::DT_INT32:
      return "32-bit integers";
    case draco::DT_UINT32:
      return "unsigned 32-bit integers";
    case draco::DT_INT64:
      return "64-bit integers";
    case draco::DT_UINT64:
      return "unsigned 64-bit integers";
    case draco::DT_FLOAT32:
      return "32-bit floats";
    case draco::DT_FLOAT64:
      return "64-bit floats";
    case draco::DT_BOOL:
      return "booleans";
    default:
      return "values of Draco type " + std::to_string(static_cast<int>(type));
  }
}

// Decodes every Draco primitive once on a model of the buffers alone and checks
// what tiny_gltf will trust when it decodes again: that the data decodes, that
// each attribute exists with the accessor's component count (tiny_gltf converts
// into a 4-element array) and component type, and that the indices fit the
// accessor's type.
std::vector<DracoPrimitive> trial_decode_draco(const GltfContainer& c) {
  std::vector<DracoPrimitive> found;
  if (!c.json.contains("meshes")) return found;
  for (size_t m = 0; m < c.json["meshes"].size(); ++m) {
    const auto& mesh = c.json["meshes"][m];
    if (!mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (size_t p = 0; p < mesh["primitives"].size(); ++p)
      if (has_draco(mesh["primitives"][p])) found.push_back({m, p, {}});
  }
  if (found.empty()) return found;
  nlohmann::json bytes_only = {{"asset", c.json["asset"]}};
  for (const char* key : {"buffers", "bufferViews"})
    if (c.json.contains(key)) bytes_only[key] = c.json[key];
  tinygltf::Model model = run_tinygltf(c, bytes_only.dump());
  const auto& accessors = c.json["accessors"];
  for (DracoPrimitive& d : found) {
    const auto& prim = c.json["meshes"][d.mesh]["primitives"][d.primitive];
    const auto& ext = prim["extensions"]["KHR_draco_mesh_compression"];
    std::string where = "mesh " + std::to_string(d.mesh) + " primitive " + std::to_string(d.primitive);
    auto fail = [&](const std::string& why) { throw InputError(c.path, where + ": " + why); };
    const tinygltf::BufferView& view = model.bufferViews[ext["bufferView"].get<size_t>()];
    const tinygltf::Buffer& buffer = model.buffers[static_cast<size_t>(view.buffer)];
    if (view.byteOffset > buffer.data.size() || view.byteLength > buffer.data.size() - view.byteOffset)
      fail("Draco buffer view reaches past the end of buffer " + std::to_string(view.buffer));
    draco::DecoderBuffer in;
    in.Init(reinterpret_cast<const char*>(buffer.data.data() + view.byteOffset), view.byteLength);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&in);
    if (!decoded.ok()) fail("corrupt Draco data (" + printable(decoded.status().error_msg_string(), 80) + ")");
    const draco::Mesh& mesh = *decoded.value();
    if (mesh.num_points() == 0 || mesh.num_points() > kMaxAccessorElements || mesh.num_faces() == 0 ||
        mesh.num_faces() > kMaxAccessorElements)
      fail("Draco data decodes to " + std::to_string(mesh.num_points()) + " points and " +
           std::to_string(mesh.num_faces()) + " triangles");
    // tiny_gltf narrows the decoded indices to the accessor's type without a check.
    size_t indices = prim["indices"].get<size_t>();
    int64_t index_type = accessors[indices]["componentType"].get<int64_t>();
    uint64_t index_limit = index_type == 5121 ? 1u << 8 : index_type == 5123 ? 1u << 16 : uint64_t(1) << 32;
    if (index_type != 5121 && index_type != 5123 && index_type != 5125)
      fail("index accessor " + std::to_string(indices) + " has component type " + std::to_string(index_type) +
           ", not an unsigned integer type");
    if (mesh.num_points() > index_limit)
      fail("Draco data has " + std::to_string(mesh.num_points()) + " points, more than index accessor " +
           std::to_string(indices) + "'s component type can name");
    for (auto& [name, id] : ext["attributes"].items()) {
      const draco::PointAttribute* attribute = mesh.GetAttributeByUniqueId(id.get<uint32_t>());
      if (!attribute) fail("Draco data has no attribute " + id.dump() + " for " + printable(name));
      int accessor = prim["attributes"][name].get<int>();
      int expected = type_components(accessors[static_cast<size_t>(accessor)]);
      if (attribute->num_components() != expected || expected > 4)
        fail("Draco attribute " + printable(name) + " has " + std::to_string(attribute->num_components()) +
             " components, but its accessor " + std::to_string(accessor) + " has " + std::to_string(expected));
      // tiny_gltf converts each value to the accessor's type without a word, so
      // 16-bit joint indices mapped to a float WEIGHTS_0 would load as weights.
      int64_t component_type = accessors[static_cast<size_t>(accessor)].value("componentType", int64_t(0));
      if (attribute->data_type() != draco_type_of(component_type))
        fail("Draco attribute " + printable(name) + " holds " + draco_type_name(attribute->data_type()) +
             ", but its accessor " + std::to_string(accessor) + " has component type " +
             std::to_string(component_type));
      d.accessors.push_back(accessor);
    }
  }
  return found;
}

// tiny_gltf decodes into new buffer views, but records a decoded attribute's
// stride and offset in Draco's units while writing it tightly packed in the
// accessor's; make the views say what the bytes hold. An accessor still on an old
// view was not decoded (tiny_gltf ignores a failed conversion), so refuse it.
void normalise_draco_views(tinygltf::Model& model, const std::vector<DracoPrimitive>& draco, size_t views_in_file,
                           const std::string& file) {
  for (const DracoPrimitive& d : draco) {
    for (int index : d.accessors) {
      const tinygltf::Accessor& a = model.accessors[static_cast<size_t>(index)];
      if (a.bufferView < 0 || static_cast<size_t>(a.bufferView) < views_in_file)
        throw InputError(file, "mesh " + std::to_string(d.mesh) + " primitive " + std::to_string(d.primitive) +
                                   ": Draco data does not convert to accessor " + std::to_string(index) +
                                   "'s component type");
      tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(a.bufferView)];
      view.byteStride = 0;
      view.byteOffset = 0;
    }
  }
}

// All characters of one file together: past this, a file is refused as absurd
// (the thesis's crowd shares one character of well under a megabyte).
constexpr size_t kMaxAssetSharedBytes = size_t(2) << 30;

GltfAsset load_checked(const std::string& file, GltfContainer container) {
  preflight_gltf(container);
  check_buffer_sizes(container);
  std::vector<DracoPrimitive> draco = trial_decode_draco(container);
  tinygltf::Model model = run_tinygltf(container, container.json_text);
  normalise_draco_views(model, draco, container.json.contains("bufferViews") ? container.json["bufferViews"].size() : 0,
                        file);

  GltfAsset asset;
  asset.file = file;
  asset.draco_decoded = !draco.empty();
  std::vector<int> parents = node_parents(model, file);
  size_t shared_bytes = 0;
  for (size_t s = 0; s < model.skins.size(); ++s) {
    asset.characters.push_back(convert_skin(model, parents, static_cast<int>(s), file));
    asset.characters.back().draco_decoded = asset.draco_decoded;
    shared_bytes += asset.characters.back().shared_bytes();
    if (shared_bytes > kMaxAssetSharedBytes)
      throw InputError(file, "its " + std::to_string(s + 1) + " skins would take more than " +
                                 std::to_string(kMaxAssetSharedBytes) + " bytes; refused as absurd");
  }
  asset.node_actions = convert_node_actions(model, file);
  for (const tinygltf::Node& node : model.nodes) asset.node_names.push_back(node.name);
  return asset;
}

// Loads the container, every InputError made one short line naming `file`.
template <class ReadContainer>
GltfAsset load_named(const std::string& file, ReadContainer read_container) {
  try {
    return load_checked(file, read_container());
  } catch (const JsonAssertion& e) {
    // A read nlohmann refused, in tiny_gltf's code or ours: the file is to blame.
    throw InputError(file, printable(e.problem(), 300));
  } catch (const InputError& e) {
    // Every message should already be one short line; this keeps it so if one is not.
    std::string what = e.what(), prefix = file + ": ";
    if (what.rfind(prefix, 0) != 0) throw;
    std::string problem = printable(std::string_view(what).substr(prefix.size()), 300);
    if (problem == what.substr(prefix.size())) throw;
    throw InputError(file, problem);
  }
}

}  // namespace

GltfAsset load_gltf(const std::string& file) {
  return load_named(file, [&] { return read_gltf_container(file); });
}

GltfAsset load_gltf_from_memory(const std::vector<unsigned char>& bytes, const std::string& file) {
  return load_named(file, [&] { return gltf_container_from_bytes(bytes, file); });
}

size_t checked_skin(const GltfAsset& asset, const CharacterSpec& spec) {
  size_t skins = asset.characters.size();
  if (skins == 0) throw InputError(spec.file, "has no skin: nothing to animate (see crowdprof info)");
  if (spec.skin < 0 && skins > 1) {
    std::string list;
    for (size_t s = 0; s < std::min<size_t>(skins, 8); ++s)
      list += (s ? ", " : "") + std::to_string(s) + " \"" + printable(asset.characters[s].name, 40) + "\"";
    if (skins > 8) list += ", ...";
    throw InputError(spec.file, "holds " + std::to_string(skins) + " skins (" + list + "); choose one with " +
                                    spec.file + "#skin=N");
  }
  size_t chosen = spec.skin < 0 ? 0 : static_cast<size_t>(spec.skin);
  if (chosen >= skins)
    throw InputError(spec.file, "has no skin " + std::to_string(chosen) + " (it holds " + std::to_string(skins) + ")");
  return chosen;
}

Character load_character(const std::string& spec_text) {
  CharacterSpec spec = parse_character_spec(spec_text);
  GltfAsset asset = load_gltf(spec.file);
  return std::move(asset.characters[checked_skin(asset, spec)]);
}

}  // namespace crowdprof
