// The README's figures (made by docs/figures.sh) are this build's: the work of
// a frame it quotes, its digest and counters, is deterministic, so this build
// must do exactly that work (issue 26 item 5). Timings are not checked: they
// belong to the machine and the load the README names.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "test_support.h"

namespace crowdprof::test {
namespace {

std::string readme_figures() {
  std::ifstream in(source_dir() / "README.md");
  std::stringstream text;
  text << in.rdbuf();
  std::string all = text.str();
  size_t begin = all.find("<!-- figures:begin"), end = all.find("<!-- figures:end -->");
  if (begin == std::string::npos || end == std::string::npos || end < begin) return {};
  return all.substr(begin, end - begin);
}

TEST(ReadmeFigures, TheWorkOfAFrameIsThisBuilds) {
  std::string block = readme_figures();
  ASSERT_FALSE(block.empty()) << "README.md has no figures block: run ./setup.sh docs";
  std::smatch m;
  std::regex work(
      R"(updates\s+(\d+) poses and skins ([\d,]+) vertices a frame \((\d+) copies on\s+screen, (\d+) culled\), digest `([0-9a-f]{16})` on CPUs with AVX2 \(fused\s+multiply-adds\), `([0-9a-f]{16})` on SSE4 and below)");
  ASSERT_TRUE(std::regex_search(block, m, work)) << block;
  std::string vertices = m[2];
  vertices.erase(std::remove(vertices.begin(), vertices.end(), ','), vertices.end());

  auto dir = scratch_dir("readme_figures");
  std::string result_file = (dir / "work.json").string();
  auto r = run_cli("bench '" + (source_dir() / "scenes" / "humanoid.glb").string() +
                   "' -n 160 --mode threaded --backend none --frames 10 --warmup 0 -q --json '" + result_file + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream in(result_file);
  nlohmann::json result = nlohmann::json::parse(in);
  const nlohmann::json& c = result["counters"];
  EXPECT_EQ(std::to_string(c["poses_updated"].get<uint64_t>()), m[1].str());
  EXPECT_EQ(std::to_string(c["vertices_skinned"].get<uint64_t>()), vertices);
  EXPECT_EQ(std::to_string(c["copies_visible"].get<uint64_t>()), m[3].str());
  EXPECT_EQ(std::to_string(c["copies_culled"].get<uint64_t>()), m[4].str());
  // The digest of this machine's arithmetic (skinning_kernels.h).
  const bool fused = result["environment"]["fused_multiply_add"].get<bool>();
  EXPECT_EQ(result["digest"].get<std::string>(), fused ? m[5].str() : m[6].str())
      << "README.md's figures are not this build's: ./setup.sh docs";
  EXPECT_NE(block.find("load average"), std::string::npos) << "the figures say the load they ran under";
}

}  // namespace
}  // namespace crowdprof::test
