#include "asset/gltf_container.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>

#include "asset/errors.h"

namespace crowdprof {
namespace fs = std::filesystem;

namespace {

uint32_t read_u32(const unsigned char* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

std::vector<unsigned char> read_bytes(const std::string& path) {
  std::error_code ec;
  fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) throw InputError(path, "no such file");
  if (fs::is_directory(status)) throw InputError(path, "is a directory, not a glTF file");
  if (!fs::is_regular_file(status)) throw InputError(path, "is not a regular file");
  uintmax_t size = fs::file_size(path, ec);
  if (ec) throw InputError(path, "cannot read: " + ec.message());
  if (size == 0) throw InputError(path, "is empty");
  if (size > kMaxAssetBytes)
    throw InputError(path, "is " + std::to_string(size) + " bytes; crowdprof reads at most " +
                               std::to_string(kMaxAssetBytes) + " bytes");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, std::string("cannot open: ") + std::strerror(errno));
  std::vector<unsigned char> bytes(static_cast<size_t>(size));
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size));
  if (in.gcount() != static_cast<std::streamsize>(size)) throw InputError(path, "cannot read all of it");
  return bytes;
}

nlohmann::json parse_json(const std::string& path, const char* begin, const char* end) {
  try {
    nlohmann::json json = nlohmann::json::parse(begin, end);
    if (!json.is_object()) throw InputError(path, "broken JSON: the top level is not an object");
    return json;
  } catch (const nlohmann::json::parse_error& e) {
    // nlohmann's message reads "[json.exception.parse_error.101] parse error at line 1, ...".
    std::string what = e.what();
    size_t at = what.find("] ");
    throw InputError(path, "broken JSON: " + (at == std::string::npos ? what : what.substr(at + 2)));
  }
}

// GLB layout: 12-byte header, then chunks of (length, type, payload padded to 4).
void split_glb(GltfContainer& c, const std::vector<unsigned char>& bytes) {
  const std::string& path = c.path;
  if (bytes.size() < 20) throw InputError(path, "truncated GLB: " + std::to_string(bytes.size()) + " bytes");
  uint32_t version = read_u32(&bytes[4]);
  uint32_t length = read_u32(&bytes[8]);
  if (version != 2) throw InputError(path, "GLB version " + std::to_string(version) + " is not 2");
  if (length > bytes.size())
    throw InputError(path, "truncated GLB: header says " + std::to_string(length) + " bytes, file has " +
                               std::to_string(bytes.size()));
  uint64_t offset = 12;
  bool have_json = false;
  while (offset + 8 <= length) {
    uint32_t chunk_length = read_u32(&bytes[offset]);
    uint32_t chunk_type = read_u32(&bytes[offset + 4]);
    uint64_t payload = offset + 8;
    if (payload + chunk_length > length)
      throw InputError(path, "truncated GLB: chunk at byte " + std::to_string(offset) + " needs " +
                                 std::to_string(chunk_length) + " bytes, " +
                                 std::to_string(length - payload) + " remain");
    const char* data = reinterpret_cast<const char*>(bytes.data() + payload);
    if (!have_json) {
      if (chunk_type != 0x4E4F534Au) throw InputError(path, "GLB's first chunk is not JSON");
      c.json = parse_json(path, data, data + chunk_length);
      have_json = true;
    } else if (chunk_type == 0x004E4942u && c.bin.empty()) {
      c.bin.assign(bytes.begin() + static_cast<std::ptrdiff_t>(payload),
                   bytes.begin() + static_cast<std::ptrdiff_t>(payload + chunk_length));
    }
    offset = payload + ((uint64_t(chunk_length) + 3) & ~uint64_t(3));
  }
  if (!have_json) throw InputError(path, "truncated GLB: no JSON chunk");
}

// Index `key` of `object`, if present, must name an element of top-level array `array`.
void check_index(const GltfContainer& c, const nlohmann::json& object, const char* key,
                 const char* array, const std::string& where) {
  if (!object.contains(key)) return;
  const auto& v = object[key];
  size_t count = c.json.contains(array) && c.json[array].is_array() ? c.json[array].size() : 0;
  if (!v.is_number_integer() || v.get<int64_t>() < 0 || v.get<uint64_t>() >= count)
    throw InputError(c.path, where + ": " + key + " " + v.dump() + " names no element of " + array +
                                 " (" + std::to_string(count) + " present)");
}

const nlohmann::json& array_or_empty(const nlohmann::json& json, const char* key) {
  static const nlohmann::json empty = nlohmann::json::array();
  return json.contains(key) && json[key].is_array() ? json[key] : empty;
}

