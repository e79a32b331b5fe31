// The culling audit (scene/culling_audit.h) on a case worked out by hand: a
// small triangle that an action carries 10 m along X, and a view that sees
// only where it ends up. Its bind-pose box never moves (a false cull when the
// triangle is in view); its action boxes span the whole path (a missed cull
// when it is not); the tight box is exact.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "one_joint_character.h"
#include "scene/culling_audit.h"

using namespace crowdprof;

namespace {

// A small tetrahedron (or, flat, one triangle in z = 0) at the origin.
Character slide(bool flat) {
  std::vector<glm::vec3> positions = {{0, 0, 0}, {0.5f, 0, 0}, {0, 0.5f, 0}};
  std::vector<uint32_t> indices = {0, 1, 2};
  if (!flat) {
    positions.push_back({0, 0, 0.5f});
    indices.insert(indices.end(), {0, 1, 3, 0, 3, 2, 1, 2, 3});
  }
  std::vector<glm::vec3> normals(positions.size(), glm::vec3(0, 0, 1));
  return test::one_joint_character("slide", positions, normals, indices, ChannelPath::Translation, {0, 0, 0, 10, 0, 0});
}

struct AuditCase {
  Character character;
  Crowd crowd;
  // x in [8, 12], y in [-2, 2], z in [-10, 10]: only the action's end is in view.
  Frustum frustum = frustum_of(glm::ortho(8.0f, 12.0f, -2.0f, 2.0f, -10.0f, 10.0f));
  explicit AuditCase(bool flat = false) : character(slide(flat)) {
    crowd.world = {glm::mat4(1.0f)};
    crowd.kind = {0};
    crowd.action = {0};
    crowd.phase = {0};
    crowd.character_boxes = {animated_bounds(character)};
    crowd.world_boxes = crowd.character_boxes;
  }
};

}  // namespace

TEST(CullingAudit, CountsFalseAndMissedCullsPerBox) {
  AuditCase c;
  const Character* characters[] = {&c.character};
  CullingAuditor auditor(characters, c.crowd, c.frustum);
  const float start[] = {0.0f}, end[] = {1.0f};
  auditor.add_frame(start);  // at the origin: outside the view
  auditor.add_frame(end);    // at x = 10: inside it
  const CullingAudit& a = auditor.audit();
  EXPECT_EQ(a.frames, 2u);
  EXPECT_EQ(a.copies, 1u);
  EXPECT_EQ(a.in_view, 1u);
  EXPECT_EQ(a.outside, 1u);
  EXPECT_EQ(a.undecided, 0u);
  const CullBoxAudit& bind = a.boxes[static_cast<size_t>(CullBox::BindPose)];
  EXPECT_EQ(bind.drawn, 0u);
  EXPECT_EQ(bind.false_culls, 1u) << "the box stays at the origin while the triangle is in view";
  EXPECT_EQ(bind.missed_culls, 0u);
  for (CullBox box : {CullBox::EveryAction, CullBox::OwnAction}) {
    const CullBoxAudit& b = a.boxes[static_cast<size_t>(box)];
    EXPECT_EQ(b.drawn, 2u) << cull_box_name(box);
    EXPECT_EQ(b.false_culls, 0u) << cull_box_name(box);
    EXPECT_EQ(b.missed_culls, 1u) << cull_box_name(box) << ": the box spans the path, drawn at the origin too";
    EXPECT_EQ(b.worst_frame_missed_culls, 1u);
    EXPECT_GT(b.slack_mean, 1.0) << cull_box_name(box);
  }
  const CullBoxAudit& tight = a.boxes[static_cast<size_t>(CullBox::Tight)];
  EXPECT_EQ(tight.drawn, 1u);
  EXPECT_EQ(tight.false_culls + tight.missed_culls, 0u);
}

TEST(CullingAudit, FlatMeshHasNoSlackToReport) {
  // The triangle lies in z = 0: its tight box has no volume, so no ratio is taken.
  AuditCase c(true);
  const Character* characters[] = {&c.character};
  CullingAuditor auditor(characters, c.crowd, c.frustum);
  const float end[] = {1.0f};
  auditor.add_frame(end);
  for (const CullBoxAudit& b : auditor.audit().boxes) {
    EXPECT_EQ(b.slack_mean, 0.0);
    EXPECT_EQ(b.slack_max, 0.0);
  }
}

TEST(CullingAudit, SameOnAnyThreadsAndStride) {
  AuditCase c;
  // Forty copies in a row along X, so some start in view and some end there.
  c.crowd = Crowd{};
  for (int i = 0; i < 40; ++i) {
    c.crowd.world.push_back(glm::translate(glm::mat4(1.0f), glm::vec3(static_cast<float>(i) * 0.5f - 10.0f, 0, 0.1f)));
    c.crowd.kind.push_back(0);
    c.crowd.action.push_back(0);
    c.crowd.phase.push_back(0);
    c.crowd.world_boxes.push_back(transform_aabb(animated_bounds(c.character), c.crowd.world.back()));
  }
  const Character* characters[] = {&c.character};
  std::vector<float> times(40);
  for (size_t i = 0; i < times.size(); ++i) times[i] = static_cast<float>(i % 7) / 7.0f;
  CullingAuditor one(characters, c.crowd, c.frustum), two(characters, c.crowd, c.frustum),
      strided(characters, c.crowd, c.frustum, 4);
  tbb::task_arena single(1), pair(2);
  one.add_frame(times, &single);
  two.add_frame(times, &pair);
  strided.add_frame(times, &pair);
  EXPECT_EQ(one.audit().in_view, two.audit().in_view);
  EXPECT_GT(one.audit().in_view, 0u);
  for (size_t b = 0; b < kCullBoxes; ++b) {
    EXPECT_EQ(one.audit().boxes[b].false_culls, two.audit().boxes[b].false_culls);
    EXPECT_EQ(one.audit().boxes[b].missed_culls, two.audit().boxes[b].missed_culls);
    EXPECT_EQ(one.audit().boxes[b].slack_mean, two.audit().boxes[b].slack_mean);
  }
  EXPECT_EQ(strided.audit().copies, 10u);
  EXPECT_EQ(strided.audit().copy_stride, 4u);
  EXPECT_EQ(strided.audit().in_view + strided.audit().outside + strided.audit().undecided, 10u);
}
