// Sampling: STEP, LINEAR and CUBICSPLINE against values worked out by hand, the
// cursor against time going backwards and looping, and InterpolationTest.glb.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>

#include <gtest/gtest.h>
#include <glm/gtc/quaternion.hpp>

#include "animation/sampling.h"
#include "asset/gltf_loader.h"

namespace crowdprof {
namespace {

Channel channel(int joint, ChannelPath path, Interpolation interpolation, std::vector<float> times,
                std::vector<float> values) {
  Channel c;
  c.joint = joint;
  c.path = path;
  c.interpolation = interpolation;
  c.times = std::move(times);
  c.values = std::move(values);
  return c;
}

Action action_of(std::vector<Channel> channels) {
  Action a;
  a.start = 1e30f;
  a.end = -1e30f;
  for (const Channel& c : channels) {
    a.start = std::min(a.start, c.times.front());
    a.end = std::max(a.end, c.times.back());
  }
  a.channels = std::move(channels);
  return a;
}

// One joint per channel, channel i driving joint i, poses starting at zero.
struct Sampler {
  explicit Sampler(Action a) : action(std::move(a)) {
    for (size_t i = 0; i < action.channels.size(); ++i) targets.push_back(static_cast<int32_t>(i));
    reset_cursor(action, &cursor);
    const size_t n = action.channels.size();
    pose.translations.assign(n, glm::vec3(0.0f));
    pose.rotations.assign(n, glm::quat(1.0f, 0.0f, 0.0f, 0.0f));
    pose.scales.assign(n, glm::vec3(0.0f));
  }
  bool at(float time) { return SamplingJob{&action, time, targets, &cursor, &pose}.Run(); }
  glm::vec3 translation(float time, size_t joint = 0) {
    EXPECT_TRUE(at(time));
    return pose.translations[joint];
  }
  glm::quat rotation(float time, size_t joint = 0) {
    EXPECT_TRUE(at(time));
    return pose.rotations[joint];
  }
  Action action;
  std::vector<int32_t> targets;
  SamplingCursor cursor;
  LocalPose pose;
};

void expect_near(glm::vec3 actual, glm::vec3 expected, float tolerance = 1e-6f) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

void expect_near(glm::quat actual, glm::vec4 xyzw, float tolerance = 1e-6f) {
  EXPECT_NEAR(actual.x, xyzw.x, tolerance);
  EXPECT_NEAR(actual.y, xyzw.y, tolerance);
  EXPECT_NEAR(actual.z, xyzw.z, tolerance);
  EXPECT_NEAR(actual.w, xyzw.w, tolerance);
}

const float kS22 = std::sin(glm::radians(22.5f));  // half-angles of 45 degree rotations
const float kC22 = std::cos(glm::radians(22.5f));
const float kHalf = std::sqrt(0.5f);

TEST(Sampling, StepHoldsEachKeyUntilTheNext) {
  Sampler s(action_of(
      {channel(0, ChannelPath::Translation, Interpolation::Step, {0, 1, 2}, {0, 0, 0, 10, 20, 30, 5, 5, 5})}));
  expect_near(s.translation(0.0f), {0, 0, 0});
  expect_near(s.translation(0.99f), {0, 0, 0});
  expect_near(s.translation(1.0f), {10, 20, 30});
  expect_near(s.translation(1.99f), {10, 20, 30});
  expect_near(s.translation(2.0f), {5, 5, 5});
}

TEST(Sampling, LinearTranslationAndScale) {
  Sampler s(action_of({channel(0, ChannelPath::Translation, Interpolation::Linear, {0, 2}, {0, 0, 0, 10, 20, 30}),
                       channel(1, ChannelPath::Scale, Interpolation::Linear, {0, 2}, {1, 1, 1, 3, 5, 1})}));
  expect_near(s.translation(0.5f), {2.5f, 5.0f, 7.5f});
  expect_near(s.pose.scales[1], {1.5f, 2.0f, 1.0f});
  expect_near(s.translation(2.0f), {10, 20, 30});
}

TEST(Sampling, LinearRotationIsSlerp) {
  // Identity to 90 degrees about z: halfway is 45 degrees, (0, 0, sin 22.5, cos 22.5).
  Sampler s(
      action_of({channel(0, ChannelPath::Rotation, Interpolation::Linear, {0, 1}, {0, 0, 0, 1, 0, 0, kHalf, kHalf})}));
  expect_near(s.rotation(0.5f), {0, 0, kS22, kC22});
  // A quarter of the way is 22.5 degrees: slerp, not a normalised lerp, gets this.
  const float s11 = std::sin(glm::radians(11.25f)), c11 = std::cos(glm::radians(11.25f));
  expect_near(s.rotation(0.25f), {0, 0, s11, c11});
}

TEST(Sampling, LinearRotationTakesTheShorterArc) {
  // The second key stored as -q: the same rotation, the far side of the sphere.
  Sampler s(action_of(
      {channel(0, ChannelPath::Rotation, Interpolation::Linear, {0, 1}, {0, 0, 0, 1, 0, 0, -kHalf, -kHalf})}));
  expect_near(s.rotation(0.5f), {0, 0, kS22, kC22});
}

// slerp in double precision, the reference for slerp_shortest.
glm::dvec4 exact_slerp(glm::dvec4 a, glm::dvec4 b, double t) {
  double d = glm::dot(a, b);
  if (d < 0) b = -b, d = -d;
  const double angle = std::acos(std::min(d, 1.0));
  if (angle < 1e-12) return a;
  return (a * std::sin((1 - t) * angle) + b * std::sin(t * angle)) / std::sin(angle);
}

TEST(Sampling, SlerpMatchesExactSlerpAtAllKeySpacings) {
  // Key spacings from a fraction of a degree (where nlerp stands in for slerp)
  // to 179 degrees: within 2e-6 everywhere, well under the 1e-5 a fast path may
  // cost at the 24-60 fps spacings of real animation. The bound leaves room
  // for what a compiler fuses (GCC or clang, -O1 or -O3, with or without
  // -march=native): it must hold whichever.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  double worst = 0;
  for (double degrees : {0.05, 0.5, 1.0, 3.0, 5.0, 5.2, 8.0, 15.0, 45.0, 90.0, 179.0}) {
    for (int trial = 0; trial < 20; ++trial) {
      const glm::dvec3 axis = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)));
      const glm::dquat a = glm::normalize(glm::dquat(u(rng), u(rng), u(rng), u(rng)));
      const glm::dquat b = glm::angleAxis(glm::radians(degrees), axis) * a;
      for (int step = 0; step <= 16; ++step) {
        const double t = step / 16.0;
        const glm::quat got = slerp_shortest(glm::quat(a), glm::quat(b), static_cast<float>(t));
        const glm::dvec4 want = exact_slerp({a.x, a.y, a.z, a.w}, {b.x, b.y, b.z, b.w}, t);
        for (int k = 0; k < 4; ++k) worst = std::max(worst, std::abs(double(got[k]) - want[k]));
      }
    }
  }
  EXPECT_LT(worst, 2e-6);
}

