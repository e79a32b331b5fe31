#include "asset/gltf_loader.h"

#include <charconv>
#include <filesystem>
#include <fstream>
#include <map>

#include <draco/compression/decode.h>
#include <tiny_gltf.h>

#include "asset/errors.h"
#include "asset/gltf_accessor.h"
#include "asset/gltf_container.h"
#include "asset/gltf_convert.h"

namespace crowdprof {
namespace fs = std::filesystem;

CharacterSpec parse_character_spec(const std::string& spec) {
  CharacterSpec out;
  size_t hash = spec.rfind('#');
  if (hash == std::string::npos) {
    out.file = spec;
    return out;
  }
  out.file = spec.substr(0, hash);
  std::string selector = spec.substr(hash + 1);
  const std::string key = "skin=";
  int skin = -1;
  const char* first = selector.data() + key.size();
  const char* last = selector.data() + selector.size();
  if (selector.rfind(key, 0) != 0 || first == last || std::from_chars(first, last, skin).ptr != last || skin < 0)
    throw UsageError("'" + spec + "': expected FILE or FILE#skin=N with N a skin index (see crowdprof info)");
  out.skin = skin;
  return out;
}

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
std::string expand_nothing(const std::string& path, void*) { return path; }
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
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
                void*) {
  return true;
}

std::string first_line(const std::string& text) {
  size_t start = text.find_first_not_of(" \n\r\t");
  if (start == std::string::npos) return "tiny_gltf could not load it";
  size_t end = text.find('\n', start);
  return text.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

void put_u32(std::vector<unsigned char>& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
}

tinygltf::Model run_tinygltf(const GltfContainer& c, const nlohmann::json& json) {
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({&file_exists, &expand_nothing, &read_whole_file, &write_nothing,
                         const_cast<GltfContainer*>(&c)});
  loader.SetImageLoader(&skip_image, nullptr);
  std::string text = json.dump();
  tinygltf::Model model;
  std::string err, warn;
  bool ok;
  if (c.binary) {
    // Re-pack the (possibly edited) JSON with the original BIN chunk.
    while (text.size() % 4) text.push_back(' ');
    size_t bin_padded = (c.bin.size() + 3) & ~size_t(3);
    std::vector<unsigned char> glb;
    glb.reserve(28 + text.size() + bin_padded);
    glb.insert(glb.end(), {'g', 'l', 'T', 'F'});
    put_u32(glb, 2);
    put_u32(glb, static_cast<uint32_t>(12 + 8 + text.size() + (c.bin.empty() ? 0 : 8 + bin_padded)));
    put_u32(glb, static_cast<uint32_t>(text.size()));
    put_u32(glb, 0x4E4F534Au);
    glb.insert(glb.end(), text.begin(), text.end());
    if (!c.bin.empty()) {
      put_u32(glb, static_cast<uint32_t>(bin_padded));
      put_u32(glb, 0x004E4942u);
      glb.insert(glb.end(), c.bin.begin(), c.bin.end());
      glb.resize(glb.size() + bin_padded - c.bin.size(), 0);
    }
    ok = loader.LoadBinaryFromMemory(&model, &err, &warn, glb.data(), static_cast<unsigned>(glb.size()),
                                     c.base_dir);
  } else {
    ok = loader.LoadASCIIFromString(&model, &err, &warn, text.data(), static_cast<unsigned>(text.size()),
                                    c.base_dir);
  }
  if (!ok) throw InputError(c.path, first_line(err));
  return model;
}

// A buffer must hold the bytes it declares (tiny_gltf checks too; this says it plainly).
void check_buffer_sizes(const GltfContainer& c) {
  if (!c.json.contains("buffers") || !c.json["buffers"].is_array()) return;
  const auto& buffers = c.json["buffers"];
  for (size_t b = 0; b < buffers.size(); ++b) {
    const auto& buffer = buffers[b];
    if (!buffer.contains("byteLength") || !buffer["byteLength"].is_number_unsigned())
      throw InputError(c.path, "buffer " + std::to_string(b) + " has no valid byteLength");
    uint64_t declared = buffer["byteLength"].get<uint64_t>();
    uint64_t actual = 0;
    std::string where;
    if (!buffer.contains("uri")) {
      if (!c.binary || b != 0) throw InputError(c.path, "buffer " + std::to_string(b) + " has no uri");
      actual = c.bin.size();
      where = "the GLB's BIN chunk";
    } else {
      std::string uri = buffer["uri"].get<std::string>();
      if (uri.rfind("data:", 0) == 0) continue;  // tiny_gltf checks decoded sizes
      std::error_code ec;
      actual = fs::file_size(resolve_inside(c, uri, "buffer " + std::to_string(b)), ec);
      where = "\"" + uri + "\"";
    }
    if (actual < declared)
      throw InputError(c.path, "buffer " + std::to_string(b) + " is shorter than declared: " + where + " has " +
                                   std::to_string(actual) + " of " + std::to_string(declared) + " bytes");
  }
}

struct DracoPrimitive {
  size_t mesh, primitive;
  std::map<std::string, int> components;  // attribute -> components Draco decodes
};

bool has_draco(const nlohmann::json& prim) {
  return prim.is_object() && prim.contains("extensions") && prim["extensions"].is_object() &&
         prim["extensions"].contains("KHR_draco_mesh_compression");
}

// Decodes every Draco primitive once on a model loaded without the extension, so
// that corrupt data becomes a message here instead of a crash inside tiny_gltf.
std::vector<DracoPrimitive> trial_decode_draco(const GltfContainer& c) {
  std::vector<DracoPrimitive> found;
  if (!c.json.contains("meshes") || !c.json["meshes"].is_array()) return found;
  for (size_t m = 0; m < c.json["meshes"].size(); ++m) {
    const auto& mesh = c.json["meshes"][m];
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (size_t p = 0; p < mesh["primitives"].size(); ++p)
      if (has_draco(mesh["primitives"][p])) found.push_back({m, p, {}});
  }
  if (found.empty()) return found;
  // Only the bytes are needed here: a model of buffers and views alone.
  nlohmann::json bytes_only = {{"asset", c.json["asset"]}};
  for (const char* key : {"buffers", "bufferViews"})
    if (c.json.contains(key)) bytes_only[key] = c.json[key];
  tinygltf::Model model = run_tinygltf(c, bytes_only);
  for (DracoPrimitive& d : found) {
    const auto& ext = c.json["meshes"][d.mesh]["primitives"][d.primitive]["extensions"]["KHR_draco_mesh_compression"];
    std::string where = "mesh " + std::to_string(d.mesh) + " primitive " + std::to_string(d.primitive);
    const tinygltf::BufferView& view = model.bufferViews[ext["bufferView"].get<size_t>()];
    const tinygltf::Buffer& buffer = model.buffers[static_cast<size_t>(view.buffer)];
    if (uint64_t(view.byteOffset) + view.byteLength > buffer.data.size())
      throw InputError(c.path, where + ": Draco buffer view reaches past the end of buffer " +
                                   std::to_string(view.buffer));
    draco::DecoderBuffer in;
    in.Init(reinterpret_cast<const char*>(buffer.data.data() + view.byteOffset), view.byteLength);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&in);
    if (!decoded.ok())
      throw InputError(c.path, where + ": corrupt Draco data (" + decoded.status().error_msg_string() + ")");
    const draco::Mesh& mesh = *decoded.value();
    if (mesh.num_points() == 0 || mesh.num_points() > kMaxAccessorElements)
      throw InputError(c.path, where + ": Draco data decodes to " + std::to_string(mesh.num_points()) + " points");
    for (auto& [name, id] : ext["attributes"].items()) {
      const draco::PointAttribute* attribute = mesh.GetAttributeByUniqueId(id.get<uint32_t>());
      if (!attribute)
        throw InputError(c.path, where + ": Draco data has no attribute " + id.dump() + " for " + name);
      d.components[name] = attribute->num_components();
    }
  }
  return found;
}

