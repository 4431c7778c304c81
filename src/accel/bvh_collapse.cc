// Collapse of the binary BVH into WideBvh<N> (SAH-optimal dynamic programming or the greedy largest-area rule),
// the wide tree's SAH cost and statistics. See bvh_build.h; triangle leaves are in triangle_leaves.cc.

#include <algorithm>
#include <string>

#include "accel/bvh_build.h"
#include "core/error.h"
#include "core/parallel.h"

namespace torte {

// One wide node from k occupied slots (see bvh_build.h).
template <int N>
void write_wide_node(WideNode<N>& w, int k, const Bounds3f* bounds, const uint32_t* child, const uint32_t* count) {
  for (int i = 0; i < N; ++i) {
    const bool used = i < k;
    const Bounds3f box = used ? bounds[i] : Bounds3f{};  // empty: lo = +inf, hi = -inf
    w.lo_x[i] = box.lo.x, w.lo_y[i] = box.lo.y, w.lo_z[i] = box.lo.z;
    w.hi_x[i] = box.hi.x, w.hi_y[i] = box.hi.y, w.hi_z[i] = box.hi.z;
    w.child[i] = used ? child[i] : kEmptyChild;
    if (used && (child[i] & kLeafFlag) && count[i] > 255)
      throw Error("BVH collapse: a leaf holds " + std::to_string(count[i]) +
                  " primitives; wide leaves hold at most 255.");
    w.leaf_count[i] = used && (child[i] & kLeafFlag) ? uint8_t(count[i]) : 0;
  }
}

namespace {

// The SAH dynamic programme runs the two subtrees of every node this close to the root as parallel tasks
// (2^10 tasks at most), if the tree is big enough for tasks to pay.
constexpr int kParallelDepth = 10;
constexpr size_t kParallelNodesMin = 8192;

// Greedy collapse: open the largest-area interior slot until N slots are filled.
template <int N>
class GreedyCollapser {
 public:
  GreedyCollapser(const BinaryBvh& binary, WideBvh<N>& wide) : bin_(binary.nodes), wide_(wide) {}

  // Emits the wide node for binary node `b` and, depth first, its subtrees; returns its index.
  uint32_t emit(uint32_t b) {
    const uint32_t index = uint32_t(wide_.nodes.size());
    wide_.nodes.emplace_back();  // value-initialised: padding bytes are zero, so nodes compare bytewise
    // Keep left-to-right order so leaf order stays the binary tree's. A root that is a leaf is its own slot.
    uint32_t slot[N];
    int k = 0;
    if (bin_[b].count > 0) {
      slot[k++] = b;
    } else {
      slot[k++] = bin_[b].first;
      slot[k++] = bin_[b].first + 1;
    }
    while (k < N) {
      int best = -1;
      float best_area = -1;
      for (int i = 0; i < k; ++i) {
        const BinaryBvhNode& n = bin_[slot[i]];
        if (n.count == 0 && n.bounds.surface_area() > best_area) {
          best = i;
          best_area = n.bounds.surface_area();
        }
      }
      if (best < 0) break;  // only leaves left: the node keeps empty slots
      const uint32_t first = bin_[slot[best]].first;
      for (int i = k; i > best + 1; --i) slot[i] = slot[i - 1];
      slot[best] = first;
      slot[best + 1] = first + 1;
      ++k;
    }
    Bounds3f bounds[N];
    uint32_t child[N], count[N];
    for (int i = 0; i < k; ++i) {
      const BinaryBvhNode& n = bin_[slot[i]];
      bounds[i] = n.bounds;
      count[i] = n.count;
      child[i] = n.count == 0 ? emit(slot[i]) : kLeafFlag | n.first;  // emit may reallocate wide_.nodes
    }
    write_wide_node<N>(wide_.nodes[index], k, bounds, child, count);
    return index;
  }

