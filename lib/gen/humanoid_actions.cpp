// The humanoid's looping actions. Each is a pose function of the phase (0..2π
// over one loop), written as rotations about the model's axes in the bind pose
// (X: pitch, Y: turn, Z: roll in the frontal plane), so that "raise the left
// arm" reads as a turn about Z whatever the bone's own frame. Every joint also
// sways a little in every action: nothing in the rig stands still.
#include <cmath>
#include <functional>

#include "gen/humanoid.h"
#include "gen/humanoid_rig.h"

namespace crowdprof::humanoid {
namespace {

constexpr double kDeg = kPi / 180.0;
constexpr int kFps = 30;

struct Pose {
  std::vector<glm::dvec3> angles;  // per joint, radians about model X, Y, Z
  glm::dvec3 root_offset{0.0};     // metres, added to the root's rest translation
};

using PoseFn = std::function<void(double phase, Pose&)>;

double rise(double x) {
  return 0.5 - 0.5 * std::cos(x);
}  // 0..1..0, smooth

struct Actor {
  const Rig& rig;
  double amp;  // the seed's slight variation of amplitude

  void each(Pose& pose, Part part, int side, const std::function<void(const Bone&, glm::dvec3&)>& f) const {
    for (size_t j = 0; j < rig.bones.size(); ++j)
      if (rig.bones[j].part == part && (side == 0 || rig.bones[j].side == side)) f(rig.bones[j], pose.angles[j]);
  }
  // Spreads a bend over a chain (the spine, a split limb) or puts it on its first segment.
  void bend(Pose& pose, Part part, int side, glm::dvec3 angles, bool spread) const {
    each(pose, part, side, [&](const Bone& b, glm::dvec3& a) {
      if (spread)
        a += angles * (amp / b.segments);
      else if (b.segment == 0)
        a += angles * amp;
    });
  }
  void fingers(Pose& pose, double curl, double spread) const {
    each(pose, Part::Finger, 0, [&](const Bone& b, glm::dvec3& a) {
      if (b.finger == 0) {
        a.x += curl * 0.6 * amp;  // the thumb folds under the palm
      } else {
        a.z += -b.side * curl * amp;  // fingers curl down, palm down
        if (b.segment == 0) a.y += b.side * spread * (b.finger - 2.5) * amp;
      }
    });
  }
};

void dance(const Actor& r, double p, Pose& pose) {
  pose.root_offset = {0.06 * std::sin(p) * r.amp, -0.03 * rise(2 * p), 0.0};
  r.bend(pose, Part::Hips, 0, {0, 10 * kDeg * std::sin(p), 6 * kDeg * std::sin(p)}, true);
  r.bend(pose, Part::Spine, 0, {4 * kDeg * rise(2 * p), -14 * kDeg * std::sin(p), -9 * kDeg * std::sin(p)}, true);
  r.bend(pose, Part::Neck, 0, {0, 0, 5 * kDeg * std::cos(p)}, true);
  r.bend(pose, Part::Head, 0, {8 * kDeg * std::sin(2 * p), 0, 0}, true);
  r.bend(pose, Part::Jaw, 0, {8 * kDeg * rise(4 * p), 0, 0}, true);
  for (int s : {1, -1}) {
    double pump = std::sin(p + s * kPi / 2);  // the arms pump in turn
    r.bend(pose, Part::Clavicle, s, {0, 0, s * 8 * kDeg * (1 + pump)}, true);
    r.bend(pose, Part::UpperArm, s, {0, -s * 10 * kDeg, s * (55 + 20 * pump) * kDeg}, false);
    r.bend(pose, Part::UpperArm, s, {s * 15 * kDeg * pump, 0, 0}, true);
    r.bend(pose, Part::Forearm, s, {0, -s * (35 + 25 * pump) * kDeg, 0}, false);
    r.bend(pose, Part::Forearm, s, {s * 12 * kDeg * std::sin(2 * p), 0, 0}, true);
    r.bend(pose, Part::Hand, s, {0, 0, s * 20 * kDeg * std::sin(2 * p)}, true);
    r.bend(pose, Part::Metacarpal, s, {0, 0, -s * 3 * kDeg * rise(2 * p)}, true);
    r.bend(pose, Part::Thigh, s, {-12 * kDeg * rise(2 * p), 0, -6 * kDeg * std::sin(p)}, false);
    r.bend(pose, Part::Thigh, s, {0, s * 6 * kDeg * std::sin(p), 0}, true);
    r.bend(pose, Part::Shin, s, {24 * kDeg * rise(2 * p), 0, 0}, true);
    r.bend(pose, Part::Foot, s, {-12 * kDeg * rise(2 * p), 0, 6 * kDeg * std::sin(p)}, true);
    r.bend(pose, Part::Toe, s, {8 * kDeg * rise(2 * p + s), 0, 0}, true);
  }
  r.fingers(pose, 25 * kDeg + 15 * kDeg * std::sin(2 * p), 4 * kDeg);
}

void walk(const Actor& r, double p, Pose& pose) {
  pose.root_offset = {0.015 * std::sin(p), 0.02 * std::cos(2 * p) - 0.02, 0.0};
  r.bend(pose, Part::Hips, 0, {0, 7 * kDeg * std::sin(p), 3 * kDeg * std::sin(p)}, true);
  r.bend(pose, Part::Spine, 0, {3 * kDeg, -10 * kDeg * std::sin(p), -3 * kDeg * std::sin(p)}, true);
  r.bend(pose, Part::Neck, 0, {-2 * kDeg * std::cos(2 * p), 3 * kDeg * std::sin(p), 0}, true);
  r.bend(pose, Part::Head, 0, {0, 2 * kDeg * std::sin(p), -2 * kDeg * std::sin(p)}, true);
  r.bend(pose, Part::Jaw, 0, {2 * kDeg * rise(2 * p), 0, 0}, true);
  for (int s : {1, -1}) {
    double swing = s * std::sin(p);  // > 0: this leg forward, this arm back
    r.bend(pose, Part::Clavicle, s, {0, s * 4 * kDeg * swing, -s * 4 * kDeg}, true);
    r.bend(pose, Part::UpperArm, s, {22 * kDeg * swing, 0, -s * 76 * kDeg}, false);
    r.bend(pose, Part::UpperArm, s, {s * 8 * kDeg * swing, 0, 0}, true);
    r.bend(pose, Part::Forearm, s, {0, -s * (18 + 12 * rise(p + s * kPi / 2)) * kDeg, 0}, false);
    r.bend(pose, Part::Forearm, s, {s * 6 * kDeg * swing, 0, 0}, true);
    r.bend(pose, Part::Hand, s, {0, -s * 10 * kDeg, -s * 8 * kDeg * swing}, true);
    r.bend(pose, Part::Metacarpal, s, {0, 0, -s * 2 * kDeg * swing}, true);
    r.bend(pose, Part::Thigh, s, {-26 * kDeg * swing, 0, 0}, false);
    r.bend(pose, Part::Thigh, s, {0, -s * 5 * kDeg * swing, 0}, true);
    // The knee folds while the leg swings through, straight while it bears weight.
    double knee = 5 + 45 * std::pow(rise(p + s * kPi / 2 + 0.4 * kPi), 3);
    r.bend(pose, Part::Shin, s, {knee * kDeg, 0, 0}, true);
    r.bend(pose, Part::Foot, s, {-10 * kDeg * std::sin(p + s * kPi / 2), 0, 0}, true);
    r.bend(pose, Part::Toe, s, {15 * kDeg * rise(p + s * kPi), 0, 0}, true);
  }
  r.fingers(pose, 18 * kDeg + 6 * kDeg * std::sin(p), 2 * kDeg);
}

void wave(const Actor& r, double p, Pose& pose) {
  pose.root_offset = {0.03 * std::sin(p), -0.01 * rise(2 * p), 0.0};
  r.bend(pose, Part::Hips, 0, {0, 5 * kDeg * std::sin(p), 3 * kDeg * std::sin(p)}, true);
  r.bend(pose, Part::Spine, 0, {0, -6 * kDeg * std::sin(p), 5 * kDeg - 4 * kDeg * std::sin(p)}, true);
  r.bend(pose, Part::Neck, 0, {0, -8 * kDeg, 0}, true);
  r.bend(pose, Part::Head, 0, {-4 * kDeg, 0, 8 * kDeg * std::sin(2 * p)}, true);
  r.bend(pose, Part::Jaw, 0, {6 * kDeg * rise(2 * p), 0, 0}, true);
  const int s = -1;  // the right arm waves, palm forward
  double wag = std::sin(2 * p);
  r.bend(pose, Part::Clavicle, s, {0, 0, s * 12 * kDeg}, true);
  r.bend(pose, Part::UpperArm, s, {0, -s * 20 * kDeg, s * (25 + 4 * wag) * kDeg}, false);
  r.bend(pose, Part::UpperArm, s, {-s * 50 * kDeg, 0, 0}, true);
  r.bend(pose, Part::Forearm, s, {0, 0, s * (85 + 28 * wag) * kDeg}, false);
  r.bend(pose, Part::Forearm, s, {s * 10 * kDeg * wag, 0, 0}, true);
  r.bend(pose, Part::Hand, s, {0, 0, s * 15 * kDeg * std::sin(2 * p + 0.7)}, true);
  r.bend(pose, Part::Metacarpal, s, {0, 0, -s * 4 * kDeg * wag}, true);
  r.bend(pose, Part::Clavicle, -s, {0, 0, s * 3 * kDeg * std::sin(p)}, true);
  r.bend(pose, Part::UpperArm, -s, {-5 * kDeg * std::sin(p), 0, s * 78 * kDeg}, false);
  r.bend(pose, Part::UpperArm, -s, {-s * 5 * kDeg * std::sin(p), 0, 0}, true);
  r.bend(pose, Part::Forearm, -s, {0, s * 12 * kDeg, 0}, false);
  r.bend(pose, Part::Forearm, -s, {-s * 4 * kDeg * std::sin(p), 0, 0}, true);
  r.bend(pose, Part::Hand, -s, {0, 0, 6 * kDeg * std::sin(p)}, true);
  r.bend(pose, Part::Metacarpal, -s, {0, 0, 2 * kDeg * std::sin(p)}, true);
  for (int side : {1, -1}) {
    r.bend(pose, Part::Thigh, side, {-4 * kDeg * rise(2 * p), 0, -3 * kDeg * std::sin(p)}, false);
    r.bend(pose, Part::Thigh, side, {0, side * 3 * kDeg * std::sin(p), 0}, true);
    r.bend(pose, Part::Shin, side, {8 * kDeg * rise(2 * p), 0, 0}, true);
    r.bend(pose, Part::Foot, side, {-4 * kDeg * rise(2 * p), 0, 3 * kDeg * std::sin(p)}, true);
    r.bend(pose, Part::Toe, side, {4 * kDeg * rise(2 * p), 0, 0}, true);
  }
  r.fingers(pose, 8 * kDeg + 6 * kDeg * wag, 5 * kDeg);
}

// Locomotion's rest between moves: standing, arms down, breathing, the weight
// drifting from foot to foot.
void idle(const Actor& r, double p, Pose& pose) {
  pose.root_offset = {0.02 * std::sin(p) * r.amp, -0.005 * rise(2 * p), 0.0};
  r.bend(pose, Part::Hips, 0, {0, 2 * kDeg * std::sin(p), 2 * kDeg * std::sin(p)}, true);
  r.bend(pose, Part::Spine, 0, {2 * kDeg * rise(2 * p), -2 * kDeg * std::sin(p), -2 * kDeg * std::sin(p)}, true);
  r.bend(pose, Part::Neck, 0, {-kDeg * rise(2 * p), 4 * kDeg * std::sin(p + 1.0), 0}, true);
  r.bend(pose, Part::Head, 0, {2 * kDeg * std::sin(2 * p), 3 * kDeg * std::sin(p + 1.0), 0}, true);
  r.bend(pose, Part::Jaw, 0, {kDeg * rise(2 * p), 0, 0}, true);
  for (int s : {1, -1}) {
    r.bend(pose, Part::Clavicle, s, {0, 0, s * 2 * kDeg * rise(2 * p)}, true);
    r.bend(pose, Part::UpperArm, s, {3 * kDeg * std::sin(p), 0, -s * 80 * kDeg}, false);
    r.bend(pose, Part::Forearm, s, {0, -s * (10 + 3 * rise(2 * p)) * kDeg, 0}, false);
    r.bend(pose, Part::Hand, s, {0, -s * 8 * kDeg, 0}, true);
    r.bend(pose, Part::Metacarpal, s, {0, 0, -s * kDeg * rise(2 * p)}, true);
    r.bend(pose, Part::Thigh, s, {-2 * kDeg * rise(p + s), 0, -2 * kDeg * std::sin(p)}, false);
    r.bend(pose, Part::Shin, s, {4 * kDeg * rise(p + s), 0, 0}, true);
    r.bend(pose, Part::Foot, s, {-2 * kDeg * rise(p + s), 0, 2 * kDeg * std::sin(p)}, true);
    r.bend(pose, Part::Toe, s, {2 * kDeg * rise(2 * p), 0, 0}, true);
  }
  r.fingers(pose, 15 * kDeg + 3 * kDeg * std::sin(p), 2 * kDeg);
}

// Walk's gait, longer and quicker: leaning forward, elbows bent, the knee
// folding high on the swing, the body bouncing twice a loop.
void run(const Actor& r, double p, Pose& pose) {
  pose.root_offset = {0.02 * std::sin(p), 0.05 * std::cos(2 * p) - 0.06, 0.0};
  r.bend(pose, Part::Hips, 0, {0, 10 * kDeg * std::sin(p), 4 * kDeg * std::sin(p)}, true);
  r.bend(pose, Part::Spine, 0, {12 * kDeg, -14 * kDeg * std::sin(p), -4 * kDeg * std::sin(p)}, true);
  r.bend(pose, Part::Neck, 0, {-8 * kDeg + -3 * kDeg * std::cos(2 * p), 4 * kDeg * std::sin(p), 0}, true);
  r.bend(pose, Part::Head, 0, {-4 * kDeg, 3 * kDeg * std::sin(p), -2 * kDeg * std::sin(p)}, true);
  r.bend(pose, Part::Jaw, 0, {4 * kDeg * rise(2 * p), 0, 0}, true);
  for (int s : {1, -1}) {
    double swing = s * std::sin(p);  // > 0: this leg forward, this arm back
    r.bend(pose, Part::Clavicle, s, {0, s * 6 * kDeg * swing, -s * 6 * kDeg}, true);
    r.bend(pose, Part::UpperArm, s, {45 * kDeg * swing, 0, -s * 70 * kDeg}, false);
    r.bend(pose, Part::UpperArm, s, {s * 10 * kDeg * swing, 0, 0}, true);
    r.bend(pose, Part::Forearm, s, {0, -s * (80 + 15 * rise(p + s * kPi / 2)) * kDeg, 0}, false);
    r.bend(pose, Part::Forearm, s, {s * 8 * kDeg * swing, 0, 0}, true);
    r.bend(pose, Part::Hand, s, {0, -s * 10 * kDeg, -s * 10 * kDeg * swing}, true);
    r.bend(pose, Part::Metacarpal, s, {0, 0, -s * 3 * kDeg * swing}, true);
    r.bend(pose, Part::Thigh, s, {(-10 - 45 * swing) * kDeg, 0, 0}, false);
    r.bend(pose, Part::Thigh, s, {0, -s * 6 * kDeg * swing, 0}, true);
    double knee = 15 + 95 * std::pow(rise(p + s * kPi / 2 + 0.4 * kPi), 2);
    r.bend(pose, Part::Shin, s, {knee * kDeg, 0, 0}, true);
    r.bend(pose, Part::Foot, s, {-20 * kDeg * std::sin(p + s * kPi / 2), 0, 0}, true);
    r.bend(pose, Part::Toe, s, {25 * kDeg * rise(p + s * kPi), 0, 0}, true);
  }
  r.fingers(pose, 50 * kDeg, 1 * kDeg);  // loose fists
}

glm::dquat turn(glm::dvec3 a) {  // about Z first, then X, then Y
  return glm::angleAxis(a.y, glm::dvec3(0, 1, 0)) * glm::angleAxis(a.x, glm::dvec3(1, 0, 0)) *
         glm::angleAxis(a.z, glm::dvec3(0, 0, 1));
}

Action sample(const std::string& name, double duration, const Rig& rig, const Skeleton& skeleton, uint32_t seed,
              const std::function<void(const Actor&, double, Pose&)>& pose_at) {
  Random random(seed * 7919ull + name.size() * 131ull + uint64_t(name[0]));
  Actor actor{rig, random.range(0.9, 1.1)};
  const size_t joints = rig.bones.size();
  // The idle sway: small, its axis and phase per joint.
  std::vector<double> idle_phase(joints);
  for (double& ph : idle_phase) ph = random.range(0.0, 2.0 * kPi);

  const int frames = int(std::lround(duration * kFps));
  Action action;
  action.name = name;
  action.start = 0.0f;
  action.end = static_cast<float>(duration);
  std::vector<float> times(static_cast<size_t>(frames) + 1);
  for (int f = 0; f <= frames; ++f) times[static_cast<size_t>(f)] = static_cast<float>(double(f) / kFps);
  times.back() = action.end;

  Channel root;
  root.joint = 0;
  root.path = ChannelPath::Translation;
  root.times = times;
  action.channels.push_back(root);
  for (size_t j = 0; j < joints; ++j) {
    Channel c;
    c.joint = static_cast<int>(j);
    c.path = ChannelPath::Rotation;
    c.times = times;
    action.channels.push_back(std::move(c));
  }
  Pose pose;
  for (int f = 0; f < frames; ++f) {  // the last key repeats the first: the loop closes exactly
    double phase = 2.0 * kPi * f / frames;
    pose.angles.assign(joints, glm::dvec3(0.0));
    pose.root_offset = glm::dvec3(0.0);
    pose_at(actor, phase, pose);
    glm::dvec3 t = glm::dvec3(skeleton.rest_translations[0]) + pose.root_offset;
    for (int k = 0; k < 3; ++k) action.channels[0].values.push_back(stable_float(t[k]));
    for (size_t j = 0; j < joints; ++j) {
      const Bone& b = rig.bones[j];
      glm::dvec3 a = pose.angles[j];
      // Three cycles per loop, a rhythm no action uses, so the sway never cancels a motion.
      a[int(j % 3)] += 2.0 * kDeg * std::sin(3 * phase + idle_phase[j]) / b.segments;
      // The turn is about model axes at bind; seen from the parent's bind frame
      // it is conjugated by the parent's orientation, then applied before the rest rotation.
      glm::dquat parent = b.parent >= 0 ? rig.bones[static_cast<size_t>(b.parent)].orientation : glm::dquat(1, 0, 0, 0);
      glm::dquat q = glm::conjugate(parent) * turn(a) * parent * glm::dquat(skeleton.rest_rotations[j]);
      q = glm::normalize(q);
      std::vector<float>& v = action.channels[j + 1].values;
      v.insert(v.end(), {stable_float(q.x), stable_float(q.y), stable_float(q.z), stable_float(q.w)});
    }
  }
  for (Channel& c : action.channels) {
    size_t n = static_cast<size_t>(c.components());
    for (size_t k = 0; k < n; ++k) c.values.push_back(c.values[k]);
    prepare_slerp(&c);
  }
  return action;
}

}  // namespace

std::vector<Action> build_actions(const Rig& rig, const Skeleton& skeleton, uint32_t seed, HumanoidActions set) {
  if (set == HumanoidActions::Locomotion)
    return {sample("idle", 2.0, rig, skeleton, seed, idle), sample("walk", 1.0, rig, skeleton, seed, walk),
            sample("run", 0.8, rig, skeleton, seed, run)};
  return {sample("dance", 2.0, rig, skeleton, seed, dance), sample("walk", 1.0, rig, skeleton, seed, walk),
          sample("wave", 1.5, rig, skeleton, seed, wave)};
}

}  // namespace crowdprof::humanoid
