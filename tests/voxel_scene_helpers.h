// Voxel grids as scene descriptions, shared by the aggregate and voxel scene tests.
#pragma once
#include <memory>
#include <utility>

#include "geometry/mesh.h"
#include "scene/builder.h"
#include "voxel/voxel_shape.h"

namespace torte::test {

/// A voxel ShapeDesc of `v` placed by `t`.
inline ShapeDesc voxel_desc(std::shared_ptr<const VoxelShape> v, const Transform& t) {
  ShapeDesc s;
  s.kind = ShapeDesc::Kind::Voxel;
  s.voxels = std::move(v);
  s.transform = t;
  return s;
}

/// Grid `g` as a VoxelShape whose id -1 cells hold a slab, a cube mesh filling [0,1] x [0,0.5] x [0,1] of the
/// cell, of material `slab`; no cube definitions (the caller adds any).
inline std::shared_ptr<VoxelShape> slab_world(const VoxelGrid& g, std::shared_ptr<MaterialDesc> slab) {
  auto shape = std::make_shared<VoxelShape>();
  shape->tree = std::make_shared<VoxelTree>(VoxelTree::build(g));
  auto group = std::make_shared<SceneBuilder>();
  ShapeDesc cube;
  cube.mesh = std::make_shared<TriangleMesh>(make_cube());
  cube.transform = translate({0.5f, 0.25f, 0.5f}) * scale({0.5f, 0.25f, 0.5f});
  cube.material = std::move(slab);
  group->add_shape(cube);
  VoxelCellDef cell;
  cell.id = -1;
  cell.shapes = group;
  shape->cells = {cell};
  return shape;
}

}  // namespace torte::test
