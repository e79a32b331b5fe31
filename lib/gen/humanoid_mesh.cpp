// The humanoid's skin: closed tubes around the bones (torso, head, nose, arms,
// palms, fingers, legs, feet), sized so that the vertex count is exact, with
// smooth weights from the distance to nearby bones.
#include <algorithm>
#include <array>
#include <cmath>

#include "gen/humanoid.h"
#include "gen/humanoid_rig.h"

namespace crowdprof::humanoid {
namespace {

struct Ring {
  double s;        // fraction of the path's length
  double ru, rv;   // radii along the width axis and across it
  double forward;  // centre shift along +Z (face, chest, calf)
};

// A closed tube: rings along a polyline, a pole at each end.
struct Tube {
  std::vector<glm::dvec3> path;
  glm::dvec3 width{1, 0, 0};  // the direction `ru` measures
  std::vector<Ring> profile;  // by increasing s, from 0 to 1
  std::vector<int> bones;     // joints that may influence its vertices
};

double length_of(const std::vector<glm::dvec3>& path) {
  double len = 0.0;
  for (size_t i = 1; i < path.size(); ++i) len += glm::length(path[i] - path[i - 1]);
  return len;
}

glm::dvec3 point_at(const std::vector<glm::dvec3>& path, double s) {
  double want = std::clamp(s, 0.0, 1.0) * length_of(path);
  for (size_t i = 1; i < path.size(); ++i) {
    double seg = glm::length(path[i] - path[i - 1]);
    if (want <= seg || i + 1 == path.size())
      return path[i - 1] + (path[i] - path[i - 1]) * (seg > 0 ? want / seg : 0.0);
    want -= seg;
  }
  return path.back();
}

// Smoothed across the path's corners, so rings do not pinch at a joint.
glm::dvec3 tangent_at(const std::vector<glm::dvec3>& path, double s) {
  const double e = 0.04;
  return glm::normalize(point_at(path, std::min(1.0, s + e)) - point_at(path, std::max(0.0, s - e)));
}

Ring ring_at(const std::vector<Ring>& profile, double s) {
  if (s <= profile.front().s) return profile.front();
  for (size_t i = 1; i < profile.size(); ++i) {
    const Ring &a = profile[i - 1], &b = profile[i];
    if (s > b.s) continue;
    double x = (s - a.s) / (b.s - a.s);
    x = x * x * (3.0 - 2.0 * x);  // smoothstep: rounded, not faceted, outlines
    return {s, a.ru + (b.ru - a.ru) * x, a.rv + (b.rv - a.rv) * x, a.forward + (b.forward - a.forward) * x};
  }
  return profile.back();
}

struct Sizing {
  int rings = 2, around = 6;
  size_t vertices() const { return size_t(rings) * size_t(around) + 2; }
};

// Rings about `spacing` apart along the tube and around it.
Sizing size_tube(const Tube& tube, double spacing) {
  double ru = 0.0, rv = 0.0;
  for (const Ring& r : tube.profile) ru = std::max(ru, r.ru), rv = std::max(rv, r.rv);
  double around = 2.0 * kPi * std::sqrt(0.5 * (ru * ru + rv * rv));
  Sizing z;
  z.around = std::max(6, int(std::lround(std::min(around / spacing, 1e6))));
  z.rings = std::max(2, int(std::lround(std::min(length_of(tube.path) / spacing, 1e6))) + 1);
  return z;
}

struct Builder {
  std::vector<glm::dvec3> positions;
  std::vector<int> tube_of;  // per vertex
  std::vector<uint32_t> indices;

