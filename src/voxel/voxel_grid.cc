#include "voxel/voxel_grid.h"

#include <algorithm>
#include <bit>
#include <climits>
#include <cstring>
#include <fstream>
#include <string>

#include "core/error.h"
#include "core/file_read.h"
#include "core/memory_budget.h"

namespace torte {

uint64_t VoxelGrid::key(int cx, int cy, int cz) {
  constexpr int kLimit = 1 << 20;
  if (cx < -kLimit || cx >= kLimit || cy < -kLimit || cy >= kLimit || cz < -kLimit || cz >= kLimit)
    throw Error("voxel grid: chunk (" + std::to_string(cx) + ", " + std::to_string(cy) + ", " + std::to_string(cz) +
                ") is out of range (chunk coordinates lie in [-2^20, 2^20), voxel coordinates in [-2^24, 2^24))");
  return uint64_t(cx + kLimit) | uint64_t(cy + kLimit) << 21 | uint64_t(cz + kLimit) << 42;
}

std::unique_ptr<VoxelChunk> VoxelGrid::new_chunk() const {
  // Chunks come one at a time (8 KB each): every kBudgetChunks of them the next batch is checked against the
  // memory budget, so a script filling chunks in a loop fails with a clear error before the machine runs out.
  constexpr size_t kBudgetChunks = 2048;
  if ((chunks_.size() + 1) % kBudgetChunks == 0)
    reserve_memory(kBudgetChunks * (sizeof(VoxelChunk) + 64),
                   "voxel grid: " + std::to_string(chunks_.size() + 1) + " chunks and more");
  return std::make_unique<VoxelChunk>();
}

void VoxelGrid::set(int x, int y, int z, int16_t id) {
  const uint64_t k = key(x >> kVoxelChunkBits, y >> kVoxelChunkBits, z >> kVoxelChunkBits);
  const int i = voxel_chunk_index(x & (kVoxelChunkSize - 1), y & (kVoxelChunkSize - 1), z & (kVoxelChunkSize - 1));
  auto it = chunks_.find(k);
  if (it == chunks_.end()) {
    if (id == 0) return;
    it = chunks_.emplace(k, new_chunk()).first;
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
  auto it = chunks_.find(k);
  if (it == chunks_.end()) it = chunks_.emplace(k, new_chunk()).first;  // made first: the budget check may throw
  std::memcpy(it->second->ids.data(), ids, sizeof(int16_t) * kVoxelChunkVoxels);
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
  check_regular_file(path);
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
