// The generated humanoid: exact counts, a valid skin, and actions that loop and
// move every joint in the way their names promise.
#include "gen/humanoid.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "base/errors.h"

using namespace crowdprof;

namespace {

int joint(const Skeleton& s, const std::string& name) {
  auto it = std::find(s.names.begin(), s.names.end(), name);
  return it == s.names.end() ? -1 : int(it - s.names.begin());
}

// Model matrices of the joints for one key of an action (or the rest pose when null).
std::vector<glm::mat4> pose(const Character& c, const Action* action, size_t key) {
  const Skeleton& s = c.skeleton;
  std::vector<glm::vec3> t = s.rest_translations;
  std::vector<glm::quat> r = s.rest_rotations;
  if (action)
    for (const Channel& ch : action->channels) {
      const float* v = &ch.values[key * size_t(ch.components())];
      if (ch.path == ChannelPath::Rotation) r[size_t(ch.joint)] = glm::quat(v[3], v[0], v[1], v[2]);
      if (ch.path == ChannelPath::Translation) t[size_t(ch.joint)] = glm::vec3(v[0], v[1], v[2]);
    }
  std::vector<glm::mat4> model(s.joint_count());
  for (size_t j = 0; j < model.size(); ++j) {
    glm::mat4 local = glm::translate(glm::mat4(1.0f), t[j]) * glm::mat4_cast(r[j]);
    model[j] = s.parents[j] < 0 ? local : model[size_t(s.parents[j])] * local;
  }
  return model;
}

glm::vec3 where(const std::vector<glm::mat4>& model, int j) {
  return glm::vec3(model[size_t(j)][3]);
}

const Action& action(const Character& c, const std::string& name) {
  for (const Action& a : c.actions)
    if (a.name == name) return a;
  throw std::runtime_error("no action " + name);
}

void expect_valid(const Character& c, int bones, int vertices) {
  const Skeleton& s = c.skeleton;
  ASSERT_EQ(s.joint_count(), size_t(bones));
  ASSERT_EQ(c.mesh.vertex_count(), size_t(vertices));
  EXPECT_EQ(std::set<std::string>(s.names.begin(), s.names.end()).size(), s.names.size()) << "joint names repeat";
  EXPECT_EQ(s.parents[0], -1);
  for (size_t j = 1; j < s.joint_count(); ++j) {
    EXPECT_GE(s.parents[j], 0) << s.names[j] << " is a second root";
    EXPECT_LT(s.parents[j], int(j)) << s.names[j] << " comes before its parent";
  }
  ASSERT_EQ(s.rest_translations.size(), size_t(bones));
  ASSERT_EQ(s.inverse_binds.size(), size_t(bones));
  ASSERT_EQ(s.parent_offsets.size(), size_t(bones));

  const SkinnedMesh& m = c.mesh;
  ASSERT_EQ(m.normals.size(), m.vertex_count());
  ASSERT_EQ(m.joints.size(), m.vertex_count());
  ASSERT_EQ(m.weights.size(), m.vertex_count());
  ASSERT_EQ(m.primitives.size(), 1u);
  EXPECT_EQ(m.primitives[0].vertex_count, uint32_t(vertices));
  EXPECT_EQ(m.primitives[0].index_count, m.indices.size());
  ASSERT_EQ(m.indices.size() % 3, 0u);
  std::vector<bool> used(m.vertex_count(), false);
  for (size_t i = 0; i < m.indices.size(); i += 3) {
    for (int k = 0; k < 3; ++k) {
      ASSERT_LT(m.indices[i + k], m.vertex_count());
      used[m.indices[i + k]] = true;
    }
    glm::vec3 a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]], d = m.positions[m.indices[i + 2]];
    EXPECT_GT(glm::length(glm::cross(b - a, d - a)), 0.0f) << "degenerate triangle " << i / 3;
  }
  EXPECT_EQ(std::count(used.begin(), used.end(), false), 0) << "vertices on no triangle";
  for (size_t v = 0; v < m.vertex_count(); ++v) {
    const glm::vec4 w = m.weights[v];
    EXPECT_NEAR(w.x + w.y + w.z + w.w, 1.0f, 1e-6f) << "vertex " << v;
    for (int k = 0; k < 4; ++k) {
      EXPECT_GE(w[k], 0.0f);
      EXPECT_LT(m.joints[v][k], bones);
      if (k > 0) {
        EXPECT_GE(w[k - 1], w[k]) << "weights not sorted, vertex " << v;
      }
      if (w[k] == 0.0f) {
        EXPECT_EQ(m.joints[v][k], 0) << "an unused slot names a joint";
      }
    }
    EXPECT_NEAR(glm::length(m.normals[v]), 1.0f, 1e-5f);
  }
}

}  // namespace