  void emit(const Tube& tube, int id, Sizing z) {
    const uint32_t base = static_cast<uint32_t>(positions.size());
    const uint32_t m = static_cast<uint32_t>(z.around);
    glm::dvec3 first_t{0.0}, last_t{0.0}, first_c{0.0}, last_c{0.0};
    double first_r = 0.0, last_r = 0.0;
    for (int i = 0; i < z.rings; ++i) {
      double s = double(i) / (z.rings - 1);
      glm::dvec3 t = tangent_at(tube.path, s);
      glm::dvec3 u = glm::normalize(tube.width - t * glm::dot(t, tube.width));
      glm::dvec3 v = glm::cross(t, u);  // u, v, t right-handed: rings run counter-clockwise about t
      Ring r = ring_at(tube.profile, s);
      glm::dvec3 c = point_at(tube.path, s) + glm::dvec3(0, 0, r.forward);
      for (uint32_t k = 0; k < m; ++k) {
        double a = 2.0 * kPi * k / m;
        positions.push_back(c + u * (r.ru * std::cos(a)) + v * (r.rv * std::sin(a)));
      }
      if (i == 0) first_t = t, first_c = c, first_r = std::min(r.ru, r.rv);
      last_t = t, last_c = c, last_r = std::min(r.ru, r.rv);
    }
    const uint32_t rings = static_cast<uint32_t>(z.rings);
    const uint32_t start_pole = base + rings * m, end_pole = start_pole + 1;
    positions.push_back(first_c - first_t * (0.6 * first_r));
    positions.push_back(last_c + last_t * (0.6 * last_r));
    tube_of.resize(positions.size(), id);
    auto at = [&](uint32_t ring, uint32_t k) { return base + ring * m + k % m; };
    for (uint32_t k = 0; k < m; ++k) {  // winding counter-clockwise seen from outside
      indices.insert(indices.end(), {at(0, k + 1), at(0, k), start_pole});
      for (uint32_t i = 0; i + 1 < rings; ++i) {
        indices.insert(indices.end(), {at(i, k), at(i, k + 1), at(i + 1, k)});
        indices.insert(indices.end(), {at(i, k + 1), at(i + 1, k + 1), at(i + 1, k)});
      }
      indices.insert(indices.end(), {at(rings - 1, k), at(rings - 1, k + 1), end_pole});
    }
  }

