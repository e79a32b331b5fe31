// Bad input, part 4: corrupt KHR_draco_mesh_compression data, from a primitive
// encoded here and from a real sample. tiny_gltf trusts Draco's output (its
// decode writes up to 255 components into a 4-element array), so the loader must
// refuse such files before tiny_gltf sees them.
#include <cstring>
#include <filesystem>
#include <random>

#include <gtest/gtest.h>

#include "draco_fixture.h"
#include "loader_checks.h"

namespace crowdprof::test {
namespace {
namespace fs = std::filesystem;

std::string write(const GltfFixture& f, const std::string& test) {
  std::string file = (scratch_dir(test) / "character.glb").string();
  f.write_glb(file);
  return file;
}

TEST(BadDraco, FixtureDecodes) {
  // The corruptions below start from a file that loads.
  GltfAsset asset = load_gltf(write(DracoFixture(), "draco_ok"));
  ASSERT_EQ(asset.characters.size(), 1u);
  EXPECT_TRUE(asset.draco_decoded);
  EXPECT_EQ(asset.characters[0].mesh.vertex_count(), 6u);
  EXPECT_EQ(asset.characters[0].mesh.triangle_count(), 4u);
}

TEST(BadDraco, ZeroedHeader) {
  DracoFixture f;
  std::memset(f.draco_bytes(), 0, 16);
  expect_bad_input(write(f, "draco_zeroed"), {"mesh 0 primitive 0", "corrupt Draco data"});
}

TEST(BadDraco, Truncated) {
  DracoFixture f;
  f.json["bufferViews"][static_cast<size_t>(f.draco_view)]["byteLength"] = f.draco_size() / 2;
  expect_bad_input(write(f, "draco_truncated"), {"mesh 0 primitive 0", "corrupt Draco data"});
}

TEST(BadDraco, AttributeIdNotInData) {
  DracoFixture f;
  f.json["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["NORMAL"] = 9;
  expect_bad_input(write(f, "draco_attribute"), {"mesh 0 primitive 0", "no attribute 9", "NORMAL"});
}

TEST(BadDraco, ComponentsDisagreeWithAccessor) {
  // Draco decodes NORMAL as 3 components; an accessor of 4 would be read as garbage.
  DracoFixture f;
  f.accessor(f.normals)["type"] = "VEC4";
  expect_bad_input(write(f, "draco_components"), {"mesh 0 primitive 0", "NORMAL", "3 components"});
  DracoFixture g;
  g.accessor(g.positions)["type"] = "MAT4";
  expect_bad_input(write(g, "draco_mat4"), {"mesh 0 primitive 0", "POSITION"});
}

TEST(BadDraco, IndexComponentTypeInvalid) {
  // tiny_gltf sizes the decoded indices by this type: 5127 has no size.
  DracoFixture f;
  f.accessor(f.indices)["componentType"] = 5127;
  expect_bad_input(write(f, "draco_index_type"), {"accessor 4", "component type 5127"});
}

TEST(BadDraco, ViewPastBuffer) {
  DracoFixture f;
  f.json["bufferViews"][static_cast<size_t>(f.draco_view)]["byteOffset"] = UINT64_MAX - 15;
  expect_bad_input(write(f, "draco_view"), {"past the end of buffer 0"});
}

TEST(BadDraco, RandomDamageNeverCrashes) {
  // Flipped bytes may still decode; then the result must pass every other check.
  DracoFixture clean;
  std::mt19937 random(7);
  for (int round = 0; round < 60; ++round) {
    DracoFixture f = clean;
    std::uniform_int_distribution<size_t> at(0, f.draco_size() - 1);
    for (int flips = 0; flips < 1 + round % 4; ++flips)
      f.draco_bytes()[at(random)] ^= static_cast<unsigned char>(1 + random() % 255);
    std::string file = write(f, "draco_random");
    try {
      load_gltf(file);
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << "round " << round << ": not an InputError: " << e.what();
    }
  }
}

TEST(BadDraco, CorruptSample) {
  CROWDPROF_REQUIRE_SAMPLES();
  fs::path source = samples_dir() / "RiggedSimple" / "glTF-Draco";
  fs::path dir = scratch_dir("draco_sample");
  for (const char* name : {"RiggedSimple.gltf", "RiggedSimple0.bin"}) {
    fs::copy_file(source / name, dir / name);
    fs::permissions(dir / name, fs::perms::owner_write, fs::perm_options::add);
  }
  std::string file = (dir / "RiggedSimple.gltf").string();
  ASSERT_NO_THROW(load_gltf(file));
  nlohmann::json json = nlohmann::json::parse(std::ifstream(file));
  size_t view = json["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"];
  size_t offset = json["bufferViews"][view].value("byteOffset", size_t(0));
  std::fstream bin(dir / "RiggedSimple0.bin", std::ios::in | std::ios::out | std::ios::binary);
  bin.seekp(static_cast<std::streamoff>(offset));
  bin.write("\0\0\0\0\0\0\0\0\0\0\0\0", 12);
  bin.close();
  expect_bad_input(file, {"mesh 0 primitive 0", "corrupt Draco data"});
}

}  // namespace
}  // namespace crowdprof::test