TEST(Humanoid, DefaultIsTheThesisCharacter) {
  Character c = generate_humanoid();
  expect_valid(c, 69, 4951);
  EXPECT_EQ(c.name, "humanoid");
  EXPECT_EQ(c.fixups.total(), 0u);
  EXPECT_FALSE(c.draco_decoded);
  for (const char* name :
       {"hips", "spine_01", "neck_01", "head", "jaw", "clavicle_l", "upperarm_r", "lowerarm_l", "hand_r", "thumb_03_l",
        "pinky_01_r", "metacarpal_index_l", "thigh_r", "calf_l", "foot_r", "ball_l"})
    EXPECT_GE(joint(c.skeleton, name), 0) << name;
  int fingers = 0;
  for (const std::string& n : c.skeleton.names)
    fingers += n.find("thumb_") == 0 || n.find("index_") == 0 || n.find("middle_") == 0 || n.find("ring_") == 0 ||
               n.find("pinky_") == 0;
  EXPECT_EQ(fingers, 30) << "3 phalanges x 5 fingers x 2 hands";
}

TEST(Humanoid, AnyCountInRangeIsExact) {
  const std::pair<int, int> sizes[] = {{20, 500},  {21, 777},    {22, 1000},  {23, 1501},  {47, 3001},  {68, 4950},
                                       {70, 4952}, {100, 12345}, {129, 8000}, {257, 2000}, {1024, 500}, {1024, 60001}};
  for (auto [bones, vertices] : sizes) {
    SCOPED_TRACE(std::to_string(bones) + " bones, " + std::to_string(vertices) + " vertices");
    expect_valid(generate_humanoid({bones, vertices, 1}), bones, vertices);
  }
}

TEST(Humanoid, OutOfRangeOptionsAreRefused) {
  EXPECT_THROW(generate_humanoid({19, 4951, 1}), UsageError);
  EXPECT_THROW(generate_humanoid({1025, 4951, 1}), UsageError);
  EXPECT_THROW(generate_humanoid({69, 499, 1}), UsageError);
  EXPECT_THROW(generate_humanoid({69, 10'000'001, 1}), UsageError);
  EXPECT_THROW(generate_humanoid({-5, -5, 1}), UsageError);
}

TEST(Humanoid, WeightsBlendNearJoints) {
  Character c = generate_humanoid();
  size_t by_count[5] = {};
  for (const glm::vec4& w : c.mesh.weights) by_count[(w.x > 0) + (w.y > 0) + (w.z > 0) + (w.w > 0)]++;
  EXPECT_EQ(by_count[0], 0u);
  EXPECT_GT(by_count[2] + by_count[3] + by_count[4], c.mesh.vertex_count() / 2);
  EXPECT_GT(by_count[3], c.mesh.vertex_count() / 20);
  EXPECT_GT(by_count[4], c.mesh.vertex_count() / 20);
}

TEST(Humanoid, InverseBindsInvertTheBindPose) {
  Character c = generate_humanoid();
  std::vector<glm::mat4> bind = pose(c, nullptr, 0);
  for (size_t j = 0; j < bind.size(); ++j) {
    glm::mat4 product = bind[j] * c.skeleton.inverse_binds[j];
    for (int col = 0; col < 4; ++col)
      for (int row = 0; row < 4; ++row)
        EXPECT_NEAR(product[col][row], col == row ? 1.0f : 0.0f, 1e-5f) << c.skeleton.names[j];
  }
}