 private:
  const HugePageVector<BinaryBvhNode>& bin_;
  WideBvh<N>& wide_;
};

// SAH-optimal collapse (Ylitie, Karras & Laine 2017, sec. 3.1). For every binary node n and i = 1..N, c(n, i) is
// the cheapest way to represent n's subtree as at most i slots of the parent wide node:
//   c(n, 1) = min(leaf(n), A(n) * traversal_cost + dist(n, N))   leaf(n) = A(n) * leaf_sah_cost(count) if
//   c(n, i) = min(c(n, i - 1), dist(n, i))                         count <= max_leaf_size, else infinite
//   dist(n, j) = min over 0 < k < j of c(left, k) + c(right, j - k)
// and a binary leaf costs leaf(n) for every i. Bottom up in parallel, then the choices are replayed top down.
template <int N>
class OptimalCollapser {
 public:
  OptimalCollapser(const BinaryBvh& binary, const BvhBuildOptions& options, WideBvh<N>& wide)
      : bin_(binary.nodes), o_(options), wide_(wide), dp_(make_huge_page_vector<Choice>(binary.nodes.size())) {
    // Every area gets a tiny floor so zero-area subtrees still prefer fewer nodes (ties broken toward memory);
    // with a zero-area root every node weighs the same, as in sah_cost.
    const float root_area = bin_[0].bounds.surface_area();
    area_floor_ = root_area > 0 ? root_area * 1e-9f : 1.0f;
  }

  void run() {
    solve(0, 0);
    if (!dp_[0].leaf) {
      emit(0);
      return;
    }
    wide_.nodes.emplace_back();  // the whole tree is one leaf: a root with one leaf child
    const uint32_t child = kLeafFlag | dp_[0].first;
    write_wide_node<N>(wide_.nodes[0], 1, &bin_[0].bounds, &child, &dp_[0].count);
  }

 private:
  // 4N + N + 10 bytes, 52 for N = 8 (one per binary node, freed after the collapse).
  struct Choice {
    float c[N];             // c[i] = c(n, i + 1)
    uint8_t split[N];       // split[i]: slots given to the left child for c[i]; 0: c[i] == c[i - 1]
    uint32_t first, count;  // primitive range of the subtree (contiguous: leaves are in depth-first order)
    uint8_t node_split;     // slots given to the left child when the subtree is one wide node
    bool leaf;              // c(n, 1) is a leaf rather than a wide node
  };

  void solve(uint32_t n, int depth) {
    Choice& e = dp_[n];
    const BinaryBvhNode& b = bin_[n];
    const float area = b.bounds.surface_area() + area_floor_;
    if (b.count > 0) {
      e.first = b.first;
      e.count = b.count;
      e.leaf = true;
      std::fill(e.c, e.c + N, area * leaf_sah_cost(b.count, o_));
      std::fill(e.split, e.split + N, uint8_t(0));
      return;
    }
    const uint32_t l = b.first, r = b.first + 1;
    if (o_.parallel && depth < kParallelDepth && bin_.size() >= kParallelNodesMin) {
      parallel_invoke([&] { solve(l, depth + 1); }, [&] { solve(r, depth + 1); });
    } else {
      solve(l, depth + 1);
      solve(r, depth + 1);
    }
    const Choice &L = dp_[l], &R = dp_[r];
    e.first = L.first;
    e.count = L.count + R.count;
    float dist[N + 1];
    uint8_t arg[N + 1];
    for (int j = 2; j <= N; ++j) {
      dist[j] = L.c[0] + R.c[j - 2];
      arg[j] = 1;
      for (int k = 2; k < j; ++k) {
        const float v = L.c[k - 1] + R.c[j - k - 1];
        if (v < dist[j]) {
          dist[j] = v;
          arg[j] = uint8_t(k);
        }
      }
    }
    const float node = area * o_.traversal_cost + dist[N];
    const float leaf = e.count <= uint32_t(o_.max_leaf_size) ? area * leaf_sah_cost(e.count, o_) : kInfinity;
    e.leaf = leaf <= node;  // ties: a leaf saves a node
    e.c[0] = std::min(leaf, node);
    e.split[0] = 0;
    e.node_split = arg[N];
    for (int i = 1; i < N; ++i) {
      const bool more = dist[i + 1] < e.c[i - 1];
      e.c[i] = more ? dist[i + 1] : e.c[i - 1];
      e.split[i] = more ? arg[i + 1] : 0;
    }
  }

