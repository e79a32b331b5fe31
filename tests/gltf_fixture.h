// Tiny glTF files built in code, for the loader's tests: a valid skinned character
// that each test breaks in one place. Header only (tests/ builds *_test.cpp).
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace crowdprof::test {

inline constexpr int kByte = 5120, kUByte = 5121, kShort = 5122, kUShort = 5123, kUInt = 5125, kFloat = 5126;

inline std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t n = uint32_t(bytes[i]) << 16;
    if (i + 1 < bytes.size()) n |= uint32_t(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) n |= bytes[i + 2];
    out += digits[n >> 18 & 63];
    out += digits[n >> 12 & 63];
    out += i + 1 < bytes.size() ? digits[n >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? digits[n & 63] : '=';
  }
  return out;
}

inline void write_file(const std::filesystem::path& path, const void* data, size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
}
inline void write_file(const std::filesystem::path& path, const std::string& text) {
  write_file(path, text.data(), text.size());
}

// A glTF document and its one buffer, with helpers to add data and to write it out.
struct GltfFixture {
  nlohmann::json json = {{"asset", {{"version", "2.0"}}},
                         {"buffers", nlohmann::json::array()},
                         {"bufferViews", nlohmann::json::array()},
                         {"accessors", nlohmann::json::array()}};
  std::vector<unsigned char> bin;

  // Appends bytes (4-aligned) as a new buffer view; returns its index.
  int add_view(const void* data, size_t size) {
    bin.resize((bin.size() + 3) & ~size_t(3));
    size_t offset = bin.size();
    bin.insert(bin.end(), static_cast<const unsigned char*>(data), static_cast<const unsigned char*>(data) + size);
    json["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}});
    return static_cast<int>(json["bufferViews"].size() - 1);
  }

  // An accessor over a new view holding `values`; `components` per element.
  template <typename T>
  int add_accessor(const std::vector<T>& values, int component_type, const char* type, size_t components,
                   bool normalized = false) {
    int view = add_view(values.data(), values.size() * sizeof(T));
    nlohmann::json a = {
        {"bufferView", view}, {"componentType", component_type}, {"count", values.size() / components}, {"type", type}};
    if (normalized) a["normalized"] = true;
    json["accessors"].push_back(a);
    return static_cast<int>(json["accessors"].size() - 1);
  }

  // Where accessor `index`'s first element lies in `bin`.
  unsigned char* bytes_of(int index) {
    const auto& a = json["accessors"][static_cast<size_t>(index)];
    const auto& v = json["bufferViews"][a["bufferView"].get<size_t>()];
    return bin.data() + v["byteOffset"].get<size_t>() + a.value("byteOffset", size_t(0));
  }
  template <typename T>
  void set(int accessor, size_t element, T value) {
    std::memcpy(bytes_of(accessor) + element * sizeof(T), &value, sizeof(T));
  }

  nlohmann::json& accessor(int index) { return json["accessors"][static_cast<size_t>(index)]; }
  nlohmann::json& view_of(int accessor_index) {
    return json["bufferViews"][accessor(accessor_index)["bufferView"].get<size_t>()];
  }

  // The "buffers" array to write: one buffer whose byteLength is bin's size unless
  // set, with a uri from `uri` unless set. A test that damaged "buffers" gets it as is.
  nlohmann::json buffers(const std::string& uri) const {
    auto it = json.find("buffers");
    if (it == json.end()) return nullptr;
    if (!it->is_array() || it->size() > 1 || (it->size() == 1 && !(*it)[0].is_object())) return *it;
    nlohmann::json b = it->empty() ? nlohmann::json::object() : (*it)[0];
    if (!b.contains("byteLength")) b["byteLength"] = bin.size();
    if (!uri.empty() && !b.contains("uri")) b["uri"] = uri;
    return nlohmann::json::array({b});
  }

  void write_glb(const std::filesystem::path& path) const {
    nlohmann::json doc = json;
    if (nlohmann::json b = buffers(""); !b.is_null()) doc["buffers"] = b;
    std::string text = doc.dump();
    while (text.size() % 4) text += ' ';
    std::vector<unsigned char> padded = bin;
    padded.resize((padded.size() + 3) & ~size_t(3), 0);
    std::vector<unsigned char> out;
    auto u32 = [&](size_t v) {
      for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
    };
    out.insert(out.end(), {'g', 'l', 'T', 'F'});
    u32(2);
    u32(12 + 8 + text.size() + 8 + padded.size());
    u32(text.size());
    u32(0x4E4F534Au);
    out.insert(out.end(), text.begin(), text.end());
    u32(padded.size());
    u32(0x004E4942u);
    out.insert(out.end(), padded.begin(), padded.end());
    write_file(path, out.data(), out.size());
  }

  // .gltf with the buffer as "<stem>.bin" beside it, or inline as a data: URI.
  void write_gltf(const std::filesystem::path& path, bool data_uri = false) const {
    std::string name = path.stem().string() + ".bin";
    nlohmann::json doc = json;
    if (data_uri) {
      doc["buffers"] = buffers("data:application/octet-stream;base64," + base64(bin));
    } else {
      write_file(path.parent_path() / name, bin.data(), bin.size());
      doc["buffers"] = buffers(name);
    }
    write_file(path, doc.dump(1));
  }
};

// A valid skinned character, small enough to read by eye:
//   nodes: 0 "body" (mesh 0, skin 0), 1 "hip" > 2 "spine" > 3 "head";
//   mesh: a 2x3 grid of vertices up the Y axis, 4 triangles, indexed; joints as
//   unsigned short, weights as float, with normals;
//   animation "bend": spine rotation and hip translation over keys at t = 0 and 1.
struct SkinnedFixture : GltfFixture {
  int positions = -1, normals = -1, joints = -1, weights = -1, indices = -1, inverse_binds = -1;
  int times = -1, rotations = -1, translations = -1;

