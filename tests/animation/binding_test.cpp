// Channel bindings: RNA-style path strings, their parser and linear name
// search (the BGE's per-frame lookup), and the bundled lookup done once.
#include <gtest/gtest.h>

#include "animation/binding.h"

namespace crowdprof {
namespace {

Skeleton skeleton_named(std::vector<std::string> names) {
  Skeleton s;
  s.names = std::move(names);
  for (size_t j = 0; j < s.names.size(); ++j) s.parents.push_back(static_cast<int>(j) - 1);
  return s;
}

Channel channel(int joint, ChannelPath path) {
  Channel c;
  c.joint = joint;
  c.path = path;
  c.times = {0.0f};
  c.values.assign(static_cast<size_t>(c.components()), 0.0f);
  return c;
}

TEST(Binding, PathsNameBoneAndProperty) {
  const Skeleton s = skeleton_named({"Hips", "Spine"});
  EXPECT_EQ(channel_path(s, channel(0, ChannelPath::Translation)), "pose.bones[\"Hips\"].location");
  EXPECT_EQ(channel_path(s, channel(1, ChannelPath::Rotation)), "pose.bones[\"Spine\"].rotation_quaternion");
  EXPECT_EQ(channel_path(s, channel(1, ChannelPath::Scale)), "pose.bones[\"Spine\"].scale");
  EXPECT_EQ(channel_path(s, channel(2, ChannelPath::Scale)), "");  // no such joint
  EXPECT_EQ(channel_path(s, channel(-1, ChannelPath::Scale)), "");
}

TEST(Binding, ResolvesBoneAndProperty) {
  const Skeleton s = skeleton_named({"Hips", "Spine", "Spine.001"});
  ChannelPath property = ChannelPath::Translation;
  EXPECT_EQ(resolve_channel_path(s, "pose.bones[\"Spine\"].rotation_quaternion", &property), 1);
  EXPECT_EQ(property, ChannelPath::Rotation);
  EXPECT_EQ(resolve_channel_path(s, "pose.bones[\"Spine.001\"].scale", &property), 2);
  EXPECT_EQ(property, ChannelPath::Scale);
  EXPECT_EQ(resolve_channel_path(s, "pose.bones[\"Hips\"].location", &property), 0);
  EXPECT_EQ(property, ChannelPath::Translation);
  EXPECT_EQ(resolve_channel_path(s, "pose.bones[\"Hips\"].location", nullptr), 0);
}

TEST(Binding, UnknownBoneOrPropertyIsNotFound) {
  const Skeleton s = skeleton_named({"Hips", "Spine"});
  ChannelPath property = ChannelPath::Scale;
  EXPECT_EQ(resolve_channel_path(s, "pose.bones[\"Head\"].location", &property), -1);
  // A prefix or an extension of a name is a different name.
  EXPECT_EQ(resolve_channel_path(s, "pose.bones[\"Hip\"].location", &property), -1);
  EXPECT_EQ(resolve_channel_path(s, "pose.bones[\"Hips2\"].location", &property), -1);
  EXPECT_EQ(resolve_channel_path(s, "pose.bones[\"hips\"].location", &property), -1);
  EXPECT_EQ(resolve_channel_path(s, "pose.bones[\"Hips\"].rotation_euler", &property), -1);
  EXPECT_EQ(resolve_channel_path(s, "pose.bones[\"Hips\"].Location", &property), -1);
  EXPECT_EQ(property, ChannelPath::Scale);  // untouched when not found
  EXPECT_EQ(resolve_channel_path(skeleton_named({}), "pose.bones[\"Hips\"].location", nullptr), -1);
}

TEST(Binding, MalformedPathsAreNotFound) {
  const Skeleton s = skeleton_named({"Hips", ""});
  for (const char* path : {
           "", "pose.bones",
           "pose.bones[\"Hips",                // no closing quote
           "pose.bones[\"Hips\"",              // no closing bracket
           "pose.bones[\"Hips\"]",             // no property
           "pose.bones[\"Hips\"].",            // empty property
           "pose.bones[\"Hips\"]location",     // no dot
           "pose.bones[\"Hips\"].location.x",  // trailing text
           "pose.bones[\"Hips\"].location ",   // trailing space
           "pose.bones[Hips].location",        // unquoted
           "pose.bones['Hips'].location",      // other quotes
           "object.bones[\"Hips\"].location",  // other prefix
           " pose.bones[\"Hips\"].location",   // leading space
           "pose.bones[\"Hi\\ps\"].location",  // escape of a plain character
           "pose.bones[\"Hips\\",              // escape at the end
       }) {
    EXPECT_EQ(resolve_channel_path(s, path, nullptr), -1) << path;
  }
  // The empty name is a name like any other.
  EXPECT_EQ(resolve_channel_path(s, "pose.bones[\"\"].scale", nullptr), 1);
}

TEST(Binding, NamesWithQuotesBracketsAndBackslashesRoundTrip) {
  const Skeleton s = skeleton_named({"Arm\"L", "a]b[\"c", "back\\slash", "\\\"", "x\"].location", "Arm", "ünïcödé 名"});
  for (int j = 0; j < static_cast<int>(s.names.size()); ++j) {
    for (ChannelPath path : {ChannelPath::Translation, ChannelPath::Rotation, ChannelPath::Scale}) {
      const std::string text = channel_path(s, channel(j, path));
      ChannelPath property{};
      EXPECT_EQ(resolve_channel_path(s, text, &property), j) << text;
      EXPECT_EQ(property, path) << text;
    }
  }
  EXPECT_EQ(channel_path(s, channel(0, ChannelPath::Scale)), "pose.bones[\"Arm\\\"L\"].scale");
  EXPECT_EQ(channel_path(s, channel(2, ChannelPath::Scale)), "pose.bones[\"back\\\\slash\"].scale");
  // An unescaped quote ends the name: what follows must be "].
  EXPECT_EQ(resolve_channel_path(s, "pose.bones[\"Arm\"L\"].scale", nullptr), -1);
}

TEST(Binding, DuplicateNamesResolveToTheFirstBothWays) {
  const Skeleton s = skeleton_named({"Bone", "Other", "Bone"});
  Action action;
  action.channels = {channel(0, ChannelPath::Rotation), channel(2, ChannelPath::Rotation)};
  const ActionBindings bindings = bind_action(s, action);
  EXPECT_EQ(bindings.targets, (std::vector<int32_t>{0, 0}));
  std::vector<int32_t> targets(2, 99);
  ASSERT_TRUE((ResolvePathsJob{&s, &bindings, targets, nullptr}.Run()));
  EXPECT_EQ(targets, bindings.targets);
}

TEST(Binding, BindActionResolvesEveryChannelOnce) {
  const Skeleton s = skeleton_named({"Hips", "Spine", "Head"});
  Action action;
  action.channels = {channel(2, ChannelPath::Rotation), channel(0, ChannelPath::Translation),
                     channel(1, ChannelPath::Scale), channel(7, ChannelPath::Scale)};
  const ActionBindings bindings = bind_action(s, action);
  ASSERT_EQ(bindings.paths.size(), 4u);
  EXPECT_EQ(bindings.paths[0], "pose.bones[\"Head\"].rotation_quaternion");
  EXPECT_EQ(bindings.targets, (std::vector<int32_t>{2, 0, 1, -1}));
}

TEST(Binding, ResolvePathsJobLooksUpEveryPathAndCountsIt) {
  const Skeleton s = skeleton_named({"Hips", "Spine", "Head"});
  Action action;
  action.channels = {channel(2, ChannelPath::Rotation), channel(0, ChannelPath::Translation),
                     channel(1, ChannelPath::Scale)};
  const ActionBindings bindings = bind_action(s, action);
  std::vector<int32_t> targets(3, -7);
  size_t lookups = 5;
  ResolvePathsJob job{&s, &bindings, targets, &lookups};
  ASSERT_TRUE(job.Run());
  EXPECT_EQ(targets, bindings.targets);
  EXPECT_EQ(lookups, 8u);  // added to, not reset: one counter serves a whole frame
  ASSERT_TRUE(job.Run());
  EXPECT_EQ(lookups, 11u);

  // A skeleton renamed after binding: the per-frame lookup sees it, the bundled
  // one does not (the price of resolving once).
  Skeleton renamed = s;
  renamed.names[2] = "Neck";
  ASSERT_TRUE((ResolvePathsJob{&renamed, &bindings, targets, &lookups}.Run()));
  EXPECT_EQ(targets, (std::vector<int32_t>{-1, 0, 1}));
}

TEST(Binding, ResolvePathsJobValidates) {
  const Skeleton s = skeleton_named({"Hips"});
  Action action;
  action.channels = {channel(0, ChannelPath::Rotation)};
  const ActionBindings bindings = bind_action(s, action);
  std::vector<int32_t> too_few;
  size_t lookups = 0;
  EXPECT_FALSE((ResolvePathsJob{&s, &bindings, too_few, &lookups}.Run()));
  std::vector<int32_t> targets(1);
  EXPECT_FALSE((ResolvePathsJob{nullptr, &bindings, targets, &lookups}.Run()));
  EXPECT_FALSE((ResolvePathsJob{&s, nullptr, targets, &lookups}.Run()));
  EXPECT_EQ(lookups, 0u);
}

}  // namespace
}  // namespace crowdprof