  // Appends the slots that represent binary node n with at most i slots, left to right.
  void gather(uint32_t n, int i, uint32_t* slot, int& k) const {
    const Choice& e = dp_[n];
    while (i > 1 && e.split[i - 1] == 0) --i;
    if (i == 1) {
      slot[k++] = n;
      return;
    }
    gather(bin_[n].first, e.split[i - 1], slot, k);
    gather(bin_[n].first + 1, i - e.split[i - 1], slot, k);
  }

  // Emits binary node n (interior, chosen as a wide node) and, depth first, its subtrees; returns its index.
  uint32_t emit(uint32_t n) {
    const uint32_t index = uint32_t(wide_.nodes.size());
    wide_.nodes.emplace_back();  // value-initialised: padding bytes are zero, so nodes compare bytewise
    uint32_t slot[N];
    int k = 0;
    gather(bin_[n].first, dp_[n].node_split, slot, k);
    gather(bin_[n].first + 1, N - dp_[n].node_split, slot, k);
    Bounds3f bounds[N];
    uint32_t child[N], count[N];
    for (int i = 0; i < k; ++i) {
      const Choice& e = dp_[slot[i]];
      bounds[i] = bin_[slot[i]].bounds;
      count[i] = e.count;
      child[i] = e.leaf ? kLeafFlag | e.first : emit(slot[i]);  // emit may reallocate wide_.nodes
    }
    write_wide_node<N>(wide_.nodes[index], k, bounds, child, count);
    return index;
  }

