// info's joint tree (lib/asset/asset_report.h): every joint named with its
// parent in JSON, and in text indented under its parent, so that a user can
// pick the joint a layer's mask starts at.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "asset/asset_report.h"
#include "test_support.h"

namespace crowdprof {
namespace {

TEST(JointTree, InfoNamesEveryJointUnderItsParent) {
  const GltfAsset asset = load_gltf((test::source_dir() / "scenes" / "humanoid.glb").string());
  const Skeleton& skeleton = asset.characters.at(0).skeleton;
  const nlohmann::json tree = describe_asset(asset)["characters"][0]["joint_tree"];
  ASSERT_EQ(tree.size(), skeleton.joint_count());
  for (size_t j = 0; j < skeleton.joint_count(); ++j) {
    EXPECT_EQ(tree[j]["name"], skeleton.names[j]);
    EXPECT_EQ(tree[j]["parent"], skeleton.parents[j]);
  }
  // In text, after its heading, each joint two spaces deeper than its parent.
  const std::string text = format_asset(asset);
  const size_t heading = text.find("  joint tree:");
  ASSERT_NE(heading, std::string::npos) << text;
  std::istringstream lines(text.substr(text.find('\n', heading) + 1));
  std::vector<size_t> indent;
  std::string line;
  for (size_t j = 0; j < skeleton.joint_count() && std::getline(lines, line); ++j) {
    const size_t spaces = line.find_first_not_of(' ');
    EXPECT_EQ(line.substr(spaces), skeleton.names[j]);
    indent.push_back(spaces);
    const int parent = skeleton.parents[j];
    EXPECT_EQ(spaces, parent < 0 ? 4 : indent[static_cast<size_t>(parent)] + 2) << skeleton.names[j];
  }
  EXPECT_EQ(indent.size(), skeleton.joint_count());
}

}  // namespace
}  // namespace crowdprof