// A LINEAR rotation channel of `keys` keys, each the last turned by a random
// angle (up to `max_degrees`) about a random axis, stored as q or -q at random.
Channel random_rotations(std::mt19937* rng, int keys, double max_degrees) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<float> times, values;
  glm::dquat q = glm::normalize(glm::dquat(u(*rng), u(*rng), u(*rng), u(*rng)));
  for (int k = 0; k < keys; ++k) {
    times.push_back(0.25f * static_cast<float>(k));
    const glm::dquat stored = u(*rng) < 0 ? -q : q;
    values.insert(values.end(), {float(stored.x), float(stored.y), float(stored.z), float(stored.w)});
    const glm::dvec3 axis = glm::normalize(glm::dvec3(u(*rng), u(*rng), u(*rng)));
    q = glm::normalize(glm::angleAxis(glm::radians(max_degrees * (u(*rng) + 1) / 2), axis) * q);
  }
  return channel(0, ChannelPath::Rotation, Interpolation::Linear, std::move(times), std::move(values));
}

TEST(Sampling, PreparedSlerpGivesTheSameBits) {
  // The key pair's half of slerp worked out once at load (prepare_slerp) must
  // sample to exactly what the whole slerp gives per sample: digests depend on it.
  std::mt19937 rng(11);
  for (double max_degrees : {2.0, 12.0, 90.0, 360.0}) {
    Channel c = random_rotations(&rng, 64, max_degrees);
    Sampler whole(action_of({c}));
    prepare_slerp(&c);
    ASSERT_EQ(c.slerp.size(), c.times.size() - 1);
    Sampler prepared(action_of({c}));
    for (int step = 0; step <= 63 * 16; ++step) {
      const float time = 0.25f * static_cast<float>(step) / 16.0f + 0.003f;
      const glm::quat want = whole.rotation(time), got = prepared.rotation(time);
      ASSERT_EQ(std::memcmp(&want, &got, sizeof(glm::quat)), 0)
          << max_degrees << " degrees at most, t " << time << ": " << got.x << " " << got.y << " " << got.z << " "
          << got.w << " against " << want.x << " " << want.y << " " << want.z << " " << want.w;
    }
  }
  // Between them the channels took every branch: the shorter-arc flip, nlerp, slerp.
  Channel c = random_rotations(&rng, 256, 30.0);
  prepare_slerp(&c);
  size_t flips = 0, nlerps = 0;
  for (const SlerpSegment& s : c.slerp) flips += s.flip, nlerps += s.nlerp;
  EXPECT_GT(flips, 0u);
  EXPECT_GT(nlerps, 0u);
  EXPECT_LT(nlerps, c.slerp.size());
}

