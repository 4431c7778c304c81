// torte's traversal layout (WideBvh<N> + TriangleLeaves) over a tree from Embree's own SAH builder, for
// `embree-compare --tree embree`: torte's kernels on Embree's tree separate the tree's share of a speed difference
// from the kernel's. Built only with embree-compare (needs Embree 3).
#pragma once
#include <embree3/rtcore.h>

#include "workloads.h"

namespace torte::bench {

// rtcBuildBVH at RTC_BUILD_QUALITY_MEDIUM with the settings of Embree's BVH8Triangle4 scene builder (the one
// behind rtcIntersect1 on triangle meshes: binned SAH over triangle bounds, leaf cost per started block of 4,
// every set of at most 4 triangles a leaf, leaves of at most 28, traversal and intersection cost 1), N children
// per node. Embree's nodes and leaves are copied into torte's layout: nodes in depth-first pre-order, leaf order
// following the tree.
template <int N>
TorteAccel<N> build_torte_layout_of_embree_tree(RTCDevice device, const TriangleMesh& mesh);

}  // namespace torte::bench
