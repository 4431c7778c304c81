#include "voxel/voxel_tree.h"


#include <atomic>
#include <chrono>
#include <climits>

#include "core/error.h"
#include "core/memory_budget.h"
#include "core/parallel.h"

namespace torte {

namespace {

constexpr int32_t kMixed = INT32_MIN;

// Children-first recursion over the implicit tree. Invariant: a call that returns a leaf leaves `out` as it found
// it, so two equal leaf children merge by truncating their pair. `out` always has an even size (pairs only).
struct TreeBuilder {
  int cn[3];                                 // root box in chunks per axis
  std::vector<const VoxelChunk*> chunks;     // dense over the root box, x fastest
  std::vector<int32_t> uniform;              // the chunk's single id, or kMixed

  size_t cidx(int cx, int cy, int cz) const { return (size_t(cz) * size_t(cn[1]) + size_t(cy)) * size_t(cn[0]) + size_t(cx); }

  // Is the chunk-aligned box one id? (absent chunks are 0)
  bool uniform_chunks(const int lo[3], const int lg[3], int32_t* id) const {
    const int c0[3] = {lo[0] >> kVoxelChunkBits, lo[1] >> kVoxelChunkBits, lo[2] >> kVoxelChunkBits};
    const int n[3] = {1 << (lg[0] - kVoxelChunkBits), 1 << (lg[1] - kVoxelChunkBits), 1 << (lg[2] - kVoxelChunkBits)};
    const int32_t first = uniform[cidx(c0[0], c0[1], c0[2])];
    if (first == kMixed) return false;
    for (int z = 0; z < n[2]; ++z)
      for (int y = 0; y < n[1]; ++y) {
        const size_t row = cidx(c0[0], c0[1] + y, c0[2] + z);
        for (int x = 0; x < n[0]; ++x)
          if (uniform[row + size_t(x)] != first) return false;
      }
    *id = first;
    return true;
  }

  VoxelNode node(const int lo_in[3], const int lg_in[3], const VoxelChunk* c, std::vector<VoxelNode>& out) const {
    int lo[3] = {lo_in[0], lo_in[1], lo_in[2]}, lg[3] = {lg_in[0], lg_in[1], lg_in[2]};
    if (!c) {  // a box of whole chunks
      int32_t id;
      if (uniform_chunks(lo, lg, &id)) return VoxelNode::leaf(int16_t(id));
      if (lg[0] == kVoxelChunkBits && lg[1] == kVoxelChunkBits && lg[2] == kVoxelChunkBits)
        c = chunks[cidx(lo[0] >> kVoxelChunkBits, lo[1] >> kVoxelChunkBits, lo[2] >> kVoxelChunkBits)];
    } else if (lg[0] == 0 && lg[1] == 0 && lg[2] == 0) {
      constexpr int m = kVoxelChunkSize - 1;
      return VoxelNode::leaf(c->ids[size_t(voxel_chunk_index(lo[0] & m, lo[1] & m, lo[2] & m))]);
    }
    const int a = voxel_split_axis(lg);
    int clg[3] = {lg[0], lg[1], lg[2]};
    --clg[a];
    int hi_lo[3] = {lo[0], lo[1], lo[2]};
    hi_lo[a] += 1 << clg[a];
    const size_t pair = out.size();
    if (pair / 2 > VoxelNode::kPairMask) throw Error("voxel grid: more than 2^30 tree nodes");
    out.resize(pair + 2);
    const VoxelNode wa = node(lo, clg, c, out);
    const VoxelNode wb = node(hi_lo, clg, c, out);
    if (wa.is_leaf() && wa == wb) {
      out.resize(pair);
      return wa;
    }
    out[pair] = wa;
    out[pair + 1] = wb;
    return VoxelNode::inner(a, uint32_t(pair / 2));
  }
  // Parallel build. The serial recursion lays nodes out in pre-order (a node's children pair, then the left
  // child's subtree, then the right one's), so a subtree's nodes are contiguous and, relative to their start,
  // independent of where they land. The top levels are planned serially down to boxes of `cut` log2 cells (or
  // uniform boxes, which are leaves); those subtrees are built as independent tasks (parallel_for, dynamic
  // balancing over many tasks), then the top levels are laid out serially exactly as the serial recursion would
  // (merging equal leaf children), and the subtrees are copied to their places in parallel with their children
  // indices shifted. The result is identical to the serial build.
  struct Top {
    int kind = 0;  // 0 leaf, 1 task, 2 inner
    VoxelNode leaf;
    int axis = 0, task = -1, child[2] = {-1, -1};
    VoxelNode result;  // after the tasks: the node this box becomes (leaf, task root, or inner before layout)
  };
  struct Task {
    int lo[3], lg[3];
    std::vector<VoxelNode> nodes;
    VoxelNode root;
    size_t dest = 0;
  };