TEST(Sampling, PrepareSlerpOnlyForLinearRotations) {
  Channel c = channel(0, ChannelPath::Rotation, Interpolation::Step, {0, 1}, {0, 0, 0, 1, 0, 0, kHalf, kHalf});
  prepare_slerp(&c);
  EXPECT_TRUE(c.slerp.empty());
  c.interpolation = Interpolation::Linear;
  prepare_slerp(&c);
  ASSERT_EQ(c.slerp.size(), 1u);
  EXPECT_FALSE(c.slerp[0].flip);
  EXPECT_FALSE(c.slerp[0].nlerp);
  EXPECT_FLOAT_EQ(c.slerp[0].angle, glm::radians(45.0f));  // half of the 90 degree turn
  Channel t = channel(0, ChannelPath::Translation, Interpolation::Linear, {0, 1}, {0, 0, 0, 1, 1, 1});
  prepare_slerp(&t);
  EXPECT_TRUE(t.slerp.empty());
  Channel one = channel(0, ChannelPath::Rotation, Interpolation::Linear, {0}, {0, 0, 0, 1});
  prepare_slerp(&one);
  EXPECT_TRUE(one.slerp.empty());
}

TEST(Sampling, ValidateRefusesStalePreparedSlerp) {
  Channel c = channel(0, ChannelPath::Rotation, Interpolation::Linear, {0, 1}, {0, 0, 0, 1, 0, 0, kHalf, kHalf});
  prepare_slerp(&c);
  Sampler s(action_of({c}));
  EXPECT_TRUE(s.at(0.5f));
  s.action.channels[0].slerp.push_back({});  // one segment more than the keys have
  EXPECT_FALSE(s.at(0.5f));
  s.action.channels[0].slerp.pop_back();
  s.action.channels[0].interpolation = Interpolation::Step;  // prepared for LINEAR only
  EXPECT_FALSE(s.at(0.5f));
}

