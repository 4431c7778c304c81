// See embree_tree.h.
#include "embree_tree.h"

#include <cstdio>
#include <string>
#include <vector>

#include "core/error.h"

namespace torte::bench {
namespace {

// Embree's BVH8Triangle4 builder settings (Embree 3.13, kernels/bvh/bvh_builder_sah.cpp: sahBlockSize 4,
// intersection cost 1, minLeafSize 4; maxLeafSize is 4 triangles times 7 leaf blocks).
constexpr unsigned kSahBlock = 4, kMinLeaf = 4, kMaxLeaf = 28;

// A node or a leaf as the builder's callbacks make it (in Embree's thread-local build memory).
struct BuiltNode {
  bool leaf;
  unsigned count;  // children, or triangles of a leaf
  void* child[8];
  RTCBounds bounds[8];
  uint32_t tris[kMaxLeaf];
};

void* create_node(RTCThreadLocalAllocator alloc, unsigned children, void*) {
  auto* n = static_cast<BuiltNode*>(rtcThreadLocalAlloc(alloc, sizeof(BuiltNode), 16));
  n->leaf = false;
  n->count = children;
  return n;
}
void set_children(void* node, void** children, unsigned count, void*) {
  for (unsigned i = 0; i < count; ++i) static_cast<BuiltNode*>(node)->child[i] = children[i];
}
void set_bounds(void* node, const RTCBounds** bounds, unsigned count, void*) {
  for (unsigned i = 0; i < count; ++i) static_cast<BuiltNode*>(node)->bounds[i] = *bounds[i];
}
void* create_leaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims, size_t count, void*) {
  if (count > kMaxLeaf) return nullptr;  // makes rtcBuildBVH fail: never happens with maxLeafSize = kMaxLeaf
  auto* n = static_cast<BuiltNode*>(rtcThreadLocalAlloc(alloc, sizeof(BuiltNode), 16));
  n->leaf = true;
  n->count = unsigned(count);
  for (size_t i = 0; i < count; ++i) n->tris[i] = prims[i].primID;
  return n;
}

Bounds3f to_bounds(const RTCBounds& b) { return {{b.lower_x, b.lower_y, b.lower_z}, {b.upper_x, b.upper_y, b.upper_z}}; }

// Copies Embree's tree into torte's layout: `node` and its subtree, depth first; returns the node's index.
template <int N>
uint32_t copy_subtree(const BuiltNode& node, WideBvh<N>& bvh) {
  const uint32_t index = uint32_t(bvh.nodes.size());
  bvh.nodes.emplace_back();
  Bounds3f bounds[N];
  uint32_t child[N], leaf_count[N];
  for (unsigned i = 0; i < node.count; ++i) {
    const BuiltNode& c = *static_cast<const BuiltNode*>(node.child[i]);
    bounds[i] = to_bounds(node.bounds[i]);
    leaf_count[i] = c.leaf ? c.count : 0;
    if (c.leaf) {
      child[i] = kLeafFlag | uint32_t(bvh.prim_indices.size());
      bvh.prim_indices.insert(bvh.prim_indices.end(), c.tris, c.tris + c.count);
    } else {
      child[i] = copy_subtree<N>(c, bvh);  // may reallocate bvh.nodes: index, not reference
    }
  }
  write_wide_node<N>(bvh.nodes[index], int(node.count), bounds, child, leaf_count);
  return index;
}

}  // namespace

template <int N>
TorteAccel<N> build_torte_layout_of_embree_tree(RTCDevice device, const TriangleMesh& mesh) {
  const std::vector<Bounds3f> bounds = triangle_bounds(mesh);
  std::vector<RTCBuildPrimitive> prims(bounds.size());
  for (size_t i = 0; i < bounds.size(); ++i) {
    const Bounds3f& b = bounds[i];
    prims[i] = {b.lo.x, b.lo.y, b.lo.z, 0u, b.hi.x, b.hi.y, b.hi.z, uint32_t(i)};
  }
  RTCBVH handle = rtcNewBVH(device);
  RTCBuildArguments args = rtcDefaultBuildArguments();
  args.byteSize = sizeof(args);
  args.buildQuality = RTC_BUILD_QUALITY_MEDIUM;
  args.maxBranchingFactor = N;
  args.sahBlockSize = kSahBlock;
  args.minLeafSize = kMinLeaf;
  args.maxLeafSize = kMaxLeaf;
  args.traversalCost = 1.0f;
  args.intersectionCost = 1.0f;
  args.bvh = handle;
  args.primitives = prims.data();
  args.primitiveCount = prims.size();
  args.primitiveArrayCapacity = prims.size();
  args.createNode = create_node;
  args.setNodeChildren = set_children;
  args.setNodeBounds = set_bounds;
  args.createLeaf = create_leaf;
  const auto* root = static_cast<const BuiltNode*>(rtcBuildBVH(&args));
  TorteAccel<N> accel;
  if (root == nullptr || root->leaf) {
    rtcReleaseBVH(handle);
    throw Error("embree-compare: rtcBuildBVH gave no tree (or a single leaf) for " +
                std::to_string(mesh.triangle_count()) + " triangles.");
  }
  accel.bvh.prim_indices.reserve(prims.size());
  copy_subtree<N>(*root, accel.bvh);
  for (unsigned i = 0; i < root->count; ++i) accel.bvh.bounds.extend(to_bounds(root->bounds[i]));
  rtcReleaseBVH(handle);  // frees every BuiltNode
  if (accel.bvh.prim_indices.size() != mesh.triangle_count())
    throw Error("embree-compare: Embree's tree holds " + std::to_string(accel.bvh.prim_indices.size()) + " of " +
                std::to_string(mesh.triangle_count()) + " triangles.");
  accel.leaves = make_triangle_leaves<N>(accel.bvh, mesh, /*parallel=*/true);
  return accel;
}

template TorteAccel<4> build_torte_layout_of_embree_tree<4>(RTCDevice, const TriangleMesh&);
template TorteAccel<8> build_torte_layout_of_embree_tree<8>(RTCDevice, const TriangleMesh&);

}  // namespace torte::bench
