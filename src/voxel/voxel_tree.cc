#include "voxel/voxel_tree.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <atomic>
#include <chrono>
#include <climits>

#include "core/error.h"

namespace torte {

namespace {

constexpr int32_t kMixed = INT32_MIN;

// Children-first recursion over the implicit tree. Invariant: a call that returns a leaf leaves `out` as it found
// it, so two equal leaf children merge by truncating their pair. `out` always has an even size (pairs only).
struct TreeBuilder {
  int cn[3];                                 // root box in chunks per axis
  std::vector<const VoxelChunk*> chunks;     // dense over the root box, x fastest
  std::vector<int32_t> uniform;              // the chunk's single id, or kMixed
  bool parallel = true;

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

  static VoxelNode splice(const std::vector<VoxelNode>& local, VoxelNode root, std::vector<VoxelNode>& out) {
    const uint32_t shift = uint32_t(out.size() / 2);
    if (out.size() / 2 + local.size() / 2 > VoxelNode::kPairMask) throw Error("voxel grid: more than 2^30 tree nodes");
    for (VoxelNode n : local) out.push_back(n.is_leaf() ? n : VoxelNode::inner(n.axis(), n.pair() + shift));
    return root.is_leaf() ? root : VoxelNode::inner(root.axis(), root.pair() + shift);
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
    if (parallel && !c && lg[0] + lg[1] + lg[2] >= 3 * kVoxelChunkBits + 9) {  // boxes of >= 2^21 cells: few big tasks, few splices
      std::vector<VoxelNode> va, vb;
      VoxelNode wa, wb;
      tbb::parallel_invoke([&] { wa = node(lo, clg, nullptr, va); }, [&] { wb = node(hi_lo, clg, nullptr, vb); });
      if (wa.is_leaf() && wa == wb) return wa;
      const size_t pair = out.size();
      out.resize(pair + 2);
      out[pair] = splice(va, wa, out);
      out[pair + 1] = splice(vb, wb, out);
      return VoxelNode::inner(a, uint32_t(pair / 2));
    }
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
  b.parallel = parallel;
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
  b.chunks.assign(total, nullptr);
  b.uniform.assign(total, 0);
  grid.for_each_chunk([&](int cx, int cy, int cz, const VoxelChunk& c) {
    b.chunks[b.cidx(cx - (lo[0] >> kVoxelChunkBits), cy - (lo[1] >> kVoxelChunkBits), cz - (lo[2] >> kVoxelChunkBits))] = &c;
  });
  std::atomic<uint64_t> voxels{0};
  tbb::parallel_for(size_t(0), total, [&](size_t i) {
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
  tree.nodes_[0] = b.node(zero, tree.lg_, nullptr, tree.nodes_);
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