TEST(Sampling, LoaderPreparesLinearRotations) {
  const std::string file = std::string(CROWDPROF_SAMPLES_DIR) + "/Fox/glTF-Binary/Fox.glb";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "sample not found: " << file;
  const GltfAsset asset = load_gltf(file);
  ASSERT_FALSE(asset.characters.empty());
  size_t prepared = 0;
  for (const Action& action : asset.characters[0].actions)
    for (const Channel& c : action.channels) {
      const bool slerps = c.path == ChannelPath::Rotation && c.interpolation == Interpolation::Linear;
      EXPECT_EQ(c.slerp.size(), slerps ? c.times.size() - 1 : 0u);
      prepared += c.slerp.size();
    }
  EXPECT_GT(prepared, 0u);
}

TEST(Sampling, CubicSplineIsGltfHermite) {
  // Keys at t = 0 and 2 with values 1 and 3, out-tangent 1 and in-tangent -1; the
  // tangents scale by the 2 s interval. At s = 0.5: h00 = h01 = 0.5, h10 = 0.125,
  // h11 = -0.125, so 0.5 + 0.125*2*1 + 1.5 + (-0.125)*2*(-1) = 2.5. At s = 0.25:
  // h00 = 0.84375, h10 = 0.140625, h01 = 0.15625, h11 = -0.046875, so
  // 0.84375 + 0.28125 + 0.46875 + 0.09375 = 1.6875.
  Sampler s(action_of({channel(0, ChannelPath::Translation, Interpolation::CubicSpline, {0, 2},
                               {/*in*/ 0, 0, 0, /*value*/ 1, 1, 1, /*out*/ 1, 1, 1,
                                /*in*/ -1, -1, -1, /*value*/ 3, 3, 3, /*out*/ 0, 0, 0})}));
  expect_near(s.translation(1.0f), glm::vec3(2.5f), 1e-5f);
  expect_near(s.translation(0.5f), glm::vec3(1.6875f), 1e-5f);
  expect_near(s.translation(0.0f), glm::vec3(1.0f));
  expect_near(s.translation(2.0f), glm::vec3(3.0f));
}

TEST(Sampling, CubicSplineRotationIsNormalised) {
  // Zero tangents, identity to 90 degrees about z: at s = 0.5 the spline gives
  // (0, 0, 0.5 sin 45, 0.5 + 0.5 cos 45), which normalises to exactly 45 degrees.
  Sampler s(action_of({channel(0, ChannelPath::Rotation, Interpolation::CubicSpline, {0, 1},
                               {0, 0, 0, 0, 0, 0, 0,     1,     0, 0, 0, 0,  //
                                0, 0, 0, 0, 0, 0, kHalf, kHalf, 0, 0, 0, 0})}));
  expect_near(s.rotation(0.5f), {0, 0, kS22, kC22}, 1e-6f);
}

TEST(Sampling, FirstValueBeforeFirstKeyAndLastAfterLast) {
  // The action runs 0..4 but this channel's keys run 1..3.
  Action a = action_of({channel(0, ChannelPath::Translation, Interpolation::Linear, {1, 3}, {1, 1, 1, 3, 3, 3}),
                        channel(1, ChannelPath::Scale, Interpolation::Linear, {0, 4}, {0, 0, 0, 4, 4, 4})});
  Sampler s(a);
  expect_near(s.translation(0.5f), glm::vec3(1.0f));
  expect_near(s.translation(3.5f), glm::vec3(3.0f));
  // Times outside the action clamp to it.
  expect_near(s.translation(-10.0f), glm::vec3(1.0f));
  expect_near(s.pose.scales[1], glm::vec3(0.0f));
  expect_near(s.translation(10.0f), glm::vec3(3.0f));
  expect_near(s.pose.scales[1], glm::vec3(4.0f));
}

TEST(Sampling, SingleKeyHoldsItsValue) {
  Sampler s(action_of(
      {channel(0, ChannelPath::Translation, Interpolation::CubicSpline, {0.5f}, {9, 9, 9, 1, 2, 3, 9, 9, 9})}));
  expect_near(s.translation(0.0f), {1, 2, 3});
  expect_near(s.translation(1.0f), {1, 2, 3});
}

