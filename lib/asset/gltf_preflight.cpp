// The checks that run on the JSON before tiny_gltf sees it. tiny_gltf reads
// indices as int (4294967296 becomes 0), indexes arrays with what the file says
// inside KHR_draco_mesh_compression, and never checks that a buffer view lies in
// its buffer; so every index and range is checked here, with a message that names
// the element, and tiny_gltf only ever gets a file whose references hold.
#include <set>

#include "base/errors.h"
#include "asset/gltf_container.h"

namespace crowdprof {

namespace {

using nlohmann::json;

const json& array_or_empty(const json& object, const char* key) {
  static const json empty = json::array();
  return object.is_object() && object.contains(key) && object[key].is_array() ? object[key] : empty;
}

struct Checker {
  const GltfContainer& c;

  [[noreturn]] void fail(const std::string& where, const std::string& problem) const {
    throw InputError(c.path, where + ": " + problem);
  }

  const json& object(const json& parent, const char* array, size_t i, const std::string& where) const {
    const json& o = parent[array][i];
    if (!o.is_object()) fail(where, "is not a JSON object");
    return o;
  }

  // `value` (found as `key` in `where`) must index an element of top-level `array`,
  // or of `within` when given (an animation's own samplers).
  void index(const json& value, const std::string& key, const char* array, const std::string& where,
             const json* within = nullptr) const {
    const json& target = within ? *within : array_or_empty(c.json, array);
    if (!value.is_number_integer()) fail(where, key + " is " + printable(value.dump(), 40) + ", not an index");
    if (value.is_number_unsigned() && value.get<uint64_t>() < target.size()) return;
    fail(where, key + " names " + array + "[" + value.dump() + "], which does not exist (" + str(target.size()) +
                    " in the " + (within ? "animation" : "file") + ")");
  }
  void optional(const json& object, const char* key, const char* array, const std::string& where) const {
    if (object.contains(key)) index(object[key], key, array, where);
  }
  void required(const json& object, const char* key, const char* array, const std::string& where) const {
    if (!object.contains(key)) fail(where, std::string("has no ") + key);
    index(object[key], key, array, where);
  }
  void each(const json& object, const char* key, const char* array, const std::string& where) const {
    if (!object.contains(key)) return;
    if (!object[key].is_array()) fail(where, std::string(key) + " is not an array");
    for (const json& value : object[key]) index(value, key, array, where);
  }
  uint64_t unsigned_number(const json& object, const char* key, uint64_t fallback, const std::string& where) const {
    if (!object.contains(key)) return fallback;
    if (!object[key].is_number_unsigned())
      fail(where, std::string(key) + " is " + printable(object[key].dump(), 40) + ", not a byte count");
    return object[key].get<uint64_t>();
  }

  void buffer_views() const {
    const json& views = array_or_empty(c.json, "bufferViews");
    for (size_t v = 0; v < views.size(); ++v) {
      std::string where = "buffer view " + str(v);
      const json& view = object(c.json, "bufferViews", v, where);
      required(view, "buffer", "buffers", where);
      size_t b = view["buffer"].get<size_t>();
      uint64_t size = unsigned_number(c.json["buffers"][b], "byteLength", 0, "buffer " + str(b));
      uint64_t offset = unsigned_number(view, "byteOffset", 0, where);
      uint64_t length = unsigned_number(view, "byteLength", 0, where);
      if (offset > size || length > size - offset)
        fail(where, "reaches past the end of buffer " + str(b) + " (bytes " + std::to_string(offset) + " + " +
                        std::to_string(length) + " of " + std::to_string(size) + ")");
    }
  }

  void accessors() const {
    static const std::set<int64_t> component_types = {5120, 5121, 5122, 5123, 5125, 5126};
    const json& list = array_or_empty(c.json, "accessors");
    for (size_t a = 0; a < list.size(); ++a) {
      std::string where = "accessor " + str(a);
      const json& accessor = object(c.json, "accessors", a, where);
      optional(accessor, "bufferView", "bufferViews", where);
      unsigned_number(accessor, "byteOffset", 0, where);
      if (!accessor.contains("componentType") || !accessor["componentType"].is_number_integer() ||
          !component_types.count(accessor["componentType"].get<int64_t>()))
        fail(where, "has component type " + printable(accessor.value("componentType", json()).dump(), 20) +
                        ", which glTF does not define");
    }
  }