  const HugePageVector<BinaryBvhNode>& bin_;
  const BvhBuildOptions& o_;
  WideBvh<N>& wide_;
  HugePageVector<Choice> dp_;  // from huge_pages like the trees: it takes the pages the references left
  float area_floor_;
};

template <int N>
Bounds3f slot_bounds(const WideNode<N>& n, int i) {
  return {{n.lo_x[i], n.lo_y[i], n.lo_z[i]}, {n.hi_x[i], n.hi_y[i], n.hi_z[i]}};
}

// The wide nodes and bounds; the callers copy or move the primitive order.
template <int N>
WideBvh<N> collapse_nodes(const BinaryBvh& binary, const BvhBuildOptions& options) {
  WideBvh<N> wide;
  if (binary.nodes.empty()) return wide;
  // About one wide node per N - 1 binary interior nodes (a full collapse); a reserve, not a bound.
  wide.nodes.reserve(binary.nodes.size() / (2 * (N - 1)) + 1);
  if (options.collapse == CollapseMode::LargestArea) {
    GreedyCollapser<N>(binary, wide).emit(0);
  } else {
    OptimalCollapser<N>(binary, options, wide).run();
  }
  wide.nodes.shrink_to_fit();
  wide.bounds = binary.nodes[0].bounds;
  return wide;
}

}  // namespace

template <int N>
WideBvh<N> collapse(const BinaryBvh& binary, const BvhBuildOptions& options) {
  WideBvh<N> wide = collapse_nodes<N>(binary, options);
  wide.prim_indices = binary.prim_indices;
  return wide;
}

template <int N>
WideBvh<N> build_wide_bvh(std::span<const Bounds3f> prim_bounds, const BvhBuildOptions& options) {
  BinaryBvh binary = build_binary_bvh(prim_bounds, options);
  WideBvh<N> wide = collapse_nodes<N>(binary, options);
  wide.prim_indices = std::move(binary.prim_indices);
  return wide;
}

template <int N>
WideBvh<N> build_wide_bvh(size_t count, const PrimBoundsFn& bounds, const BvhBuildOptions& options) {
  BinaryBvh binary = build_binary_bvh(count, bounds, options);
  WideBvh<N> wide = collapse_nodes<N>(binary, options);
  wide.prim_indices = std::move(binary.prim_indices);
  return wide;
}

template <int N>
float sah_cost(const WideBvh<N>& bvh, const BvhBuildOptions& options) {
  if (bvh.nodes.empty()) return 0;
  const float root_area = bvh.bounds.surface_area();
  auto p = [&](const Bounds3f& b) { return root_area > 0 ? double(b.surface_area()) / root_area : 1.0; };
  double cost = 0;
  // (node, its bounds' area weight); nodes are visited once each.
  std::vector<std::pair<uint32_t, double>> stack{{0, p(bvh.bounds)}};
  while (!stack.empty()) {
    const auto [index, weight] = stack.back();
    stack.pop_back();
    cost += weight * options.traversal_cost;
    const WideNode<N>& n = bvh.nodes[index];
    for (int i = 0; i < N; ++i) {
      if (n.child[i] == kEmptyChild) continue;
      const double w = p(slot_bounds(n, i));
      if (n.child[i] & kLeafFlag) cost += w * leaf_sah_cost(n.leaf_count[i], options);
      else stack.push_back({n.child[i], w});
    }
  }
  return float(cost);
}

template <int N>
BvhStats bvh_stats(const WideBvh<N>& bvh) {
  BvhStats s;
  s.nodes = bvh.nodes.size();
  s.node_bytes = s.nodes * sizeof(WideNode<N>);
  s.index_bytes = bvh.prim_indices.size() * sizeof(uint32_t);
  if (bvh.nodes.empty()) return s;
  size_t slots = 0;
  std::vector<std::pair<uint32_t, int>> stack{{0, 0}};
  while (!stack.empty()) {
    const auto [index, depth] = stack.back();
    stack.pop_back();
    s.max_depth = std::max(s.max_depth, depth);
    const WideNode<N>& n = bvh.nodes[index];
    for (int i = 0; i < N; ++i) {
      if (n.child[i] == kEmptyChild) continue;
      ++slots;
      if (n.child[i] & kLeafFlag) {
        ++s.leaves;
        s.primitives += n.leaf_count[i];
        s.max_depth = std::max(s.max_depth, depth + 1);
      } else {
        stack.push_back({n.child[i], depth + 1});
      }
    }
  }
  s.avg_leaf_size = s.leaves ? double(s.primitives) / double(s.leaves) : 0;
  s.avg_children = double(slots) / double(s.nodes);
  return s;
}

template void write_wide_node<4>(WideNode<4>&, int, const Bounds3f*, const uint32_t*, const uint32_t*);
template void write_wide_node<8>(WideNode<8>&, int, const Bounds3f*, const uint32_t*, const uint32_t*);
template WideBvh<4> collapse<4>(const BinaryBvh&, const BvhBuildOptions&);
template WideBvh<8> collapse<8>(const BinaryBvh&, const BvhBuildOptions&);
template WideBvh<4> build_wide_bvh<4>(std::span<const Bounds3f>, const BvhBuildOptions&);
template WideBvh<8> build_wide_bvh<8>(std::span<const Bounds3f>, const BvhBuildOptions&);
template WideBvh<4> build_wide_bvh<4>(size_t, const PrimBoundsFn&, const BvhBuildOptions&);
template WideBvh<8> build_wide_bvh<8>(size_t, const PrimBoundsFn&, const BvhBuildOptions&);
template float sah_cost<4>(const WideBvh<4>&, const BvhBuildOptions&);
template float sah_cost<8>(const WideBvh<8>&, const BvhBuildOptions&);
template BvhStats bvh_stats<4>(const WideBvh<4>&);
template BvhStats bvh_stats<8>(const WideBvh<8>&);

}  // namespace torte