TEST(Humanoid, IsAnUprightPersonFacingPlusZ) {
  Character c = generate_humanoid();
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (const glm::vec3& p : c.mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  EXPECT_NEAR(lo.y, 0.0f, 0.03f) << "feet on the ground";
  EXPECT_GT(hi.y - lo.y, 1.7f);
  EXPECT_LT(hi.y - lo.y, 1.9f);
  EXPECT_GT(hi.x - lo.x, 1.5f) << "T-pose: arms out";
  std::vector<glm::mat4> bind = pose(c, nullptr, 0);
  const Skeleton& s = c.skeleton;
  EXPECT_GT(where(bind, joint(s, "ball_l")).z, where(bind, joint(s, "foot_l")).z) << "toes point forward";
  EXPECT_GT(where(bind, joint(s, "hand_l")).x, 0.5f) << "the left hand is on +X";
  EXPECT_LT(where(bind, joint(s, "hand_r")).x, -0.5f);
  EXPECT_GT(where(bind, joint(s, "head")).y, where(bind, joint(s, "hips")).y + 0.5f);

  // Outward normals and counter-clockwise winding: each part is a closed
  // surface, so the signed volume it encloses is positive.
  double volume = 0.0;
  const auto& m = c.mesh;
  for (size_t i = 0; i < m.indices.size(); i += 3)
    volume += glm::dot(glm::dvec3(m.positions[m.indices[i]]), glm::cross(glm::dvec3(m.positions[m.indices[i + 1]]),
                                                                         glm::dvec3(m.positions[m.indices[i + 2]]))) /
              6.0;
  EXPECT_GT(volume, 0.04);
  EXPECT_LT(volume, 0.15);
  size_t outward = 0;
  for (size_t v = 0; v < m.vertex_count(); ++v) {
    // The vertex's heaviest bone runs from its joint towards a child: the
    // normal must point away from the segment of the joint's position.
    glm::vec3 from = where(bind, m.joints[v][0]);
    outward += glm::dot(m.normals[v], m.positions[v] - from) > 0.0f;
  }
  EXPECT_GT(outward, m.vertex_count() * 8 / 10);
}

TEST(Humanoid, ActionsLoopAndMoveEveryJoint) {
  for (int bones : {20, 69, 300}) {
    Character c = generate_humanoid({bones, 2000, 7});
    SCOPED_TRACE(std::to_string(bones) + " bones");
    ASSERT_EQ(c.actions.size(), 3u);
    EXPECT_EQ(c.actions[0].name, "dance");
    EXPECT_EQ(c.actions[1].name, "walk");
    EXPECT_EQ(c.actions[2].name, "wave");
    for (const Action& a : c.actions) {
      SCOPED_TRACE(a.name);
      EXPECT_EQ(a.start, 0.0f);
      EXPECT_GE(a.duration(), 1.0f);
      EXPECT_LE(a.duration(), 2.0f);
      std::vector<int> rotations(size_t(bones), 0);
      bool root_moves = false;
      for (const Channel& ch : a.channels) {
        ASSERT_EQ(ch.interpolation, Interpolation::Linear);
        ASSERT_GE(ch.key_count(), 25u);
        ASSERT_EQ(ch.values.size(), ch.key_count() * size_t(ch.components()));
        EXPECT_EQ(ch.times.front(), a.start);
        EXPECT_EQ(ch.times.back(), a.end);
        for (size_t k = 1; k < ch.key_count(); ++k) {
          ASSERT_GT(ch.times[k], ch.times[k - 1]);
          ASSERT_LE(ch.times[k] - ch.times[k - 1], 1.0f / 24.0f + 1e-6f) << "keys at 24 fps or more";
        }
        const size_t n = size_t(ch.components()), last = (ch.key_count() - 1) * n;
        EXPECT_EQ(0, std::memcmp(&ch.values[0], &ch.values[last], n * sizeof(float))) << "the loop must close";
        if (ch.path == ChannelPath::Translation) {
          EXPECT_EQ(ch.joint, 0);
          for (size_t k = 1; k < ch.key_count(); ++k) root_moves |= ch.values[k * 3] != ch.values[0];
          continue;
        }
        ASSERT_EQ(ch.path, ChannelPath::Rotation);
        rotations[size_t(ch.joint)]++;
        double widest = 0.0;
        glm::dquat first(ch.values[3], ch.values[0], ch.values[1], ch.values[2]);
        for (size_t k = 0; k < ch.key_count(); ++k) {
          glm::dquat q(ch.values[4 * k + 3], ch.values[4 * k], ch.values[4 * k + 1], ch.values[4 * k + 2]);
          EXPECT_NEAR(glm::length(q), 1.0, 1e-6);
          if (k > 0) {
            glm::dquat prev(ch.values[4 * k - 1], ch.values[4 * k - 4], ch.values[4 * k - 3], ch.values[4 * k - 2]);
            EXPECT_GT(glm::dot(q, prev), 0.99) << "neighbouring keys take the short way";
          }
          widest = std::max(widest, 2.0 * std::acos(std::min(1.0, std::abs(glm::dot(q, first)))));
        }
        EXPECT_GT(widest, 0.5 * 3.14159 / 180.0 / (bones > 69 ? 10 : 1))
            << c.skeleton.names[size_t(ch.joint)] << " barely moves";
      }
      EXPECT_TRUE(root_moves);
      for (int j = 0; j < bones; ++j) EXPECT_EQ(rotations[size_t(j)], 1) << c.skeleton.names[size_t(j)];
    }
  }
}

TEST(Humanoid, ActionsDoWhatTheirNamesSay) {
  Character c = generate_humanoid();
  const Skeleton& s = c.skeleton;
  const int head = joint(s, "head"), hand_l = joint(s, "hand_l"), hand_r = joint(s, "hand_r");
  const int foot_l = joint(s, "foot_l"), foot_r = joint(s, "foot_r"), hips = joint(s, "hips");

  // Walk: the feet pass each other, the left foot leading a quarter in, the
  // right one three quarters in; each hand swings with the opposite foot.
  const Action& walk = action(c, "walk");
  const size_t keys = walk.channels[0].key_count(), quarter = (keys - 1) / 4;
  for (size_t key : {quarter, 3 * quarter}) {
    std::vector<glm::mat4> p = pose(c, &walk, key);
    float lead = key == quarter ? 1.0f : -1.0f;
    EXPECT_GT(lead * (where(p, foot_l).z - where(p, foot_r).z), 0.25f) << "stride at key " << key;
    EXPECT_LT(lead * (where(p, hand_l).z - where(p, hand_r).z), -0.1f) << "arm swing at key " << key;
    EXPECT_LT(where(p, hand_l).y, where(p, hips).y + 0.2f) << "arms down";
  }
  // Dance: both hands above the head at some point, the hips swaying.
  const Action& dance = action(c, "dance");
  bool hands_up = false;
  float sway_lo = 1e9f, sway_hi = -1e9f;
  for (size_t k = 0; k < dance.channels[0].key_count(); ++k) {
    std::vector<glm::mat4> p = pose(c, &dance, k);
    hands_up |= where(p, hand_l).y > where(p, head).y && where(p, hand_r).y > where(p, head).y;
    sway_lo = std::min(sway_lo, where(p, hips).x), sway_hi = std::max(sway_hi, where(p, hips).x);
  }
  EXPECT_TRUE(hands_up);
  EXPECT_GT(sway_hi - sway_lo, 0.08f);
  // Wave: the right hand up by the head throughout, the left one down; the
  // right hand travels side to side.
  const Action& wave = action(c, "wave");
  float wave_lo = 1e9f, wave_hi = -1e9f;
  for (size_t k = 0; k < wave.channels[0].key_count(); ++k) {
    std::vector<glm::mat4> p = pose(c, &wave, k);
    EXPECT_GT(where(p, hand_r).y, where(p, head).y - 0.1f);
    EXPECT_LT(where(p, hand_l).y, where(p, hips).y + 0.2f);
    wave_lo = std::min(wave_lo, where(p, hand_r).x), wave_hi = std::max(wave_hi, where(p, hand_r).x);
  }
  EXPECT_GT(wave_hi - wave_lo, 0.1f);
}

TEST(Humanoid, SameOptionsSameCharacter) {
  auto same = [](const Character& a, const Character& b) {
    auto bytes = [](const auto& v) {
      return std::vector<char>((const char*)v.data(), (const char*)(v.data() + v.size()));
    };
    bool eq = a.skeleton.names == b.skeleton.names && a.skeleton.parents == b.skeleton.parents &&
              bytes(a.skeleton.rest_translations) == bytes(b.skeleton.rest_translations) &&
              bytes(a.skeleton.rest_rotations) == bytes(b.skeleton.rest_rotations) &&
              bytes(a.skeleton.inverse_binds) == bytes(b.skeleton.inverse_binds) &&
              bytes(a.mesh.positions) == bytes(b.mesh.positions) && bytes(a.mesh.normals) == bytes(b.mesh.normals) &&
              bytes(a.mesh.joints) == bytes(b.mesh.joints) && bytes(a.mesh.weights) == bytes(b.mesh.weights) &&
              a.mesh.indices == b.mesh.indices && a.actions.size() == b.actions.size();
    for (size_t i = 0; eq && i < a.actions.size(); ++i)
      for (size_t k = 0; eq && k < a.actions[i].channels.size(); ++k)
        eq = bytes(a.actions[i].channels[k].values) == bytes(b.actions[i].channels[k].values) &&
             a.actions[i].channels[k].times == b.actions[i].channels[k].times;
    return eq;
  };
  EXPECT_TRUE(same(generate_humanoid(), generate_humanoid()));
  EXPECT_TRUE(same(generate_humanoid({150, 7000, 42}), generate_humanoid({150, 7000, 42})));
  Character other = generate_humanoid({69, 4951, 2});
  EXPECT_FALSE(same(generate_humanoid(), other)) << "the seed must change something";
  expect_valid(other, 69, 4951);
}

TEST(Humanoid, LocomotionIdlesWalksAndRunsOnTheSameBody) {
  HumanoidOptions options;
  options.actions = HumanoidActions::Locomotion;
  const Character c = generate_humanoid(options), thesis = generate_humanoid();
  ASSERT_EQ(c.actions.size(), 3u);
  EXPECT_EQ(c.actions[0].name, "idle");
  EXPECT_EQ(c.actions[1].name, "walk");
  EXPECT_EQ(c.actions[2].name, "run");
  EXPECT_EQ(c.skeleton.names, thesis.skeleton.names);
  EXPECT_EQ(c.mesh.positions, thesis.mesh.positions) << "only the actions differ";
  // The walk is the thesis character's walk, key for key.
  const Action& walk = action(c, "walk");
  const Action& thesis_walk = action(thesis, "walk");
  ASSERT_EQ(walk.channels.size(), thesis_walk.channels.size());
  for (size_t k = 0; k < walk.channels.size(); ++k) EXPECT_EQ(walk.channels[k].values, thesis_walk.channels[k].values);
  const Skeleton& s = c.skeleton;
  const int foot_l = joint(s, "foot_l"), foot_r = joint(s, "foot_r"), hips = joint(s, "hips");
  const int hand_l = joint(s, "hand_l");
  // Widest stride (feet apart along Z) and lowest hips over each loop.
  auto stride = [&](const Action& a) {
    float widest = 0.0f;
    for (size_t k = 0; k < a.channels[0].key_count(); ++k) {
      std::vector<glm::mat4> p = pose(c, &a, k);
      widest = std::max(widest, std::fabs(where(p, foot_l).z - where(p, foot_r).z));
    }
    return widest;
  };
  const Action& idle = action(c, "idle");
  const Action& run = action(c, "run");
  EXPECT_LT(stride(idle), 0.1f) << "idle stands";
  EXPECT_GT(stride(walk), 0.25f);
  EXPECT_GT(stride(run), 1.3f * stride(walk)) << "a run strides further than a walk";
  EXPECT_LT(run.duration(), walk.duration()) << "and quicker";
  for (size_t k = 0; k < idle.channels[0].key_count(); ++k) {
    std::vector<glm::mat4> p = pose(c, &idle, k);
    EXPECT_LT(where(p, hand_l).y, where(p, hips).y + 0.2f) << "idle's arms hang, key " << k;
  }
  // Loops close and every joint turns in every action, as the thesis's actions.
  for (const Action& a : c.actions)
    for (const Channel& ch : a.channels) {
      const size_t n = size_t(ch.components()), last = (ch.key_count() - 1) * n;
      EXPECT_EQ(0, std::memcmp(&ch.values[0], &ch.values[last], n * sizeof(float))) << a.name;
    }
}
