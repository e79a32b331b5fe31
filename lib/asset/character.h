// The shared, immutable description of one skinned, animated character: what the
// loader (gltf_loader.h) and the generator (humanoid.h) produce, and what every
// copy in a crowd reads. Per-copy state lives elsewhere (animation/pose.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "asset/slerp_segment.h"

namespace crowdprof {

// Joints in parent-before-child order: parents[j] < j, or -1 for a root.
struct Skeleton {
  std::vector<std::string> names;
  std::vector<int> parents;
  std::vector<glm::vec3> rest_translations;
  std::vector<glm::quat> rest_rotations;
  std::vector<glm::vec3> rest_scales;
  std::vector<glm::mat4> inverse_binds;
  // glTF places a joint by all its ancestors, joints or not. This is the fixed
  // transform of the non-joint nodes between a joint and its parent joint (for a
  // root: between it and the scene root). Identity for almost every joint.
  std::vector<glm::mat4> parent_offsets;

  size_t joint_count() const { return names.size(); }
  // Joints on the longest root-to-leaf chain (a lone root has depth 1).
  int depth() const;
};

// A range of the mesh's index buffer, from one glTF primitive.
struct Primitive {
  uint32_t first_index = 0;
  uint32_t index_count = 0;
  uint32_t first_vertex = 0;
  uint32_t vertex_count = 0;
};

// All primitives of the skinned mesh(es) bound to one skin, in one vertex array.
struct SkinnedMesh {
  std::vector<glm::vec3> positions;  // bind pose, in the skin's model space
  std::vector<glm::vec3> normals;    // unit length
  std::vector<glm::u16vec4> joints;  // indices into Skeleton; unused slots 0
  std::vector<glm::vec4> weights;    // sorted largest first, sum to 1; unused slots 0
  std::vector<uint32_t> indices;     // triangle list, indices into the whole vertex array
  std::vector<Primitive> primitives;

  size_t vertex_count() const { return positions.size(); }
  size_t triangle_count() const { return indices.size() / 3; }
};

enum class Interpolation : uint8_t { Step, Linear, CubicSpline };
enum class ChannelPath : uint8_t { Translation, Rotation, Scale };

const char* to_string(Interpolation interpolation);
const char* to_string(ChannelPath path);

// One animated property of one joint, as glTF stores it.
struct Channel {
  int joint = 0;
  ChannelPath path = ChannelPath::Translation;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<float> times;  // seconds, strictly increasing
  // Per key: `components()` floats, or for CUBICSPLINE three groups of them
  // (in-tangent, value, out-tangent), as in glTF. Rotations are x, y, z, w.
  std::vector<float> values;
  // LINEAR rotations: per key segment k (keys k and k+1), what slerp needs of the
  // pair alone (asset/slerp_segment.h), so sampling pays only two sines a
  // sample. Set by prepare_slerp (the loader and the generator call it); empty
  // otherwise, and sampling then works it out per sample, to the same bits.
  // Derived from `values`: call prepare_slerp again after changing them.
  // Not counted in Character::shared_bytes (12 bytes a rotation key segment).
  std::vector<SlerpSegment> slerp;

  int components() const { return path == ChannelPath::Rotation ? 4 : 3; }
  size_t key_count() const { return times.size(); }
};

// Fills `channel->slerp` for a LINEAR rotation channel of two keys or more;
// clears it for any other.
void prepare_slerp(Channel* channel);

// One glTF animation restricted to the skeleton's joints.
struct Action {
  std::string name;
  float start = 0.0f;  // first key time over all channels (may be > 0)
  float end = 0.0f;    // last key time over all channels
  std::vector<Channel> channels;

  float duration() const { return end - start; }
};

// What the loader had to repair. Reported by `info`, never applied silently.
struct Fixups {
  size_t influences_trimmed = 0;    // vertices with > 4 influences cut to the 4 largest
  size_t weights_renormalised = 0;  // vertices whose weights did not sum to 1
  size_t weightless_vertices = 0;   // vertices with all weights 0, bound to joint 0
  size_t normals_computed = 0;      // vertices whose normals were computed from faces
  size_t rotations_normalised = 0;  // rotation keys that were not unit quaternions
  size_t channels_dropped = 0;      // channels on nodes outside the skeleton (or weights)
  size_t names_made_unique = 0;     // joints renamed: nameless, or a name used twice
  size_t actions_dropped = 0;       // animations left with no channel on this skin's joints
  size_t total() const {
    return influences_trimmed + weights_renormalised + weightless_vertices + normals_computed + rotations_normalised +
           channels_dropped + names_made_unique + actions_dropped;
  }
};

struct Character {
  std::string name;
  Skeleton skeleton;
  SkinnedMesh mesh;
  // Coarser meshes the file gives itself (MSFT_lod on the skinned mesh's
  // nodes), finest first, bound to the same skeleton; empty when it gives none
  // (mesh LOD then simplifies `mesh`, asset/mesh_lod.h).
  std::vector<SkinnedMesh> file_lods;
  // Per file level: its surface distance from `mesh` (asset/mesh_lod.h's
  // surface_distance), measured at load, in the mesh's own units.
  std::vector<float> file_lod_errors;
  std::vector<Action> actions;
  Fixups fixups;
  bool draco_decoded = false;

  // Bytes the shared data holds (skeleton, mesh, actions), not counting names.
  size_t shared_bytes() const;
};

}  // namespace crowdprof
