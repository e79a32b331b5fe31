// A small, deterministic fuzz of the loader: valid fixtures damaged at random
// (bytes flipped, files cut short, JSON values swapped for hostile ones) must load
// or be refused with one InputError; never crash, hang or throw anything else.
// The fast tests run in CI; the DISABLED_ one runs many more rounds, for a build
// with -fsanitize=address,undefined (see docs/errors.md).
#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>

#include <gtest/gtest.h>

#include "draco_fixture.h"
#include "loader_checks.h"

namespace crowdprof::test {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

std::vector<unsigned char> read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Loads `file`; fails the test unless it loads or throws a one-line InputError in time.
void expect_loads_or_refuses(const std::string& file, const std::string& round) {
  auto start = std::chrono::steady_clock::now();
  try {
    load_gltf(file);
  } catch (const InputError& e) {
    std::string what = e.what();
    EXPECT_EQ(what.rfind(file + ": ", 0), 0u) << round << ": " << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << round << ": " << what;
  } catch (const std::exception& e) {
    ADD_FAILURE() << round << ": threw something other than InputError: " << e.what();
  }
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 5.0) << round << ": a tiny file took " << seconds << " s";
}

// Raw damage to a whole GLB: flipped bytes, or the file cut short.
void fuzz_bytes(const GltfFixture& fixture, const std::string& name, int rounds) {
  fs::path dir = scratch_dir("fuzz_" + name);
  fixture.write_glb(dir / "clean.glb");
  std::vector<unsigned char> clean = read_all(dir / "clean.glb");
  std::mt19937 random(1234);
  for (int round = 0; round < rounds; ++round) {
    std::vector<unsigned char> bytes = clean;
    if (round % 5 == 4) {
      bytes.resize(random() % bytes.size());
    } else {
      for (auto flips = 1 + random() % 8; flips > 0; --flips)
        bytes[random() % bytes.size()] ^= static_cast<unsigned char>(1 + random() % 255);
    }
    fs::path file = dir / "damaged.glb";
    write_file(file, bytes.data(), bytes.size());
    expect_loads_or_refuses(file.string(), name + " byte round " + std::to_string(round));
    if (::testing::Test::HasFailure()) return;
  }
}

void leaves(const json& value, const json::json_pointer& at, std::vector<json::json_pointer>& out) {
  if (value.is_object()) {
    for (auto& [key, child] : value.items()) leaves(child, at / key, out);
  } else if (value.is_array() && value.size() <= 64) {  // not into long number lists
    for (size_t i = 0; i < value.size(); ++i) leaves(value[i], at / i, out);
  }
  out.push_back(at);
}

// Structured damage: JSON values (indices, counts, offsets, names) replaced by
// the values that break loaders, one to three at a time; the BIN chunk intact.
void fuzz_json(const GltfFixture& fixture, const std::string& name, int rounds) {
  static const json hostile[] = {-1,
                                 0,
                                 1,
                                 2,
                                 3,
                                 7,
                                 255,
                                 65536,
                                 int64_t(1) << 31,
                                 int64_t(1) << 32,
                                 uint64_t(1) << 63,
                                 UINT64_MAX,
                                 -9007199254740993LL,
                                 0.5,
                                 1e308,
                                 -1e308,
                                 "",
                                 "x",
                                 "CUBICSPLINE",
                                 "weights",
                                 "VEC2",
                                 "MAT4",
                                 nullptr,
                                 true,
                                 json::array(),
                                 json::object(),
                                 json::array({0, 0}),
                                 json::array({1e39, 0, 0})};
  std::vector<json::json_pointer> paths;
  leaves(fixture.json, json::json_pointer(), paths);
  fs::path dir = scratch_dir("fuzz_json_" + name);
  std::mt19937 random(99);
  for (int round = 0; round < rounds; ++round) {
    GltfFixture damaged = fixture;
    std::string what;
    for (auto edits = 1 + random() % 3; edits > 0; --edits) {
      const json::json_pointer& at = paths[random() % paths.size()];
      if (at.empty() || !damaged.json.contains(at)) continue;
      if (random() % 6 == 0) {
        json& parent = damaged.json[at.parent_pointer()];
        if (parent.is_object()) parent.erase(at.back());
        what.append(" erase ").append(at.to_string());
      } else {
        const json& value = hostile[random() % std::size(hostile)];
        damaged.json[at] = value;
        what.append(" ")
            .append(at.to_string())
            .append("=")
            .append(value.dump());  // not "+": GCC 12 -Wrestrict false alarm
      }
    }
    fs::path file = dir / "damaged.glb";
    damaged.write_glb(file);
    expect_loads_or_refuses(file.string(), name + " json round " + std::to_string(round) + ":" + what);
    if (::testing::Test::HasFailure()) return;
  }
}

TEST(LoaderFuzz, DamagedBytes) {
  fuzz_bytes(SkinnedFixture(), "plain", 300);
  fuzz_bytes(DracoFixture(), "draco", 200);
}

TEST(LoaderFuzz, HostileJsonValues) {
  fuzz_json(SkinnedFixture(), "plain", 400);
  fuzz_json(DracoFixture(), "draco", 200);
}

TEST(LoaderFuzz, DISABLED_Long) {
  fuzz_bytes(SkinnedFixture(), "plain_long", 20000);
  fuzz_bytes(DracoFixture(), "draco_long", 20000);
  fuzz_json(SkinnedFixture(), "plain_long", 20000);
  fuzz_json(DracoFixture(), "draco_long", 20000);
}

}  // namespace
}  // namespace crowdprof::test