  // Tops the count up by splitting `extra` triangles, spread over the whole
  // mesh, at their centroids: the surface keeps its shape and stays closed.
  void pad(size_t extra) {
    while (extra > 0) {
      const size_t triangles = indices.size() / 3, now = std::min(extra, triangles);
      for (size_t j = 0; j < now; ++j) {
        size_t t = (2 * j + 1) * triangles / (2 * now);
        uint32_t a = indices[3 * t], b = indices[3 * t + 1], c = indices[3 * t + 2];
        uint32_t mid = static_cast<uint32_t>(positions.size());
        positions.push_back((positions[a] + positions[b] + positions[c]) / 3.0);
        tube_of.push_back(tube_of[a]);
        indices[3 * t + 2] = mid;
        indices.insert(indices.end(), {b, c, mid, c, a, mid});
      }
      extra -= now;
    }
  }
};

double distance2_to_bone(glm::dvec3 p, const Bone& b) {
  glm::dvec3 d = b.tail - b.head;
  double t = std::clamp(glm::dot(p - b.head, d) / glm::dot(d, d), 0.0, 1.0);
  glm::dvec3 q = b.head + d * t - p;
  return glm::dot(q, q);
}

// Up to four joints by inverse distance to the bone (to the 8th power, so the
// nearest bone dominates away from joints and neighbours blend near them).
void weigh(glm::dvec3 p, const Rig& rig, const std::vector<int>& bones, glm::u16vec4& joints, glm::vec4& weights) {
  std::vector<std::pair<double, int>> w;
  double total = 0.0;
  for (int b : bones) {
    double d2 = distance2_to_bone(p, rig.bones[static_cast<size_t>(b)]) + 1e-6;
    w.emplace_back(1.0 / (d2 * d2 * d2 * d2), b);
    total += w.back().first;
  }
  // Shares on stable_float's grid: a vertex midway between two bones is then
  // an exact tie, broken by bone index, on any build.
  for (auto& x : w) x.first = stable_float(x.first / total);
  std::sort(w.begin(), w.end(),
            [](auto& x, auto& y) { return x.first != y.first ? x.first > y.first : x.second < y.second; });
  w.resize(std::min<size_t>(w.size(), 4));
  double sum = 0.0;
  for (auto& x : w) sum += x.first;
  while (w.size() > 1 && w.back().first / sum < 0.015) sum -= w.back().first, w.pop_back();
  joints = glm::u16vec4(0);
  weights = glm::vec4(0.0f);
  float rest = 0.0f;
  for (size_t i = w.size(); i-- > 1;) {
    weights[int(i)] = stable_float(w[i].first / sum);
    joints[int(i)] = static_cast<uint16_t>(w[i].second);
    rest += weights[int(i)];
  }
  weights[0] = 1.0f - rest;  // so the float sum is 1
  joints[0] = static_cast<uint16_t>(w[0].second);
  // Where the two largest tie, that rounding can leave the first a hair below
  // the second: keep the slots sorted.
  if (weights[0] < weights[1]) std::swap(weights[0], weights[1]), std::swap(joints[0], joints[1]);
}

// Appends `b`'s whole chain(s) to `set`.
void add(std::vector<int>& set, const std::vector<int>& bones) {
  for (int b : bones)
    if (b >= 0 && std::find(set.begin(), set.end(), b) == set.end()) set.push_back(b);
}

std::vector<Tube> body_tubes(const Rig& rig) {
  const Build& k = rig.build;
  auto at = [&](double x, double y, double z) {
    return glm::dvec3(x * k.height * k.width, y * k.height, z * k.height);
  };
  const double g = k.height * k.girth;
  auto ring = [&](double s, double ru, double rv, double fwd = 0.0) { return Ring{s, ru * g, rv * g, fwd * k.height}; };
  auto head_of = [&](int b) { return rig.bones[static_cast<size_t>(b)].head; };
  auto tail_of = [&](int b) { return rig.bones[static_cast<size_t>(b)].tail; };
  std::vector<Tube> tubes;

  // Torso: pelvis to the base of the neck, following the spine's bow.
  Tube torso;
  torso.path.push_back(at(0, 0.84, 0));
  for (int b : rig.chain(Part::Hips)) torso.path.push_back(head_of(b));
  for (int b : rig.chain(Part::Spine)) torso.path.push_back(head_of(b));
  torso.path.push_back(head_of(rig.first(Part::Neck)));
  torso.path.push_back(at(0, 1.50, 0));
  auto by_y = [](double y, double y0, double y1) { return (y - y0) / (y1 - y0); };
  for (auto [y, ru, rv, f] : std::vector<std::array<double, 4>>{{0.84, 0.10, 0.075, 0},
                                                                {0.90, 0.16, 0.105, 0},
                                                                {0.97, 0.172, 0.112, 0},
                                                                {1.08, 0.145, 0.098, 0.005},
                                                                {1.20, 0.155, 0.105, 0.012},
                                                                {1.31, 0.172, 0.112, 0.016},
                                                                {1.39, 0.182, 0.1, 0.005},
                                                                {1.45, 0.165, 0.088, 0},
                                                                {1.49, 0.09, 0.062, 0},
                                                                {1.50, 0.05, 0.045, 0}})
    torso.profile.push_back(ring(by_y(y, 0.84, 1.50), ru, rv, f));
  add(torso.bones, rig.chain(Part::Hips));
  add(torso.bones, rig.chain(Part::Spine));
  add(torso.bones, {rig.first(Part::Neck)});
  for (int side : {1, -1})
    add(torso.bones, {rig.first(Part::Clavicle, side), rig.first(Part::UpperArm, side), rig.first(Part::Thigh, side)});
  tubes.push_back(torso);

  // Neck and head, the face pushed forward (+Z); a nose shows which way it looks.
  Tube head;
  head.path.push_back(at(0, 1.42, 0));
  for (int b : rig.chain(Part::Neck)) head.path.push_back(head_of(b));
  head.path.push_back(head_of(rig.first(Part::Head)));
  head.path.push_back(at(0, 1.797, 0.01));
  for (auto [y, ru, rv, f] : std::vector<std::array<double, 4>>{{1.42, 0.06, 0.06, 0},
                                                                {1.50, 0.05, 0.052, 0},
                                                                {1.555, 0.052, 0.058, 0.005},
                                                                {1.60, 0.072, 0.085, 0.018},
                                                                {1.67, 0.08, 0.097, 0.02},
                                                                {1.73, 0.076, 0.092, 0.012},
                                                                {1.765, 0.06, 0.075, 0.008},
                                                                {1.785, 0.04, 0.05, 0.005},
                                                                {1.797, 0.018, 0.022, 0.004}})
    head.profile.push_back(ring(by_y(y, 1.42, 1.797), ru, rv, f));
  add(head.bones, {rig.last(Part::Spine)});
  add(head.bones, rig.chain(Part::Neck));
  add(head.bones, {rig.first(Part::Head), rig.first(Part::Jaw)});
  tubes.push_back(head);
  tubes.push_back(Tube{{at(0, 1.665, 0.09), at(0, 1.645, 0.128)},
                       {1, 0, 0},
                       {ring(0, 0.014, 0.012), ring(1, 0.008, 0.007)},
                       {rig.first(Part::Head)}});

  for (int side : {1, -1}) {
    const double s = side;
    Tube arm;
    arm.width = {0, 1, 0};
    arm.path = {at(s * 0.13, 1.42, -0.01)};
    for (int b : rig.chain(Part::UpperArm, side)) arm.path.push_back(head_of(b));
    for (int b : rig.chain(Part::Forearm, side)) arm.path.push_back(head_of(b));
    glm::dvec3 wrist = head_of(rig.first(Part::Hand, side));
    arm.path.push_back(wrist);
    arm.path.push_back(wrist + at(s * 0.01, 0, 0));
    for (auto [x, ru, rv] : std::vector<std::array<double, 3>>{{0.13, 0.05, 0.054},
                                                               {0.20, 0.052, 0.054},
                                                               {0.30, 0.047, 0.05},
                                                               {0.44, 0.037, 0.04},
                                                               {0.52, 0.04, 0.046},
                                                               {0.66, 0.028, 0.034},
                                                               {0.705, 0.024, 0.03}})
      arm.profile.push_back(ring(by_y(x, 0.13, 0.705), ru, rv));
    add(arm.bones, {rig.last(Part::Spine), rig.first(Part::Clavicle, side)});
    add(arm.bones, rig.chain(Part::UpperArm, side));
    add(arm.bones, rig.chain(Part::Forearm, side));
    add(arm.bones, {rig.first(Part::Hand, side)});
    tubes.push_back(arm);

    // Palm down, thumb forward; fingers are thin tubes along their phalanges.
    int hand = rig.first(Part::Hand, side);
    Tube palm{{wrist - at(s * 0.01, 0, 0), wrist + at(s * 0.09, 0, 0)},
              {0, 0, 1},
              {ring(0, 0.03, 0.017), ring(0.4, 0.044, 0.018), ring(1, 0.04, 0.012)},
              {}};
    add(palm.bones, {rig.last(Part::Forearm, side), hand});
    for (int f = 0; f < 5; ++f)
      add(palm.bones, {rig.first(Part::Metacarpal, side, f), rig.first(Part::Finger, side, f)});
    tubes.push_back(palm);
    for (int f = 0; f < 5; ++f) {
      std::vector<int> phalanges = rig.chain(Part::Finger, side, f);
      if (phalanges.empty()) continue;
      glm::dvec3 base = head_of(phalanges.front()), tip = tail_of(phalanges.back());
      Tube finger;
      finger.width = {0, 1, 0};
      finger.path = {base - glm::normalize(tip - base) * (0.012 * k.height)};
      for (int b : phalanges) finger.path.push_back(tail_of(b));
      double r = f == 0 ? 0.012 : 0.0095;
      finger.profile = {ring(0, r, r * 0.95), ring(1, r * 0.78, r * 0.72)};
      add(finger.bones, {hand, rig.first(Part::Metacarpal, side, f)});
      add(finger.bones, phalanges);
      tubes.push_back(finger);
    }

    Tube leg;
    leg.path = {at(s * 0.09, 0.97, 0)};
    for (int b : rig.chain(Part::Thigh, side)) leg.path.push_back(head_of(b));
    for (int b : rig.chain(Part::Shin, side)) leg.path.push_back(head_of(b));
    glm::dvec3 ankle = head_of(rig.first(Part::Foot, side));
    leg.path.push_back(ankle);
    leg.path.push_back(ankle - at(0, 0.015, 0));
    for (auto [y, ru, rv, f] : std::vector<std::array<double, 4>>{{0.97, 0.085, 0.09, 0},
                                                                  {0.80, 0.075, 0.08, 0},
                                                                  {0.50, 0.05, 0.055, 0},
                                                                  {0.36, 0.052, 0.06, -0.01},
                                                                  {0.07, 0.033, 0.036, 0}})
      leg.profile.push_back(ring(by_y(y, 0.97, 0.07), ru, rv, f));
    add(leg.bones, rig.chain(Part::Hips));
    add(leg.bones, rig.chain(Part::Thigh, side));
    add(leg.bones, rig.chain(Part::Shin, side));
    add(leg.bones, {rig.first(Part::Foot, side)});
    tubes.push_back(leg);

    Tube foot{{at(s * 0.1, 0.045, -0.065), at(s * 0.105, 0.04, 0.11), at(s * 0.11, 0.028, 0.19)},
              {1, 0, 0},
              {ring(0, 0.03, 0.035), ring(0.25, 0.04, 0.04), ring(0.7, 0.048, 0.03), ring(1, 0.035, 0.016)},
              {}};
    add(foot.bones, {rig.last(Part::Shin, side), rig.first(Part::Foot, side), rig.first(Part::Toe, side)});
    tubes.push_back(foot);
  }
  return tubes;
}

size_t count_at(const std::vector<Tube>& tubes, double spacing) {
  size_t n = 0;
  for (const Tube& t : tubes) n += size_tube(t, spacing).vertices();
  return n;
}

}  // namespace

SkinnedMesh build_mesh(const Rig& rig, int vertices) {
  const std::vector<Tube> tubes = body_tubes(rig);
  const size_t want = static_cast<size_t>(vertices);
  // The finest even spacing that stays within the budget (the count falls as
  // the spacing grows); the few vertices left over are added by `pad`. At 1 m
  // every tube is at its coarsest (2 rings of 6): at most 20 x 14 vertices,
  // under kHumanoidMinVertices.
  double fine = 1e-4, coarse = 1.0;
  for (int i = 0; i < 100; ++i) {
    double mid = std::sqrt(fine * coarse);
    (count_at(tubes, mid) > want ? fine : coarse) = mid;
  }
  Builder builder;
  for (size_t t = 0; t < tubes.size(); ++t) builder.emit(tubes[t], int(t), size_tube(tubes[t], coarse));
  builder.pad(want - std::min(want, builder.positions.size()));

  SkinnedMesh mesh;
  const size_t n = builder.positions.size();
  std::vector<glm::dvec3> normals(n, glm::dvec3(0.0));
  for (size_t i = 0; i < builder.indices.size(); i += 3) {
    uint32_t a = builder.indices[i], b = builder.indices[i + 1], c = builder.indices[i + 2];
    glm::dvec3 f = glm::cross(builder.positions[b] - builder.positions[a], builder.positions[c] - builder.positions[a]);
    normals[a] += f, normals[b] += f, normals[c] += f;  // area-weighted
  }
  mesh.positions.reserve(n);
  mesh.joints.resize(n);
  mesh.weights.resize(n);
  for (size_t v = 0; v < n; ++v) {
    mesh.positions.push_back(stable_float(builder.positions[v]));
    mesh.normals.push_back(stable_float(glm::normalize(normals[v])));
    weigh(builder.positions[v], rig, tubes[static_cast<size_t>(builder.tube_of[v])].bones, mesh.joints[v],
          mesh.weights[v]);
  }
  mesh.indices = std::move(builder.indices);
  mesh.primitives.push_back({0, static_cast<uint32_t>(mesh.indices.size()), 0, static_cast<uint32_t>(n)});
  return mesh;
}

}  // namespace crowdprof::humanoid
