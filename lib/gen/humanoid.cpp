// The humanoid's rig: which bones a given count buys, where they sit in the
// bind pose, and the Skeleton made from them. Mesh and actions are built from the
// rig in humanoid_mesh.cpp and humanoid_actions.cpp.
#include "gen/humanoid.h"

#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "base/errors.h"
#include "asset/gltf_accessor.h"
#include "gen/humanoid_rig.h"

namespace crowdprof {
namespace humanoid {

double Random::uniform() {  // splitmix64
  uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}

std::vector<int> Rig::chain(Part part, int side, int finger) const {
  std::vector<int> found;
  for (size_t b = 0; b < bones.size(); ++b)
    if (bones[b].part == part && bones[b].side == side && bones[b].finger == finger)
      found.push_back(static_cast<int>(b));
  return found;
}

int Rig::first(Part part, int side, int finger) const {
  std::vector<int> c = chain(part, side, finger);
  return c.empty() ? -1 : c.front();
}

int Rig::last(Part part, int side, int finger) const {
  std::vector<int> c = chain(part, side, finger);
  return c.empty() ? -1 : c.back();
}

namespace {

// How many bones each chain gets. The smallest humanoid (20 bones) has one
// segment per chain and no fingers; each Step adds one bone on the midline or
// one on each side.
struct Layout {
  int spine = 1, neck = 1, jaw = 0;
  int upper_arm = 1, forearm = 1, thigh = 1, shin = 1;
  int fingers = 0;                 // thumb, index, middle, ring, little: the first `fingers`
  std::array<int, 5> phalanges{};  // per finger
  int metacarpals = 0;             // for index, middle, ring, little: the first `metacarpals`

  int count() const {
    int hand = metacarpals;
    for (int f = 0; f < fingers; ++f) hand += phalanges[static_cast<size_t>(f)];
    int side = 1 + upper_arm + forearm + 1 + hand + thigh + shin + 2;
    return 1 + spine + neck + 1 + jaw + 2 * side;
  }
};

enum class Step : uint8_t { Spine, Neck, Jaw, Finger, Phalanx, UpperArm, Forearm, Thigh, Shin, Metacarpal };

struct Growth {
  Step step;
  int finger = 0;  // for Phalanx
};

bool midline(Step step) {
  return step == Step::Spine || step == Step::Neck || step == Step::Jaw;
}

void apply(Layout& layout, Growth g) {
  switch (g.step) {
    case Step::Spine:
      ++layout.spine;
      break;
    case Step::Neck:
      ++layout.neck;
      break;
    case Step::Jaw:
      layout.jaw = 1;
      break;
    case Step::Finger:
      layout.phalanges[static_cast<size_t>(layout.fingers++)] = 1;
      break;
    case Step::Phalanx:
      ++layout.phalanges[static_cast<size_t>(g.finger)];
      break;
    case Step::UpperArm:
      ++layout.upper_arm;
      break;
    case Step::Forearm:
      ++layout.forearm;
      break;
    case Step::Thigh:
      ++layout.thigh;
      break;
    case Step::Shin:
      ++layout.shin;
      break;
    case Step::Metacarpal:
      ++layout.metacarpals;
      break;
  }
}

// Growth from 20 to 69 bones (the default rig), then a repeating subdivision of
// the chains. Steps are taken in order; a two-sided step that would overshoot is
// skipped for the next midline one, so every count is reachable.
Layout layout_for(int bones) {
  std::vector<Growth> to_default = {{Step::Spine}, {Step::Spine}};
  for (int f = 0; f < 5; ++f) to_default.push_back({Step::Finger});
  to_default.push_back({Step::Neck});
  for (int f = 0; f < 5; ++f) to_default.push_back({Step::Phalanx, f});
  to_default.push_back({Step::Jaw});
  for (int f = 0; f < 5; ++f) to_default.push_back({Step::Phalanx, f});
  to_default.insert(to_default.end(), {{Step::UpperArm}, {Step::Forearm}, {Step::Spine}});
  for (int m = 0; m < 4; ++m) to_default.push_back({Step::Metacarpal});
  to_default.push_back({Step::Thigh});

  std::vector<Growth> cycle = {{Step::Spine}, {Step::UpperArm}, {Step::Forearm}, {Step::Thigh}, {Step::Shin}};
  for (int f = 0; f < 5; ++f) cycle.push_back({Step::Phalanx, f});
  cycle.push_back({Step::Neck});

  Layout layout;
  int left = bones - layout.count();
  auto take = [&](Growth g) {
    int cost = midline(g.step) ? 1 : 2;
    if (cost > left) return;
    apply(layout, g);
    left -= cost;
  };
  for (Growth g : to_default) take(g);
  while (left > 0)
    for (Growth g : cycle) take(g);
  return layout;
}

glm::dquat orientation_along(glm::dvec3 head, glm::dvec3 tail) {
  glm::dvec3 y = glm::normalize(tail - head);
  glm::dvec3 ref = std::abs(y.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 1, 0);
  glm::dvec3 x = glm::normalize(glm::cross(y, ref));
  glm::dvec3 z = glm::cross(x, y);
  return glm::normalize(glm::quat_cast(glm::dmat3(x, y, z)));
}

class RigBuilder {
 public:
  RigBuilder(Rig& rig) : rig_(rig) {}