TEST(Sampling, UnboundChannelsAndUnanimatedJointsKeepTheirValues) {
  Sampler s(action_of({channel(0, ChannelPath::Translation, Interpolation::Linear, {0, 1}, {0, 0, 0, 1, 1, 1}),
                       channel(1, ChannelPath::Translation, Interpolation::Linear, {0, 1}, {0, 0, 0, 1, 1, 1})}));
  s.targets[1] = -1;
  s.pose.translations[1] = glm::vec3(7.0f);
  s.pose.scales[0] = glm::vec3(5.0f);
  expect_near(s.translation(0.5f), glm::vec3(0.5f));
  expect_near(s.pose.translations[1], glm::vec3(7.0f));
  expect_near(s.pose.scales[0], glm::vec3(5.0f));
}

// A channel whose value at time t is t (keys at irregular times).
Action ramp_action() {
  std::vector<float> times, values;
  float t = 0.0f;
  for (int k = 0; k < 40; ++k) {
    times.push_back(t);
    values.insert(values.end(), {t, -t, 2 * t});
    t += 0.02f + 0.03f * static_cast<float>(k % 5);
  }
  return action_of({channel(0, ChannelPath::Translation, Interpolation::Linear, times, values)});
}

TEST(Sampling, CursorGivesTheSameValuesAsAFreshSearch) {
  Sampler kept(ramp_action());
  const float end = kept.action.end;
  std::vector<float> times;
  for (float t = 0.0f; t < end; t += 1.0f / 60.0f) times.push_back(t);  // playback
  for (float t = end; t > 0.0f; t -= 0.07f) times.push_back(t);         // backwards
  for (int loop = 0; loop < 3; ++loop)                                  // looping
    for (float t = 0.0f; t < end; t += 0.11f) times.push_back(t);
  times.insert(times.end(), {0.0f, end, 0.0f, end * 0.9f, end * 0.1f, end});  // jumps
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> anywhere(-0.5f, end + 0.5f);
  for (int k = 0; k < 500; ++k) times.push_back(anywhere(rng));

  for (float t : times) {
    Sampler fresh(ramp_action());
    const glm::vec3 expected = fresh.translation(t);
    const glm::vec3 got = kept.translation(t);
    ASSERT_EQ(got, expected) << "t = " << t;
    const float c = std::clamp(t, 0.0f, end);
    ASSERT_NEAR(got.x, c, 1e-5f) << "t = " << t;
  }
}

TEST(Sampling, ValidateRefusesInconsistentInput) {
  Sampler s(action_of({channel(0, ChannelPath::Translation, Interpolation::Linear, {0, 1}, {0, 0, 0, 1, 1, 1})}));
  EXPECT_TRUE(s.at(0.5f));
  EXPECT_FALSE(s.at(std::nanf("")));
  EXPECT_FALSE((SamplingJob{&s.action, 0.5f, {}, &s.cursor, &s.pose}.Run()));
  EXPECT_FALSE((SamplingJob{nullptr, 0.5f, s.targets, &s.cursor, &s.pose}.Run()));
  s.targets[0] = 1;  // past the pose's one joint
  EXPECT_FALSE(s.at(0.5f));
  s.targets[0] = 0;
  s.cursor.keys.clear();  // not reset for this action
  EXPECT_FALSE(s.at(0.5f));
  reset_cursor(s.action, &s.cursor);
  s.action.channels[0].values.pop_back();  // values do not match the keys
  EXPECT_FALSE(s.at(0.5f));
  s.action.channels[0].values.push_back(1);
  s.action.channels[0].interpolation = Interpolation::CubicSpline;  // needs 3 groups a key
  EXPECT_FALSE(s.at(0.5f));
}