// tiny_gltf records a decoded attribute's stride in Draco's own units, but writes
// it tightly packed in the accessor's; make the views say what the bytes hold.
void normalise_draco_views(tinygltf::Model& model, const std::vector<DracoPrimitive>& draco,
                           const std::string& file) {
  for (const DracoPrimitive& d : draco) {
    const tinygltf::Primitive& prim = model.meshes[d.mesh].primitives[d.primitive];
    for (const auto& [name, components] : d.components) {
      const tinygltf::Accessor& a = model.accessors[static_cast<size_t>(prim.attributes.at(name))];
      int expected = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
      if (expected != components)
        throw InputError(file, "mesh " + std::to_string(d.mesh) + " primitive " + std::to_string(d.primitive) +
                                   ": Draco attribute " + name + " has " + std::to_string(components) +
                                   " components, its accessor " + std::to_string(expected));
      tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(a.bufferView)];
      view.byteStride = 0;
      view.byteOffset = 0;
    }
  }
}

}  // namespace

GltfAsset load_gltf(const std::string& file) {
  GltfContainer container = read_gltf_container(file);
  preflight_gltf(container);
  check_buffer_sizes(container);
  std::vector<DracoPrimitive> draco = trial_decode_draco(container);
  tinygltf::Model model = run_tinygltf(container, container.json);
  normalise_draco_views(model, draco, file);

  GltfAsset asset;
  asset.file = file;
  asset.draco_decoded = !draco.empty();
  std::vector<int> parents = node_parents(model, file);
  for (size_t s = 0; s < model.skins.size(); ++s) {
    asset.characters.push_back(convert_skin(model, parents, static_cast<int>(s), file));
    asset.characters.back().draco_decoded = asset.draco_decoded;
  }
  asset.node_actions = convert_node_actions(model, file);
  for (const tinygltf::Node& node : model.nodes) asset.node_names.push_back(node.name);
  return asset;
}

Character load_character(const std::string& spec_text) {
  CharacterSpec spec = parse_character_spec(spec_text);
  GltfAsset asset = load_gltf(spec.file);
  size_t skins = asset.characters.size();
  if (skins == 0) throw InputError(spec.file, "has no skin: nothing to animate (see crowdprof info)");
  if (spec.skin < 0 && skins > 1) {
    std::string list;
    for (size_t s = 0; s < skins; ++s)
      list += (s ? ", " : "") + std::to_string(s) + " \"" + asset.characters[s].name + "\"";
    throw InputError(spec.file, "holds " + std::to_string(skins) + " skins (" + list + "); choose one with " +
                                    spec.file + "#skin=N");
  }
  size_t chosen = spec.skin < 0 ? 0 : static_cast<size_t>(spec.skin);
  if (chosen >= skins)
    throw InputError(spec.file, "has no skin " + std::to_string(chosen) + " (it holds " + std::to_string(skins) + ")");
  return std::move(asset.characters[chosen]);
}

}  // namespace crowdprof
