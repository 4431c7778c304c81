// A sparse voxel grid filled chunk by chunk: 16^3 chunks of 16-bit voxel ids, created on first write.
//
// Voxel ids: 0 = empty; > 0 = a solid unit cube with a material per face; < 0 = a "cell shape" (any geometry
// modelled in the unit cell: slabs, stairs, torches, plants), see voxel/voxel_traverse.h. Voxel (x, y, z) occupies
// [x, x+1] x [y, y+1] x [z, z+1] of the grid's cell space.
//
// Inside a chunk, ids are stored y-major, then z, then x (Minecraft's section order):
//   index = (y * 16 + z) * 16 + x,   x, y, z in [0, 16).
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>

namespace torte {

constexpr int kVoxelChunkBits = 4;
constexpr int kVoxelChunkSize = 1 << kVoxelChunkBits;  // 16
constexpr int kVoxelChunkVoxels = kVoxelChunkSize * kVoxelChunkSize * kVoxelChunkSize;  // 4096

inline int voxel_chunk_index(int x, int y, int z) { return (y * kVoxelChunkSize + z) * kVoxelChunkSize + x; }

struct VoxelChunk {
  std::array<int16_t, kVoxelChunkVoxels> ids{};
};

class VoxelGrid {
 public:
  // Chunk coordinates (voxel >> 4) must lie in [-2^20, 2^20). New chunks are checked against the memory budget
  // (core/memory_budget.h) in batches; both limits throw torte::Error.
  void set(int x, int y, int z, int16_t id);
  int16_t get(int x, int y, int z) const;
  // Replaces chunk (cx, cy, cz) by 4096 ids in chunk order (see above). An all-zero chunk removes the chunk.
  void set_chunk(int cx, int cy, int cz, const int16_t* ids);
  const VoxelChunk* chunk(int cx, int cy, int cz) const;

  size_t chunk_count() const { return chunks_.size(); }
  // Non-empty voxels (counted on demand: O(chunks)).
  uint64_t voxel_count() const;
  // Voxel-space box [lo, hi) of all chunks held (hi <= lo on every axis when the grid has no chunks).
  void chunk_bounds(int lo[3], int hi[3]) const;
  // Bumped by every change (lets holders of a built tree know it is stale).
  uint64_t revision() const { return revision_; }

  // A raw dump (benchmarks of real worlds): "TVOX1\n", then per chunk int32 cx, cy, cz and 4096 int16, all
  // little-endian. Throws torte::Error on I/O errors or a malformed file.
  void save(const std::string& path) const;
  static VoxelGrid load(const std::string& path);

  template <class F>  // f(cx, cy, cz, const VoxelChunk&)
  void for_each_chunk(F&& f) const {
    for (const auto& [key, c] : chunks_) f(key_x(key), key_y(key), key_z(key), *c);
  }

 private:
  static uint64_t key(int cx, int cy, int cz);
  std::unique_ptr<VoxelChunk> new_chunk() const;  // checks the memory budget every few thousand chunks
  static int key_x(uint64_t k) { return int(k & 0x1fffff) - (1 << 20); }
  static int key_y(uint64_t k) { return int((k >> 21) & 0x1fffff) - (1 << 20); }
  static int key_z(uint64_t k) { return int((k >> 42) & 0x1fffff) - (1 << 20); }
  std::unordered_map<uint64_t, std::unique_ptr<VoxelChunk>> chunks_;
  uint64_t revision_ = 0;
};

}  // namespace torte
