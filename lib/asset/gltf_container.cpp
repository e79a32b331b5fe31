#include "asset/gltf_container.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "base/errors.h"

namespace crowdprof {
namespace fs = std::filesystem;

namespace {

uint32_t read_u32(const unsigned char* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

// Why a file that is not glTF is refused; for another 3D format, how to get
// glTF from it.
std::string not_gltf(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  static const std::pair<const char*, const char*> kOthers[] = {
      {".fbx", "an FBX file"}, {".dae", "a COLLADA file"}, {".blend", "a Blender file"}, {".3ds", "a 3ds file"},
      {".usd", "a USD file"},  {".usdz", "a USDZ file"},   {".usda", "a USD file"},      {".usdc", "a USD file"}};
  if (ext == ".obj")  // OBJ holds meshes only: converting it gives no skin to animate
    return "is a Wavefront OBJ file, not glTF: OBJ holds no skeleton or animation; crowdprof needs a skinned, "
           "animated character as .glb or .gltf, e.g. rigged in Blender and written with File > Export > glTF 2.0";
  for (const auto& [suffix, what] : kOthers)
    if (ext == suffix)
      return std::string("is ") + what +
             ", not glTF: crowdprof reads .glb and .gltf; convert it to glTF, e.g. in Blender (import it, then "
             "File > Export > glTF 2.0, with its armature and animations)";
  return "is not a glTF file (neither GLB nor a JSON object)";
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
  // Judge the format on the first bytes: a large file that is not glTF at all
  // is refused before it is read whole.
  std::string head = read_file_head(path);
  if (head.rfind("glTF", 0) != 0) {
    size_t first = head.find_first_not_of(" \t\r\n");
    if (first != std::string::npos && head[first] != '{') throw InputError(path, not_gltf(path));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, std::string("cannot open: ") + std::strerror(errno));
  std::vector<unsigned char> bytes(static_cast<size_t>(size));
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size));
  if (in.gcount() != static_cast<std::streamsize>(size)) throw InputError(path, "cannot read all of it");
  return bytes;
}

nlohmann::json parse_json(const std::string& path, const char* begin, const char* end) {
  nlohmann::json json = parse_json_input(path, std::string_view(begin, static_cast<size_t>(end - begin)));
  if (!json.is_object()) throw InputError(path, "broken JSON: the top level is not an object");
  return json;
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
                                 std::to_string(chunk_length) + " bytes, " + std::to_string(length - payload) +
                                 " remain");
    const char* data = reinterpret_cast<const char*>(bytes.data() + payload);
    if (!have_json) {
      if (chunk_type != 0x4E4F534Au) throw InputError(path, "GLB's first chunk is not JSON");
      c.json_text.assign(data, chunk_length);
      c.json = parse_json(path, c.json_text.data(), c.json_text.data() + c.json_text.size());
      have_json = true;
    } else if (chunk_type == 0x004E4942u && c.bin.empty()) {
      c.bin.assign(bytes.begin() + static_cast<std::ptrdiff_t>(payload),
                   bytes.begin() + static_cast<std::ptrdiff_t>(payload + chunk_length));
    }
    offset = payload + ((uint64_t(chunk_length) + 3) & ~uint64_t(3));
  }
  if (!have_json) throw InputError(path, "truncated GLB: no JSON chunk");
}

}  // namespace

GltfContainer read_gltf_container(const std::string& path) {
  return gltf_container_from_bytes(read_bytes(path), path);
}

