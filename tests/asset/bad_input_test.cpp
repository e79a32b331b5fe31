// Bad input, part 1: files that are not glTF, or whose bytes do not hold what the
// JSON says (issue 2, "Bad input, for every command"). Each test breaks a valid
// fixture in one place and checks the one-line message and exit status 3.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "base/input_file.h"
#include "gltf_fixture.h"
#include "loader_checks.h"

namespace crowdprof::test {
namespace {
namespace fs = std::filesystem;

std::string path_in(const std::string& test, const std::string& name) {
  return (scratch_dir(test) / name).string();
}

TEST(BadInput, MissingFile) {
  std::string file = (scratch_dir("missing") / "nowhere.glb").string();
  expect_bad_input(file, {"no such file"});
}

TEST(BadInput, Directory) {
  fs::path dir = scratch_dir("directory") / "looks_like.glb";
  fs::create_directories(dir);
  expect_bad_input(dir.string(), {"is a directory"});
}

TEST(BadInput, EmptyFile) {
  std::string file = path_in("empty", "empty.glb");
  write_file(file, "");
  expect_bad_input(file, {"is empty"});
}

TEST(BadInput, NotGltf) {
  std::string text = path_in("not_gltf", "notes.gltf");
  write_file(text, "these are not the droids you are looking for\n");
  expect_bad_input(text, {"not a glTF file"});
  // Valid JSON, but not glTF.
  std::string json = path_in("not_gltf_json", "array.gltf");
  write_file(json, "[1, 2, 3]");
  expect_bad_input(json, {"not a glTF file"});
  std::string no_asset = path_in("not_gltf_asset", "object.gltf");
  write_file(no_asset, R"({"meshes": []})");
  expect_bad_input(no_asset, {"asset.version"});
  std::string png = path_in("not_gltf_png", "image.glb");
  write_file(png, "\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16);
  expect_bad_input(png, {"not a glTF file"});
}

TEST(BadInput, TruncatedGlb) {
  std::string whole = path_in("truncated", "whole.glb");
  SkinnedFixture().write_glb(whole);
  std::vector<char> bytes(fs::file_size(whole));
  std::ifstream(whole, std::ios::binary).read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  for (size_t keep : {size_t(6), size_t(16), size_t(40), bytes.size() / 2, bytes.size() - 4}) {
    std::string cut = path_in("truncated_" + std::to_string(keep), "cut.glb");
    write_file(cut, bytes.data(), keep);
    expect_bad_input(cut, {"truncated GLB"});
  }
}

TEST(BadInput, BrokenJson) {
  std::string file = path_in("broken_json", "broken.gltf");
  write_file(file, R"({"asset": {"version": "2.0"}, "nodes": [ {"name": "hip"} )");
  expect_bad_input(file, {"truncated JSON"});
  // Broken inside a GLB's JSON chunk.
  std::string glb = path_in("broken_json_glb", "broken.glb");
  std::string json = R"({"asset": {"version": "2.0"},, })";
  std::string bytes = std::string("glTF") + std::string("\2\0\0\0", 4);
  uint32_t length = static_cast<uint32_t>(12 + 8 + json.size()), chunk = static_cast<uint32_t>(json.size());
  bytes.append(reinterpret_cast<const char*>(&length), 4).append(reinterpret_cast<const char*>(&chunk), 4);
  bytes.append("JSON").append(json);
  write_file(glb, bytes);
  expect_bad_input(glb, {"broken JSON"});
}

TEST(BadInput, JsonNestedTooDeep) {
  // Deep nesting would exhaust the stack in recursive JSON walkers.
  std::string file = path_in("deep_json", "deep.gltf");
  std::string extras(100000, '[');
  write_file(file, R"({"asset": {"version": "2.0"}, "extras": )" + extras + std::string(100000, ']') + "}");
  expect_bad_input(file, {"nested"});
}

TEST(BadInput, JsonDepthLimitIsExactly64Levels) {
  // The limit the message names: 64 levels of arrays and objects are read, 65 are not.
  auto nested = [](int levels) {
    std::string text;
    for (int i = 0; i < levels; ++i) text += i % 2 ? "[" : "{\"k\": ";
    text += "0";
    for (int i = levels - 1; i >= 0; --i) text += i % 2 ? "]" : "}";
    return text;
  };
  EXPECT_EQ(parse_json_input("ok.json", nested(kMaxJsonDepth)).size(), 1u);
  try {
    parse_json_input("deep.json", nested(kMaxJsonDepth + 1));
    FAIL() << "65 levels were read";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "deep.json: broken JSON: nested more than 64 levels deep");
  }
}

TEST(BadInput, BufferShorterThanDeclared) {
  SkinnedFixture f;
  // External .bin cut short.
  std::string gltf = path_in("short_bin", "short.gltf");
  f.write_gltf(gltf);
  fs::resize_file(fs::path(gltf).parent_path() / "short.bin", f.bin.size() - 8);
  expect_bad_input(gltf, {"buffer 0 is shorter than declared"});
  // GLB whose buffer declares more than its BIN chunk.
  f.json["buffers"] = {{{"byteLength", f.bin.size() + 64}}};
  std::string glb = path_in("short_glb", "short.glb");
  f.write_glb(glb);
  expect_bad_input(glb, {"buffer 0 is shorter than declared"});
  // A data: URI holding fewer bytes than declared.
  std::string inline_file = path_in("short_data_uri", "short.gltf");
  f.write_gltf(inline_file, /*data_uri=*/true);
  expect_bad_input(inline_file, {"buffer 0 is shorter than declared"});
}

TEST(BadInput, BufferViewPastItsBuffer) {
  SkinnedFixture f;
  f.view_of(f.weights)["byteLength"] = f.bin.size();
  std::string file = path_in("view_past_buffer", "view.glb");
  f.write_glb(file);
  expect_bad_input(file, {"buffer view 3", "past the end of buffer 0"});
  // An offset so large that offset + length wraps around 64 bits.
  SkinnedFixture g;
  g.view_of(g.positions)["byteOffset"] = UINT64_MAX - 7;
  g.write_glb(file);
  expect_bad_input(file, {"buffer view 0", "past the end of buffer 0"});
}

TEST(BadInput, AccessorPastItsBufferView) {
  SkinnedFixture f;
  f.accessor(f.normals)["byteOffset"] = 4;
  std::string file = path_in("accessor_past_view", "accessor.glb");
  f.write_glb(file);
  expect_bad_input(file, {"accessor 1 reads past the end of buffer view 1"});
  SkinnedFixture g;
  g.accessor(g.times)["count"] = 3;
  g.write_glb(file);
  expect_bad_input(file, {"accessor 6 reads past the end of buffer view 6"});
  SkinnedFixture h;
  h.accessor(h.positions)["byteOffset"] = UINT64_MAX - 3;
  h.write_glb(file);
  expect_bad_input(file, {"accessor 0 reads past the end of buffer view 0"});
}

TEST(BadInput, AbsurdCounts) {
  SkinnedFixture f;
  f.accessor(f.positions)["count"] = 1000000000;
  std::string file = path_in("absurd", "absurd.glb");
  f.write_glb(file);
  expect_bad_input(file, {"accessor 0", "1000000000", "absurd"});
  SkinnedFixture g;
  g.accessor(g.times)["count"] = UINT64_MAX;
  g.write_glb(file);
  expect_bad_input(file, {"accessor 6", "absurd"});
  // A buffer that claims more than a character could need.
  SkinnedFixture h;
  h.json["buffers"] = {{{"byteLength", uint64_t(1) << 40}}};
  h.write_glb(file);
  expect_bad_input(file, {"buffer 0"});
}

}  // namespace
}  // namespace crowdprof::test