  void meshes() const {
    const json& list = array_or_empty(c.json, "meshes");
    for (size_t m = 0; m < list.size(); ++m) {
      const json& mesh = object(c.json, "meshes", m, "mesh " + str(m));
      const json& primitives = array_or_empty(mesh, "primitives");
      for (size_t p = 0; p < primitives.size(); ++p) {
        std::string where = "mesh " + str(m) + " primitive " + str(p);
        const json& prim = object(mesh, "primitives", p, where);
        if (!prim.contains("attributes") || !prim["attributes"].is_object()) fail(where, "has no attributes");
        for (auto& [name, value] : prim["attributes"].items()) index(value, printable(name), "accessors", where);
        optional(prim, "indices", "accessors", where);
      }
    }
  }

  void nodes_and_skins() const {
    const json& nodes = array_or_empty(c.json, "nodes");
    for (size_t n = 0; n < nodes.size(); ++n) {
      std::string where = "node " + str(n);
      const json& node = object(c.json, "nodes", n, where);
      each(node, "children", "nodes", where);
      optional(node, "mesh", "meshes", where);
      optional(node, "skin", "skins", where);
    }
    const json& skins = array_or_empty(c.json, "skins");
    for (size_t s = 0; s < skins.size(); ++s) {
      std::string where = "skin " + str(s);
      const json& skin = object(c.json, "skins", s, where);
      if (!skin.contains("joints")) fail(where, "has no joints");
      each(skin, "joints", "nodes", where);
      optional(skin, "inverseBindMatrices", "accessors", where);
      optional(skin, "skeleton", "nodes", where);
    }
    const json& scenes = array_or_empty(c.json, "scenes");
    for (size_t s = 0; s < scenes.size(); ++s)
      each(object(c.json, "scenes", s, "scene " + str(s)), "nodes", "nodes", "scene " + str(s));
    optional(c.json, "scene", "scenes", "the file");
  }

  void animations() const {
    const json& list = array_or_empty(c.json, "animations");
    for (size_t a = 0; a < list.size(); ++a) {
      const json& animation = object(c.json, "animations", a, "animation " + str(a));
      const json& samplers = array_or_empty(animation, "samplers");
      for (size_t s = 0; s < samplers.size(); ++s) {
        std::string where = "animation " + str(a) + " sampler " + str(s);
        const json& sampler = object(animation, "samplers", s, where);
        required(sampler, "input", "accessors", where);
        required(sampler, "output", "accessors", where);
      }
      const json& channels = array_or_empty(animation, "channels");
      for (size_t ch = 0; ch < channels.size(); ++ch) {
        std::string where = "animation " + str(a) + " channel " + str(ch);
        const json& channel = object(animation, "channels", ch, where);
        if (!channel.contains("sampler")) fail(where, "has no sampler");
        index(channel["sampler"], "sampler", "samplers", where, &samplers);
        if (!channel.contains("target") || !channel["target"].is_object()) fail(where, "has no target");
        if (channel["target"].contains("node")) index(channel["target"]["node"], "target node", "nodes", where);
      }
    }
  }

  void images() const {
    const json& list = array_or_empty(c.json, "images");
    for (size_t i = 0; i < list.size(); ++i) {
      std::string where = "image " + str(i);
      const json& image = object(c.json, "images", i, where);
      optional(image, "bufferView", "bufferViews", where);
      if (!image.contains("uri")) continue;
      if (!image["uri"].is_string()) fail(where, "has a uri that is not a string");
      std::string uri = image["uri"].get<std::string>();
      if (uri.rfind("data:", 0) != 0) resolve_inside(c, uri, where);
    }
  }

