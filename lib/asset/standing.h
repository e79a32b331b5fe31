// How a character stands in its scene: its rest pose (each joint's own
// translation, rotation and scale, as the file gives them) skinned into glTF
// world space through every node above the joints, +Y up. The mesh's own
// coordinates are not that: an export modelled Z-up, or in centimetres, is
// turned upright and scaled by its nodes, so only the skinned rest pose says
// how tall the character stands. Every height, and every distance given in
// millimetres, a share of the height or pixels, is taken from here.
#pragma once

#include "asset/character.h"

namespace crowdprof {

struct Standing {
  float height = 0;  // extent in Y, world units (glTF's metres)
  // How long one unit of the mesh's own (bind-pose) space is in world space:
  // the rest pose's skinning scale (the cube root of its determinant, averaged
  // over the vertices). A distance measured on the bind-pose mesh (mesh LOD's
  // error) times this is a world distance. 1 for a mesh modelled in world units.
  float world_per_mesh_unit = 1;
};

// Skins the bind-pose mesh with the rest pose in plain glm arithmetic, once
// per call (a few microseconds a thousand vertices). Allocates. A character
// without vertices stands 0 high.
Standing standing_of(const Character& character);

}  // namespace crowdprof
