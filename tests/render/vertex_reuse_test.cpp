// Issue 52: triangles in vertex-cache order (--index-order optimized) make the
// GPU shade each vertex fewer times than the file's order, on the bundled
// humanoid and on the Khronos samples as they come, and draw the same image.
// Measured by the GL's own count (pipeline statistics), on llvmpipe in CI.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <memory>

#include "asset/vertex_order.h"
#include "measuring/gpu_passes.h"
#include "render_support.h"

using namespace crowdprof;
using namespace crowdprof::test;

namespace {

// The colour pass's vertex-shader invocations over the vertices it drew, in
// the last frame of a shot; NaN when the GL did not count them.
double invocations_per_vertex(GlContext& context, const Character& character, IndexOrder order) {
  Shot shot;
  shot.mode = "hwskin";
  shot.copies = 6;
  shot.frame = 3;
  shot.camera = "close";
  shot.index_order = order;
  const Frame frame = render(context, character, shot);
  for (const GpuTime& t : frame.gpu_times)
    if (t.frame == shot.frame && t.passes.has_stats() && frame.counters.vertices_drawn > 0)
      return t.passes.stats[static_cast<size_t>(GpuPass::Colour)]
                           [static_cast<size_t>(PipelineStat::VertexShaderInvocations)] /
             static_cast<double>(frame.counters.vertices_drawn);
  return std::nan("");
}

}  // namespace

TEST(VertexReuse, OptimizedOrderShadesNoMoreThanTheFilesAndTenPercentLessOnTheHumanoid) {
  OPEN_GL_OR_SKIP(context);
  std::vector<std::pair<std::string, const Character*>> characters = {{"humanoid", &default_humanoid()}};
  std::vector<std::unique_ptr<Character>> samples;
  if (have_samples()) {
    for (const char* file : {"CesiumMan/glTF-Binary/CesiumMan.glb", "Fox/glTF-Binary/Fox.glb",
                             "RiggedFigure/glTF-Binary/RiggedFigure.glb"}) {
      samples.push_back(std::make_unique<Character>(load_character(sample(file))));
      characters.emplace_back(file, samples.back().get());
    }
  } else {
    std::cout << "[ info ] sample characters not found at " << samples_dir().string()
              << ": checking the humanoid only\n";
  }
  for (const auto& [name, character] : characters) {
    const double file = invocations_per_vertex(*context, *character, IndexOrder::File);
    const double optimized = invocations_per_vertex(*context, *character, IndexOrder::Optimized);
    if (std::isnan(file)) GTEST_SKIP() << "this GL does not count vertex-shader invocations";
    std::cout << "[ info ] " << name << ": " << file << " invocations per vertex drawn in file order, " << optimized
              << " optimized\n";
    EXPECT_GE(file, 1.0) << name << ": each vertex drawn is shaded at least once";
    EXPECT_LE(optimized, file) << name;
    if (name == "humanoid") EXPECT_LE(optimized, 0.9 * file) << name;
  }
}

TEST(VertexReuse, BothOrdersDrawTheSameImage) {
  OPEN_GL_OR_SKIP(context);
  Shot shot;
  shot.mode = "hwskin";
  shot.camera = "close";
  shot.index_order = IndexOrder::File;
  const Frame file = render(*context, default_humanoid(), shot);
  shot.index_order = IndexOrder::Optimized;
  const Frame optimized = render(*context, default_humanoid(), shot);
  // Today's tolerance (gpu_modes_test.cpp): at most 0.05% of the pixels off
  // by more than 4 levels; equal depths may resolve the other way.
  const size_t pixels = file.rgba.size() / 4;
  ASSERT_GT(covered(file.rgba), pixels / 200) << "too little drawn to compare";
  EXPECT_LE(pixels_differing(file.rgba, optimized.rgba, 4) * 2000, pixels);
  EXPECT_EQ(file.digest, optimized.digest) << "the same palettes: only the triangles' order differs";
}

TEST(VertexReuse, CacheOrderKeepsEveryTriangleAndItsWinding) {
  const SkinnedMesh& mesh = default_humanoid().mesh;
  const std::vector<uint32_t> ordered = vertex_cache_order(mesh);
  ASSERT_EQ(ordered.size(), mesh.indices.size());
  // Each triangle as its rotation that starts at its smallest index: the same
  // triangle wound the same way compares equal.
  auto triangles = [](const std::vector<uint32_t>& indices) {
    std::vector<std::array<uint32_t, 3>> out;
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
      std::array<uint32_t, 3> tri = {indices[t], indices[t + 1], indices[t + 2]};
      while (tri[0] != std::min({tri[0], tri[1], tri[2]})) std::rotate(tri.begin(), tri.begin() + 1, tri.end());
      out.push_back(tri);
    }
    std::sort(out.begin(), out.end());
    return out;
  };
  EXPECT_EQ(triangles(ordered), triangles(mesh.indices));
  EXPECT_NE(ordered, mesh.indices) << "the humanoid's file order is not already cache order";
  const VertexCacheModel& nvidia = kVertexCacheModels[0];
  EXPECT_LT(analyze_vertex_cache(ordered, mesh.vertex_count(), nvidia).acmr,
            analyze_vertex_cache(mesh.indices, mesh.vertex_count(), nvidia).acmr);
}