  // A point of the template body (metres, ~1.8 m tall) in this build.
  glm::dvec3 at(double x, double y, double z) const {
    const Build& b = rig_.build;
    return {x * b.height * b.width, y * b.height, z * b.height};
  }

  // Splits head..tail into `n` bones named name[_NN]suffix; returns the last.
  int chain(const std::string& name, const std::string& suffix, bool numbered, int parent, Part part, int side,
            int finger, int n, glm::dvec3 head, glm::dvec3 tail, double bow = 0.0) {
    auto point = [&](int i) {
      double s = double(i) / n;
      return head + (tail - head) * s + glm::dvec3(0, 0, bow * std::sin(3.141592653589793 * s));
    };
    for (int i = 0; i < n; ++i) {
      std::string label = name;
      if (numbered || i > 0) label += (i + 1 < 10 ? "_0" : "_") + std::to_string(i + 1);
      parent = add(label + suffix, parent, part, side, finger, i, n, point(i), point(i + 1));
    }
    return parent;
  }

  int add(const std::string& name, int parent, Part part, int side, int finger, int segment, int segments,
          glm::dvec3 head, glm::dvec3 tail) {
    Bone b{name, parent, part, side, finger, segment, segments, head, tail, orientation_along(head, tail)};
    rig_.bones.push_back(b);
    return static_cast<int>(rig_.bones.size()) - 1;
  }