  void buffers() const {
    const json& list = array_or_empty(c.json, "buffers");
    for (size_t b = 0; b < list.size(); ++b) {
      std::string where = "buffer " + str(b);
      const json& buffer = object(c.json, "buffers", b, where);
      if (!buffer.contains("byteLength") || !buffer["byteLength"].is_number_unsigned())
        fail(where, "has no valid byteLength");
      if (!buffer.contains("uri")) continue;
      if (!buffer["uri"].is_string()) fail(where, "has a uri that is not a string");
      std::string uri = buffer["uri"].get<std::string>();
      if (uri.rfind("data:", 0) == 0) continue;
      std::string full = resolve_inside(c, uri, where);
      std::error_code ec;
      if (!std::filesystem::is_regular_file(full, ec)) fail(where, "file \"" + printable(uri, 80) + "\" is missing");
    }
  }

  // tiny_gltf decodes Draco into the primitive's accessors, trusting every index.
  void draco() const {
    std::map<uint64_t, std::string> views;  // Draco view -> the primitive that decodes it
    const json& meshes = array_or_empty(c.json, "meshes");
    for (size_t m = 0; m < meshes.size(); ++m) {
      const json& primitives = array_or_empty(meshes[m], "primitives");
      for (size_t p = 0; p < primitives.size(); ++p) {
        const json& prim = primitives[p];
        if (!prim.contains("extensions") || !prim["extensions"].is_object()) continue;
        const json& ext = prim["extensions"];
        if (!ext.contains("KHR_draco_mesh_compression")) continue;
        std::string where = "mesh " + str(m) + " primitive " + str(p) + " Draco extension";
        const json& draco = ext["KHR_draco_mesh_compression"];
        if (!draco.is_object() || !draco.contains("bufferView") || !draco.contains("attributes") ||
            !draco["attributes"].is_object())
          fail(where, "needs bufferView and attributes");
        index(draco["bufferView"], "bufferView", "bufferViews", where);
        if (!prim.contains("indices"))
          fail(where, "primitive has no indices; crowdprof reads Draco triangle meshes only");
        for (auto& [name, id] : draco["attributes"].items()) {
          if (!id.is_number_unsigned())
            fail(where, "attribute " + printable(name) + " has id " + printable(id.dump(), 20));
          if (!prim["attributes"].contains(name))
            fail(where, "attribute " + printable(name) + " is not among the primitive's");
        }
        // tiny_gltf decodes a view once: a second primitive on it would keep undecoded accessors.
        std::string identity = prim["attributes"].dump() + prim["indices"].dump();
        auto [it, fresh] = views.emplace(draco["bufferView"].get<uint64_t>(), identity);
        if (!fresh && it->second != identity)
          fail(where, "shares Draco buffer view " + draco["bufferView"].dump() + " with another primitive");
      }
    }
  }
};

const std::set<std::string>& supported_required_extensions() {
  static const std::set<std::string> names = {"KHR_draco_mesh_compression", "KHR_mesh_quantization",
                                              "KHR_materials_unlit", "KHR_texture_transform"};
  return names;
}

}  // namespace

void preflight_gltf(const GltfContainer& c) {
  const json& root = c.json;
  if (!root.contains("asset") || !root["asset"].is_object() || !root["asset"].contains("version") ||
      !root["asset"]["version"].is_string())
    throw InputError(c.path, "is not glTF: no asset.version");
  std::string version = root["asset"]["version"].get<std::string>();
  if (version.rfind("2.", 0) != 0) throw InputError(c.path, "glTF version " + printable(version, 20) + " is not 2.x");
  for (const json& name : array_or_empty(root, "extensionsRequired")) {
    if (!name.is_string() || !supported_required_extensions().count(name.get<std::string>()))
      throw InputError(c.path, "requires extension " + printable(name.dump()) + ", which crowdprof does not support");
  }
  for (const char* key :
       {"buffers", "bufferViews", "accessors", "meshes", "nodes", "skins", "animations", "scenes", "images"})
    if (root.contains(key) && !root[key].is_array()) throw InputError(c.path, std::string(key) + " is not an array");
  Checker check{c};
  check.buffers();
  check.buffer_views();
  check.accessors();
  check.meshes();
  check.nodes_and_skins();
  check.animations();
  check.images();
  check.draco();
}

}  // namespace crowdprof