  int plan(const int lo[3], const int lg[3], int cut, std::vector<Top>& top, std::vector<Task>& tasks) const {
    const int t = int(top.size());
    top.emplace_back();
    int32_t id;
    if (uniform_chunks(lo, lg, &id)) {
      top[size_t(t)].leaf = VoxelNode::leaf(int16_t(id));
      return t;
    }
    const bool chunk = lg[0] == kVoxelChunkBits && lg[1] == kVoxelChunkBits && lg[2] == kVoxelChunkBits;
    if (chunk || lg[0] + lg[1] + lg[2] <= cut) {
      top[size_t(t)].kind = 1;
      top[size_t(t)].task = int(tasks.size());
      Task& k = tasks.emplace_back();
      for (int a = 0; a < 3; ++a) k.lo[a] = lo[a], k.lg[a] = lg[a];
      return t;
    }
    const int a = voxel_split_axis(lg);
    int clg[3] = {lg[0], lg[1], lg[2]};
    --clg[a];
    int hi_lo[3] = {lo[0], lo[1], lo[2]};
    hi_lo[a] += 1 << clg[a];
    const int c0 = plan(lo, clg, cut, top, tasks);
    const int c1 = plan(hi_lo, clg, cut, top, tasks);
    Top& n = top[size_t(t)];
    n.kind = 2;
    n.axis = a;
    n.child[0] = c0;
    n.child[1] = c1;
    return t;
  }

  // Bottom-up: what each top box becomes (leaf children that are equal merge, as in node()).
  static VoxelNode resolve(std::vector<Top>& top, const std::vector<Task>& tasks, int t) {
    Top& n = top[size_t(t)];
    if (n.kind == 0) return n.result = n.leaf;
    if (n.kind == 1) return n.result = tasks[size_t(n.task)].root;
    const VoxelNode wa = resolve(top, tasks, n.child[0]), wb = resolve(top, tasks, n.child[1]);
    if (wa.is_leaf() && wa == wb) {
      n.kind = 0;
      n.leaf = wa;
      return n.result = wa;
    }
    return n.result = VoxelNode::inner(n.axis, 0);
  }

  // Pre-order layout of the top levels into `out`, already sized (cursor = where the next node goes, always even).
  static VoxelNode layout(std::vector<Top>& top, std::vector<Task>& tasks, int t, std::vector<VoxelNode>& out,
                          size_t& cursor) {
    Top& n = top[size_t(t)];
    if (n.kind == 0) return n.leaf;
    if (n.kind == 1) {
      Task& k = tasks[size_t(n.task)];
      if (k.root.is_leaf()) return k.root;
      k.dest = cursor;
      cursor += k.nodes.size();
      return VoxelNode::inner(k.root.axis(), k.root.pair() + uint32_t(k.dest / 2));
    }
    const size_t pair = cursor;
    cursor += 2;
    const VoxelNode wa = layout(top, tasks, n.child[0], out, cursor);
    const VoxelNode wb = layout(top, tasks, n.child[1], out, cursor);
    out[pair] = wa;
    out[pair + 1] = wb;
    return VoxelNode::inner(n.axis, uint32_t(pair / 2));
  }