// InterpolationTest.glb (Khronos sample): one node per action, each a single
// channel with five keys; the expected values are worked from the file's keys.
class InterpolationTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string file =
        std::string(CROWDPROF_SAMPLES_DIR) + "/InterpolationTest/glTF-Binary/InterpolationTest.glb";
    if (!std::filesystem::exists(file)) GTEST_SKIP() << "sample not found: " << file;
    asset_ = load_gltf(file);
  }
  // Samples the action named `name` at `time`; returns the pose of its node.
  size_t sample(const std::string& name, float time) {
    for (const Action& action : asset_.node_actions) {
      if (action.name != name) continue;
      EXPECT_EQ(action.channels.size(), 1u);
      const size_t nodes = asset_.node_names.size();
      pose_.translations.assign(nodes, glm::vec3(0.0f));
      pose_.rotations.assign(nodes, glm::quat(1.0f, 0.0f, 0.0f, 0.0f));
      pose_.scales.assign(nodes, glm::vec3(1.0f));
      std::vector<int32_t> targets{action.channels[0].joint};
      SamplingCursor cursor;
      reset_cursor(action, &cursor);
      EXPECT_TRUE((SamplingJob{&action, time, targets, &cursor, &pose_}.Run()));
      return static_cast<size_t>(targets[0]);
    }
    ADD_FAILURE() << "no action " << name;
    return 0;
  }
  glm::vec3 scale(const std::string& name, float time) {
    const size_t node = sample(name, time);
    return pose_.scales[node];
  }
  glm::quat rotation(const std::string& name, float time) {
    const size_t node = sample(name, time);
    return pose_.rotations[node];
  }
  glm::vec3 translation(const std::string& name, float time) {
    const size_t node = sample(name, time);
    return pose_.translations[node];
  }
  GltfAsset asset_;
  LocalPose pose_;
};

TEST_F(InterpolationTest, Scale) {
  // Keys at 1/24, 10/24, 21/24, 30/24, 40/24 s with scales 1, 0.5, 1, 0.5, 1.
  const float mid = (10.0f / 24 + 21.0f / 24) / 2;
  expect_near(scale("Step Scale", 0.6f), glm::vec3(0.5f), 1e-5f);
  expect_near(scale("Step Scale", 0.3f), glm::vec3(1.0f), 1e-5f);
  expect_near(scale("Linear Scale", mid), glm::vec3(0.75f), 1e-5f);
  // Zero tangents: halfway is the average, a quarter of the way h01 = 0.15625.
  expect_near(scale("CubicSpline Scale", mid), glm::vec3(0.75f), 1e-5f);
  const float quarter = 10.0f / 24 + (21.0f / 24 - 10.0f / 24) / 4;
  expect_near(scale("CubicSpline Scale", quarter), glm::vec3(0.578125f), 1e-5f);
}

TEST_F(InterpolationTest, Rotation) {
  // Keys at 0, 10/24, 21/24, 30/24, 41/24 s: 0, -45, -90, -135, -180 degrees about z.
  expect_near(rotation("Step Rotation", 0.5f), {0, 0, -kS22, kC22}, 1e-5f);
  const float mid = 5.0f / 24;  // halfway to -45: -22.5 degrees
  const float s11 = std::sin(glm::radians(11.25f)), c11 = std::cos(glm::radians(11.25f));
  expect_near(rotation("Linear Rotation", mid), {0, 0, -s11, c11}, 1e-5f);
  // On a key the spline is the key's value, whatever its tangents.
  expect_near(rotation("CubicSpline Rotation", 21.0f / 24), {0, 0, -kHalf, kHalf}, 1e-5f);
}

TEST_F(InterpolationTest, Translation) {
  // Step: keys at 0, 11/24, 20/24, ... with y = 6.66523, 10, 6, 10, 6.
  expect_near(translation("Step Translation", 0.5f), {0, 10, 0}, 1e-5f);
  // Linear: keys at 0 and 10/24 with y = 6.62101 and 10; x stays -3.29758.
  expect_near(translation("Linear Translation", 5.0f / 24), {-3.29758f, (6.62101f + 10.0f) / 2, 0}, 1e-4f);
  // Cubic, zero tangents: keys at 0 and 10/24 with y = 6.64012 and 10.
  expect_near(translation("CubicSpline Translation", 5.0f / 24), {3.30518f, (6.64012f + 10.0f) / 2, 0}, 1e-4f);
}

}  // namespace
}  // namespace crowdprof