GltfContainer gltf_container_from_bytes(const std::vector<unsigned char>& bytes, const std::string& path) {
  GltfContainer c;
  c.path = path;
  std::error_code ec;
  fs::path absolute = fs::absolute(path, ec);
  c.base_dir = absolute.parent_path().string();
  if (bytes.empty()) throw InputError(path, "is empty");
  if (bytes.size() > kMaxAssetBytes)
    throw InputError(path, "is " + std::to_string(bytes.size()) + " bytes; crowdprof reads at most " +
                               std::to_string(kMaxAssetBytes) + " bytes");
  if (bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0) {
    c.binary = true;
    split_glb(c, bytes);
    return c;
  }
  size_t first = 0;
  while (first < bytes.size() && std::isspace(bytes[first])) ++first;
  if (first == bytes.size() || bytes[first] != '{') throw InputError(path, not_gltf(path));
  c.json_text.assign(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  c.json = parse_json(path, c.json_text.data(), c.json_text.data() + c.json_text.size());
  return c;
}

std::string resolve_inside(const GltfContainer& c, const std::string& uri, const std::string& what) {
  auto refuse = [&](const std::string& why) {
    throw InputError(c.path, what + " URI \"" + printable(uri, 80) + "\" " + why);
  };
  if (uri.empty()) refuse("is empty");
  if (uri.find('\\') != std::string::npos) refuse("holds a backslash; URIs separate folders with /");
  if (uri.find(':') != std::string::npos) refuse("has a scheme; only data: URIs and relative paths are read");
  if (uri[0] == '/') refuse("is an absolute path; refused, assets may only read beside themselves");
  // Check the decoded form, so that "..%2F" cannot slip past, decoded as
  // tiny_gltf's urldecode does (the file it will read): '+' is a space, and a
  // '%' with two characters after it is a byte, a character that is not a hex
  // digit counting as 0.
  auto nibble = [](char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return 0;
  };
  std::string decoded;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '+') {
      decoded += ' ';
    } else if (uri[i] == '%' && i + 2 < uri.size()) {
      decoded += static_cast<char>(nibble(uri[i + 1]) << 4 | nibble(uri[i + 2]));
      i += 2;
    } else {
      decoded += uri[i];
    }
  }
  if (decoded.find('\\') != std::string::npos) refuse("holds a backslash; URIs separate folders with /");
  if (decoded[0] == '/') refuse("is an absolute path; refused, assets may only read beside themselves");
  if (decoded.find('\0') != std::string::npos) refuse("holds a NUL byte");
  fs::path relative(decoded);
  // "sub/../x.bin" stays inside; "../x.bin" and "sub/../../x.bin" do not.
  // (Symlinks are judged below, on the resolved path.)
  int depth = 0;
  for (const auto& part : relative) {
    if (part == "..")
      --depth;
    else if (part != "." && !part.empty())
      ++depth;
    if (depth < 0) refuse("points outside the asset's folder; refused");
  }
  std::error_code ec;
  fs::path base = fs::weakly_canonical(c.base_dir, ec);
  fs::path full = fs::weakly_canonical(base / relative, ec);
  if (ec) refuse("cannot be resolved");
  // A symlink inside the folder may still lead out of it.
  auto [b, f] = std::mismatch(base.begin(), base.end(), full.begin(), full.end());
  if (b != base.end()) refuse("points outside the asset's folder; refused");
  return full.string();
}

std::vector<std::string> gltf_external_files(const std::string& path) {
  // The JSON alone (of a GLB, its first chunk): a character's BIN chunk may be
  // a gigabyte, and only the URIs are wanted here.
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  std::string text(20, '\0');
  in.read(text.data(), 20);
  text.resize(static_cast<size_t>(in.gcount()));
  if (text.size() == 20 && text.compare(0, 4, "glTF") == 0) {
    uint32_t length = 0;
    for (int i = 3; i >= 0; --i) length = length << 8 | static_cast<unsigned char>(text[12 + i]);
    if (length > kMaxAssetBytes) return {};
    text.assign(length, '\0');
    in.read(text.data(), length);
    text.resize(static_cast<size_t>(in.gcount()));
  } else {
    std::error_code ec;
    if (fs::file_size(path, ec) > kMaxAssetBytes || ec) return {};
    text.append(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  GltfContainer c;
  c.path = path;
  std::error_code ec;
  c.base_dir = fs::absolute(path, ec).parent_path().string();
  c.json = nlohmann::json::parse(text, nullptr, false);
  std::vector<std::string> files;
  if (!c.json.is_object()) return files;  // also a parse error; loading it says why
  for (const char* kind : {"buffers", "images"}) {
    const auto list = c.json.find(kind);
    if (list == c.json.end() || !list->is_array()) continue;
    for (const nlohmann::json& item : *list) {
      if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
      const std::string uri = item["uri"].get<std::string>();
      if (uri.rfind("data:", 0) == 0) continue;
      try {
        files.push_back(resolve_inside(c, uri, kind));
      } catch (const InputError&) {
      }
    }
  }
  return files;
}

}  // namespace crowdprof
