#include "voxel/voxel_grid.h"

#include <algorithm>
#include <bit>
#include <climits>
#include <cstring>
#include <fstream>

#include "core/error.h"

namespace torte {

uint64_t VoxelGrid::key(int cx, int cy, int cz) {
  constexpr int kLimit = 1 << 20;
  if (cx < -kLimit || cx >= kLimit || cy < -kLimit || cy >= kLimit || cz < -kLimit || cz >= kLimit)
    throw Error("voxel grid: chunk coordinates out of range (|chunk| must stay below 2^20)");
  return uint64_t(cx + kLimit) | uint64_t(cy + kLimit) << 21 | uint64_t(cz + kLimit) << 42;
}

void VoxelGrid::set(int x, int y, int z, int16_t id) {
  const uint64_t k = key(x >> kVoxelChunkBits, y >> kVoxelChunkBits, z >> kVoxelChunkBits);
  const int i = voxel_chunk_index(x & (kVoxelChunkSize - 1), y & (kVoxelChunkSize - 1), z & (kVoxelChunkSize - 1));
  auto it = chunks_.find(k);
  if (it == chunks_.end()) {
    if (id == 0) return;
    it = chunks_.emplace(k, std::make_unique<VoxelChunk>()).first;
  }
  it->second->ids[size_t(i)] = id;
  ++revision_;
}

int16_t VoxelGrid::get(int x, int y, int z) const {
  const auto it = chunks_.find(key(x >> kVoxelChunkBits, y >> kVoxelChunkBits, z >> kVoxelChunkBits));
  if (it == chunks_.end()) return 0;
  return it->second->ids[size_t(
      voxel_chunk_index(x & (kVoxelChunkSize - 1), y & (kVoxelChunkSize - 1), z & (kVoxelChunkSize - 1)))];
}

void VoxelGrid::set_chunk(int cx, int cy, int cz, const int16_t* ids) {
  const uint64_t k = key(cx, cy, cz);
  ++revision_;
  const bool empty = std::all_of(ids, ids + kVoxelChunkVoxels, [](int16_t v) { return v == 0; });
  if (empty) {
    chunks_.erase(k);
    return;
  }
  auto& slot = chunks_[k];
  if (!slot) slot = std::make_unique<VoxelChunk>();
  std::memcpy(slot->ids.data(), ids, sizeof(int16_t) * kVoxelChunkVoxels);
}

const VoxelChunk* VoxelGrid::chunk(int cx, int cy, int cz) const {
  const auto it = chunks_.find(key(cx, cy, cz));
  return it == chunks_.end() ? nullptr : it->second.get();
}

uint64_t VoxelGrid::voxel_count() const {
  uint64_t n = 0;
  for (const auto& [k, c] : chunks_)
    for (int16_t v : c->ids) n += v != 0;
  return n;
}

void VoxelGrid::chunk_bounds(int lo[3], int hi[3]) const {
  for (int a = 0; a < 3; ++a) {
    lo[a] = INT_MAX;
    hi[a] = INT_MIN;
  }
  for_each_chunk([&](int cx, int cy, int cz, const VoxelChunk&) {
    const int c[3] = {cx, cy, cz};
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], c[a] * kVoxelChunkSize);
      hi[a] = std::max(hi[a], (c[a] + 1) * kVoxelChunkSize);
    }
  });
  if (chunks_.empty())
    for (int a = 0; a < 3; ++a) lo[a] = hi[a] = 0;
}

// x86 and ARM are little-endian: the dump is the in-memory layout.
static_assert(std::endian::native == std::endian::little, "VoxelGrid::save assumes a little-endian machine");

void VoxelGrid::save(const std::string& path) const {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw Error("cannot write " + path);
  out.write("TVOX1\n", 6);
  for_each_chunk([&](int cx, int cy, int cz, const VoxelChunk& c) {
    const int32_t xyz[3] = {cx, cy, cz};
    out.write(reinterpret_cast<const char*>(xyz), sizeof(xyz));
    out.write(reinterpret_cast<const char*>(c.ids.data()), sizeof(c.ids));
  });
  if (!out) throw Error("error writing " + path);
}

VoxelGrid VoxelGrid::load(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read " + path);
  char magic[6];
  if (!in.read(magic, 6) || std::memcmp(magic, "TVOX1\n", 6) != 0) throw Error(path + ": not a torte voxel dump");
  VoxelGrid g;
  int32_t xyz[3];
  std::array<int16_t, kVoxelChunkVoxels> ids;
  while (in.read(reinterpret_cast<char*>(xyz), sizeof(xyz))) {
    if (!in.read(reinterpret_cast<char*>(ids.data()), sizeof(ids))) throw Error(path + ": truncated chunk");
    g.set_chunk(xyz[0], xyz[1], xyz[2], ids.data());
  }
  return g;
}

}  // namespace torte