 private:
  Rig& rig_;
};

void build_arm(RigBuilder& r, const Layout& layout, int side, int chest) {
  const std::string sfx = side > 0 ? "_l" : "_r";
  const double s = side;
  int clavicle = r.add("clavicle" + sfx, chest, Part::Clavicle, side, -1, 0, 1, r.at(s * 0.02, 1.40, 0.03),
                       r.at(s * 0.165, 1.42, -0.01));
  glm::dvec3 shoulder = r.at(s * 0.165, 1.42, -0.01), elbow = r.at(s * 0.445, 1.42, -0.02);
  glm::dvec3 wrist = r.at(s * 0.695, 1.42, -0.01);
  int upper = r.chain("upperarm", sfx, false, clavicle, Part::UpperArm, side, -1, layout.upper_arm, shoulder, elbow);
  int fore = r.chain("lowerarm", sfx, false, upper, Part::Forearm, side, -1, layout.forearm, elbow, wrist);
  int hand = r.add("hand" + sfx, fore, Part::Hand, side, -1, 0, 1, wrist, wrist + r.at(s * 0.10, 0, 0));

  static const char* names[5] = {"thumb", "index", "middle", "ring", "pinky"};
  // Knuckles across the palm (palm down, thumb forward) and each finger's length.
  static const double knuckle_x[5] = {0.02, 0.095, 0.10, 0.095, 0.085};
  static const double knuckle_z[5] = {0.022, 0.028, 0.008, -0.012, -0.03};
  static const double length[5] = {0.11, 0.075, 0.085, 0.08, 0.062};
  for (int f = 0; f < layout.fingers; ++f) {
    size_t fi = static_cast<size_t>(f);
    glm::dvec3 knuckle = wrist + r.at(s * knuckle_x[fi], f == 0 ? -0.012 : 0.0, knuckle_z[fi]);
    glm::dvec3 dir = f == 0 ? glm::normalize(glm::dvec3(s * 0.55, -0.2, 0.8))
                            : glm::normalize(glm::dvec3(s * 1.0, 0.0, knuckle_z[fi] * 1.5));
    int parent = hand;
    if (f >= 1 && f <= layout.metacarpals)
      parent = r.add("metacarpal_" + std::string(names[fi]) + sfx, hand, Part::Metacarpal, side, f, 0, 1,
                     wrist + r.at(s * 0.012, 0, knuckle_z[fi] * 0.5), knuckle);
    // Phalanges shorten towards the tip.
    int n = layout.phalanges[fi];
    double total = 0.0, piece = 1.0;
    for (int i = 0; i < n; ++i, piece *= 0.75) total += piece;
    glm::dvec3 head = knuckle;
    piece = 1.0;
    for (int i = 0; i < n; ++i, piece *= 0.75) {
      glm::dvec3 tail = head + dir * (length[fi] * r.at(0, 1, 0).y * piece / total);
      std::string label = std::string(names[fi]) + (i + 1 < 10 ? "_0" : "_") + std::to_string(i + 1) + sfx;
      parent = r.add(label, parent, Part::Finger, side, f, i, n, head, tail);
      head = tail;
    }
  }
}

void build_leg(RigBuilder& r, const Layout& layout, int side, int hips) {
  const std::string sfx = side > 0 ? "_l" : "_r";
  const double s = side;
  glm::dvec3 hip = r.at(s * 0.09, 0.92, 0.0), knee = r.at(s * 0.095, 0.50, 0.015);
  glm::dvec3 ankle = r.at(s * 0.10, 0.085, -0.025), ball = r.at(s * 0.105, 0.025, 0.11);
  int thigh = r.chain("thigh", sfx, false, hips, Part::Thigh, side, -1, layout.thigh, hip, knee);
  int shin = r.chain("calf", sfx, false, thigh, Part::Shin, side, -1, layout.shin, knee, ankle);
  int foot = r.add("foot" + sfx, shin, Part::Foot, side, -1, 0, 1, ankle, ball);
  r.add("ball" + sfx, foot, Part::Toe, side, -1, 0, 1, ball, r.at(s * 0.11, 0.02, 0.175));
}

Rig build_rig(const Layout& layout, const Build& build) {
  Rig rig;
  rig.build = build;
  RigBuilder r(rig);
  int hips = r.add("hips", -1, Part::Hips, 0, -1, 0, 1, r.at(0, 0.94, 0), r.at(0, 1.02, 0));
  int chest = r.chain("spine", "", true, hips, Part::Spine, 0, -1, layout.spine, r.at(0, 1.02, 0), r.at(0, 1.44, 0),
                      -0.02 * build.height);
  int neck = r.chain("neck", "", true, chest, Part::Neck, 0, -1, layout.neck, r.at(0, 1.44, 0), r.at(0, 1.55, 0.01));
  int head = r.add("head", neck, Part::Head, 0, -1, 0, 1, r.at(0, 1.55, 0.01), r.at(0, 1.78, 0.01));
  if (layout.jaw) r.add("jaw", head, Part::Jaw, 0, -1, 0, 1, r.at(0, 1.60, 0.015), r.at(0, 1.555, 0.085));
  for (int side : {1, -1}) build_arm(r, layout, side, chest);
  for (int side : {1, -1}) build_leg(r, layout, side, hips);
  return rig;
}

// Rest TRS relative to the parent, and inverse binds computed from the rounded
// TRS, so that they agree with what a loader recomputes from the file.
Skeleton make_skeleton(const Rig& rig) {
  Skeleton sk;
  std::vector<glm::dmat4> model(rig.bones.size());
  for (size_t j = 0; j < rig.bones.size(); ++j) {
    const Bone& b = rig.bones[j];
    glm::dquat parent_rot(1, 0, 0, 0);
    glm::dvec3 parent_pos(0.0);
    if (b.parent >= 0) {
      parent_rot = rig.bones[static_cast<size_t>(b.parent)].orientation;
      parent_pos = rig.bones[static_cast<size_t>(b.parent)].head;
    }
    glm::vec3 t = stable_float(glm::conjugate(parent_rot) * (b.head - parent_pos));
    glm::dquat r = glm::normalize(glm::conjugate(parent_rot) * b.orientation);
    glm::quat q(stable_float(r.w), stable_float(r.x), stable_float(r.y), stable_float(r.z));
    sk.names.push_back(b.name);
    sk.parents.push_back(b.parent);
    sk.rest_translations.push_back(t);
    sk.rest_rotations.push_back(q);
    sk.rest_scales.emplace_back(1.0f);
    sk.parent_offsets.emplace_back(1.0f);
    glm::dmat4 local = glm::translate(glm::dmat4(1.0), glm::dvec3(t)) * glm::mat4_cast(glm::dquat(q));
    model[j] = b.parent >= 0 ? model[static_cast<size_t>(b.parent)] * local : local;
    glm::dmat4 inverse = glm::inverse(model[j]);
    glm::mat4 narrow;
    for (int col = 0; col < 4; ++col)
      for (int row = 0; row < 4; ++row) narrow[col][row] = stable_float(inverse[col][row]);
    sk.inverse_binds.push_back(narrow);
  }
  return sk;
}

}  // namespace
}  // namespace humanoid

// What gen writes, the loader must take back: about six indices per vertex.
static_assert(6ull * kHumanoidMaxVertices + 1000 < kMaxAccessorElements);

Character generate_humanoid(const HumanoidOptions& options) {
  if (options.bones < kHumanoidMinBones || options.bones > kHumanoidMaxBones)
    throw SettingError("bones", std::to_string(options.bones),
                       "expected " + std::to_string(kHumanoidMinBones) + " to " + std::to_string(kHumanoidMaxBones));
  if (options.vertices < kHumanoidMinVertices || options.vertices > kHumanoidMaxVertices)
    throw SettingError(
        "vertices", std::to_string(options.vertices),
        "expected " + std::to_string(kHumanoidMinVertices) + " to " + std::to_string(kHumanoidMaxVertices));
  humanoid::Random random(options.seed);
  humanoid::Build build;
  build.height = random.range(0.97, 1.03);
  build.width = random.range(0.96, 1.04);
  build.girth = random.range(0.93, 1.07);
  humanoid::Rig rig = humanoid::build_rig(humanoid::layout_for(options.bones), build);

  Character character;
  character.name = "humanoid";
  character.skeleton = humanoid::make_skeleton(rig);
  character.mesh = humanoid::build_mesh(rig, options.vertices);
  if (options.lod_levels < 0 || options.lod_levels > 3)
    throw SettingError("lods", std::to_string(options.lod_levels), "expected 0 to 3");
  constexpr int kLevelDivisor[] = {2, 4, 10};
  int previous = options.vertices;
  for (int l = 0; l < options.lod_levels; ++l) {
    const int vertices = std::max(kHumanoidMinVertices, options.vertices / kLevelDivisor[l]);
    if (vertices >= previous) break;  // no coarser body to make
    character.file_lods.push_back(humanoid::build_mesh(rig, vertices));
    previous = vertices;
  }
  character.actions = humanoid::build_actions(rig, character.skeleton, options.seed, options.actions);
  return character;
}

}  // namespace crowdprof