void preflight_draco(const GltfContainer& c) {
  const auto& meshes = array_or_empty(c.json, "meshes");
  for (size_t m = 0; m < meshes.size(); ++m) {
    const auto& primitives = array_or_empty(meshes[m], "primitives");
    for (size_t p = 0; p < primitives.size(); ++p) {
      const auto& prim = primitives[p];
      if (!prim.is_object() || !prim.contains("extensions") || !prim["extensions"].is_object()) continue;
      const auto& ext = prim["extensions"];
      if (!ext.contains("KHR_draco_mesh_compression")) continue;
      std::string where = "mesh " + std::to_string(m) + " primitive " + std::to_string(p) + " Draco extension";
      const auto& draco = ext["KHR_draco_mesh_compression"];
      if (!draco.is_object() || !draco.contains("bufferView") || !draco.contains("attributes") ||
          !draco["attributes"].is_object())
        throw InputError(c.path, where + ": needs bufferView and attributes");
      check_index(c, draco, "bufferView", "bufferViews", where);
      const auto& view = c.json["bufferViews"][draco["bufferView"].get<size_t>()];
      check_index(c, view, "buffer", "buffers", "buffer view " + draco["bufferView"].dump());
      check_index(c, prim, "indices", "accessors", where);
      if (!prim.contains("attributes") || !prim["attributes"].is_object())
        throw InputError(c.path, where + ": primitive has no attributes");
      for (auto& [name, id] : draco["attributes"].items()) {
        if (!id.is_number_integer() || id.get<int64_t>() < 0)
          throw InputError(c.path, where + ": attribute " + name + " has id " + id.dump());
        if (!prim["attributes"].contains(name))
          throw InputError(c.path, where + ": attribute " + name + " is not among the primitive's");
        check_index(c, prim["attributes"], name.c_str(), "accessors", where);
      }
    }
  }
}

const std::set<std::string>& supported_required_extensions() {
  static const std::set<std::string> names = {"KHR_draco_mesh_compression", "KHR_mesh_quantization",
                                              "KHR_materials_unlit", "KHR_texture_transform"};
  return names;
}

}  // namespace

GltfContainer read_gltf_container(const std::string& path) {
  GltfContainer c;
  c.path = path;
  std::error_code ec;
  fs::path absolute = fs::absolute(path, ec);
  c.base_dir = absolute.parent_path().string();
  std::vector<unsigned char> bytes = read_bytes(path);
  if (bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0) {
    c.binary = true;
    split_glb(c, bytes);
    return c;
  }
  size_t first = 0;
  while (first < bytes.size() && std::isspace(bytes[first])) ++first;
  if (first == bytes.size() || bytes[first] != '{')
    throw InputError(path, "is not a glTF file (neither GLB nor JSON)");
  const char* text = reinterpret_cast<const char*>(bytes.data());
  c.json = parse_json(path, text, text + bytes.size());
  return c;
}

std::string resolve_inside(const GltfContainer& c, const std::string& uri, const std::string& what) {
  auto refuse = [&](const std::string& why) {
    throw InputError(c.path, what + " URI \"" + uri.substr(0, 80) + "\" " + why);
  };
  if (uri.empty()) refuse("is empty");
  if (uri.find(':') != std::string::npos) refuse("has a scheme; only data: URIs and relative paths are read");
  if (uri[0] == '/' || uri[0] == '\\') refuse("is an absolute path; refused, assets may only read beside themselves");
  // Check the decoded form, so that "..%2F" cannot slip past.
  std::string decoded;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
      decoded += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      decoded += uri[i];
    }
  }
  if (decoded[0] == '/' || decoded[0] == '\\') refuse("is an absolute path; refused, assets may only read beside themselves");
  if (decoded.find('\0') != std::string::npos) refuse("holds a NUL byte");
  fs::path relative(decoded);
  for (const auto& part : relative)
    if (part == "..") refuse("points outside the asset's folder; refused");
  std::error_code ec;
  fs::path base = fs::weakly_canonical(c.base_dir, ec);
  fs::path full = fs::weakly_canonical(base / relative, ec);
  if (ec) refuse("cannot be resolved");
  // A symlink inside the folder may still lead out of it.
  auto [b, f] = std::mismatch(base.begin(), base.end(), full.begin(), full.end());
  if (b != base.end()) refuse("points outside the asset's folder; refused");
  return full.string();
}

void preflight_gltf(const GltfContainer& c) {
  const auto& json = c.json;
  if (!json.contains("asset") || !json["asset"].is_object() || !json["asset"].contains("version") ||
      !json["asset"]["version"].is_string())
    throw InputError(c.path, "is not glTF: no asset.version");
  std::string version = json["asset"]["version"].get<std::string>();
  if (version.rfind("2.", 0) != 0) throw InputError(c.path, "glTF version " + version + " is not 2.x");
  for (const auto& name : array_or_empty(json, "extensionsRequired")) {
    if (!name.is_string() || !supported_required_extensions().count(name.get<std::string>()))
      throw InputError(c.path, "requires extension " + name.dump() + ", which crowdprof does not support");
  }
  const auto& buffers = array_or_empty(json, "buffers");
  for (size_t b = 0; b < buffers.size(); ++b) {
    if (!buffers[b].is_object()) throw InputError(c.path, "buffer " + std::to_string(b) + " is not an object");
    if (!buffers[b].contains("uri")) continue;
    if (!buffers[b]["uri"].is_string()) throw InputError(c.path, "buffer " + std::to_string(b) + " has a non-string uri");
    std::string uri = buffers[b]["uri"].get<std::string>();
    if (uri.rfind("data:", 0) == 0) continue;
    std::string full = resolve_inside(c, uri, "buffer " + std::to_string(b));
    std::error_code ec;
    if (!fs::is_regular_file(full, ec))
      throw InputError(c.path, "buffer " + std::to_string(b) + " file \"" + uri + "\" is missing");
  }
  const auto& images = array_or_empty(json, "images");
  for (size_t i = 0; i < images.size(); ++i) {
    if (!images[i].is_object() || !images[i].contains("uri") || !images[i]["uri"].is_string()) continue;
    std::string uri = images[i]["uri"].get<std::string>();
    if (uri.rfind("data:", 0) != 0) resolve_inside(c, uri, "image " + std::to_string(i));
  }
  preflight_draco(c);
}

}  // namespace crowdprof