  SkinnedFixture() {
    std::vector<float> p = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 2, 0, 1, 2, 0};
    std::vector<float> n;
    for (int v = 0; v < 6; ++v) n.insert(n.end(), {0, 0, 1});
    std::vector<uint16_t> j = {0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 2, 1, 0, 0, 2, 1, 0, 0};
    std::vector<float> w = {1, 0, 0, 0, 1, 0, 0, 0, .5f, .5f, 0, 0, .5f, .5f, 0, 0, .75f, .25f, 0, 0, .75f, .25f, 0, 0};
    std::vector<uint16_t> i = {0, 1, 2, 2, 1, 3, 2, 3, 4, 4, 3, 5};
    std::vector<float> ibm;
    for (int k = 0; k < 3; ++k) ibm.insert(ibm.end(), {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -float(k), 0, 1});
    positions = add_accessor(p, kFloat, "VEC3", 3);
    normals = add_accessor(n, kFloat, "VEC3", 3);
    joints = add_accessor(j, kUShort, "VEC4", 4);
    weights = add_accessor(w, kFloat, "VEC4", 4);
    indices = add_accessor(i, kUShort, "SCALAR", 1);
    inverse_binds = add_accessor(ibm, kFloat, "MAT4", 16);
    times = add_accessor(std::vector<float>{0, 1}, kFloat, "SCALAR", 1);
    rotations = add_accessor(std::vector<float>{0, 0, 0, 1, 0, 0, 0.38268343f, 0.92387953f}, kFloat, "VEC4", 4);
    translations = add_accessor(std::vector<float>{0, 0, 0, 0, 0.5f, 0}, kFloat, "VEC3", 3);
    json["meshes"] = {
        {{"name", "body"},
         {"primitives",
          {{{"attributes",
             {{"POSITION", positions}, {"NORMAL", normals}, {"JOINTS_0", joints}, {"WEIGHTS_0", weights}}},
            {"indices", indices}}}}}};
    json["nodes"] = {{{"name", "body"}, {"mesh", 0}, {"skin", 0}},
                     {{"name", "hip"}, {"children", {2}}},
                     {{"name", "spine"}, {"translation", {0, 1, 0}}, {"children", {3}}},
                     {{"name", "head"}, {"translation", {0, 1, 0}}}};
    json["skins"] = {{{"name", "rig"}, {"joints", {1, 2, 3}}, {"inverseBindMatrices", inverse_binds}, {"skeleton", 1}}};
    json["scenes"] = {{{"nodes", {0, 1}}}};
    json["scene"] = 0;
    json["animations"] = {{{"name", "bend"},
                           {"samplers",
                            {{{"input", times}, {"output", rotations}, {"interpolation", "LINEAR"}},
                             {{"input", times}, {"output", translations}, {"interpolation", "LINEAR"}}}},
                           {"channels",
                            {{{"sampler", 0}, {"target", {{"node", 2}, {"path", "rotation"}}}},
                             {{"sampler", 1}, {"target", {{"node", 1}, {"path", "translation"}}}}}}}};
  }
};

}  // namespace crowdprof::test
