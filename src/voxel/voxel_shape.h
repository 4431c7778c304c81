// A voxel grid as the scene builder holds it (ShapeDesc::Kind::Voxel): the built kd-tree, shared by every
// placement, and what each voxel id looks like. Filled by the Lua bindings (lua/bind_voxel.cc).
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/rgb.h"

#include "voxel/voxel_tree.h"

namespace torte {

struct MaterialDesc;
class SceneBuilder;

// A solid id (> 0): a material per face (0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z); null = the shape's material.
struct VoxelCubeDef {
  int16_t id = 1;
  std::array<std::shared_ptr<const MaterialDesc>, 6> faces;
  Rgb emission;  // radiance of every exposed face (black: does not emit)
};

// A cell-shape id (< 0): a group of shapes modelling the unit cell [0, 1]^3 (meshes and analytic shapes with
// their own materials; no instances). Meshes may emit (their `emission`); they emit on both sides.
struct VoxelCellDef {
  int16_t id = -1;
  std::shared_ptr<const SceneBuilder> shapes;
};

struct VoxelShape {
  std::shared_ptr<const VoxelTree> tree;
  std::vector<VoxelCubeDef> cubes;
  std::vector<VoxelCellDef> cells;
};

}  // namespace torte