  VoxelNode build_parallel(const int lg[3], std::vector<VoxelNode>& out) const {
    const int zero[3] = {0, 0, 0};
    // Tasks of 1/1024 of the root box (at least a chunk): enough for dynamic balancing on sparse worlds.
    const int cut = std::max(3 * kVoxelChunkBits, lg[0] + lg[1] + lg[2] - 10);
    std::vector<Top> top;
    std::vector<Task> tasks;
    plan(zero, lg, cut, top, tasks);
    parallel_for(size_t(0), tasks.size(), [&](size_t i) {
      Task& k = tasks[i];
      k.root = node(k.lo, k.lg, nullptr, k.nodes);
    }, Split::each_block);
    resolve(top, tasks, 0);
    // The final size, so `out` is allocated once: a pair per inner top box (merged ones are leaves now), and the
    // nodes of every task that is not a leaf.
    size_t total = out.size();
    for (const Top& n : top) total += n.kind == 2 ? 2 : 0;
    for (const Task& k : tasks) total += k.root.is_leaf() ? 0 : k.nodes.size();
    if (total / 2 > VoxelNode::kPairMask) throw Error("voxel grid: more than 2^30 tree nodes");
    size_t cursor = out.size();
    out.resize(total);
    const VoxelNode root = layout(top, tasks, 0, out, cursor);
    if (cursor != total) throw Error("voxel grid: internal error in the parallel build layout");
    parallel_for(size_t(0), tasks.size(), [&](size_t i) {
      Task& k = tasks[i];
      if (k.root.is_leaf()) return;
      const uint32_t shift = uint32_t(k.dest / 2);
      VoxelNode* dst = out.data() + k.dest;
      for (size_t j = 0; j < k.nodes.size(); ++j) {
        const VoxelNode n = k.nodes[j];
        dst[j] = n.is_leaf() ? n : VoxelNode::inner(n.axis(), n.pair() + shift);
      }
      std::vector<VoxelNode>().swap(k.nodes);
    }, Split::each_block);
    return root;
  }
};

int ceil_log2(int n) {
  int l = 0;
  while ((1 << l) < n) ++l;
  return l;
}

}  // namespace

VoxelTree VoxelTree::build(const VoxelGrid& grid, bool parallel) {
  const auto start = std::chrono::steady_clock::now();
  VoxelTree tree;
  int lo[3], hi[3];
  grid.chunk_bounds(lo, hi);
  TreeBuilder b;
  size_t total = 1;
  for (int a = 0; a < 3; ++a) {
    tree.origin_[a] = lo[a];
    tree.lg_[a] = std::max(kVoxelChunkBits, ceil_log2(std::max(1, hi[a] - lo[a])));
    if (tree.lg_[a] > 30) throw Error("voxel grid: too large");
    b.cn[a] = 1 << (tree.lg_[a] - kVoxelChunkBits);
    total *= size_t(b.cn[a]);
  }
  if (total > (size_t(1) << 26))
    throw Error("voxel grid: the chunks span more than 2^26 chunk cells (" + std::to_string(total) +
                "); split the world into several grids");
  reserve_memory(total * (sizeof(const VoxelChunk*) + sizeof(int32_t)),
                 "voxel grid: the box of " + std::to_string(total) + " chunk cells");
  b.chunks.assign(total, nullptr);
  b.uniform.assign(total, 0);
  grid.for_each_chunk([&](int cx, int cy, int cz, const VoxelChunk& c) {
    b.chunks[b.cidx(cx - (lo[0] >> kVoxelChunkBits), cy - (lo[1] >> kVoxelChunkBits), cz - (lo[2] >> kVoxelChunkBits))] = &c;
  });
  std::atomic<uint64_t> voxels{0};
  parallel_for(size_t(0), total, [&](size_t i) {
    const VoxelChunk* c = b.chunks[i];
    if (!c) return;
    const int16_t first = c->ids[0];
    bool same = true;
    uint64_t n = 0;
    for (int16_t v : c->ids) {
      same &= v == first;
      n += v != 0;
    }
    b.uniform[i] = same ? first : kMixed;
    voxels += n;
  });
  const int zero[3] = {0, 0, 0};
  tree.nodes_.assign(2, VoxelNode{});
  // Both append to nodes_ (which may reallocate): the root goes to nodes_[0] only afterwards.
  const VoxelNode root =
      parallel ? b.build_parallel(tree.lg_, tree.nodes_) : b.node(zero, tree.lg_, nullptr, tree.nodes_);
  tree.nodes_[0] = root;
  tree.nodes_.shrink_to_fit();
  VoxelBuildStats& s = tree.stats_;
  s.voxels = voxels;
  s.cells = uint64_t(1) << (tree.lg_[0] + tree.lg_[1] + tree.lg_[2]);
  s.nodes = tree.nodes_.size() - 1;
  for (size_t i = 0; i < tree.nodes_.size(); ++i) s.leaves += i != 1 && tree.nodes_[i].is_leaf();
  s.bytes = tree.nodes_.size() * sizeof(VoxelNode);
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return tree;
}

Bounds3f VoxelTree::bounds() const {
  Bounds3f b;
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = float(origin_[a]);
    b.hi[a] = float(origin_[a] + (1 << lg_[a]));
  }
  return b;
}

int16_t VoxelTree::lookup(int x, int y, int z) const {
  int p[3] = {x - origin_[0], y - origin_[1], z - origin_[2]};
  int lo[3] = {0, 0, 0}, lg[3] = {lg_[0], lg_[1], lg_[2]};
  for (int a = 0; a < 3; ++a)
    if (p[a] < 0 || p[a] >= (1 << lg[a])) return 0;
  VoxelNode n = nodes_[0];
  while (!n.is_leaf()) {
    const int a = n.axis();
    --lg[a];
    const int split = lo[a] + (1 << lg[a]);
    const bool above = p[a] >= split;
    if (above) lo[a] = split;
    n = nodes_[2 * size_t(n.pair()) + (above ? 1 : 0)];
  }
  return n.id();
}

}  // namespace torte
