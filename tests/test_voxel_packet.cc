// The voxel packet traversal (simd/voxel_packet.h) against the single-ray kd-tree traversal (voxel/voxel_traverse.h),
// for every Highway target compiled in and supported here, packets of 8 and 16: random and coherent rays over
// random, terrain and cell-shape grids, rays starting inside solid voxels or on cell boundaries, axis-parallel
// rays, mixed direction signs in a packet, and NaN / infinite rays among valid ones. Every field of the hit must
// be equal to the bit.
#include <catch2/catch.hpp>
#include <hwy/highway.h>  // HWY_TARGETS

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/rng.h"
#include "hwy_targets.h"
#include "test_random.h"
#include "voxel/voxel_traverse.h"
#include "voxel_packet.h"
#include "voxel_test_cells.h"

using namespace torte;
using torte::test::for_each_hwy_target;
using torte::test::random_grid;
using torte::test::SlabCells;
using torte::test::terrain_grid;

namespace {

bool same_float(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool same_hit(const VoxelHit& a, const VoxelHit& b) {
  return same_float(a.t, b.t) && a.voxel[0] == b.voxel[0] && a.voxel[1] == b.voxel[1] && a.voxel[2] == b.voxel[2] &&
         a.id == b.id && a.face == b.face && a.inside == b.inside && same_float(a.u, b.u) && same_float(a.v, b.v) &&
         same_float(a.cell.t, b.cell.t) && a.cell.prim == b.cell.prim;
}

struct Stats {
  long rays = 0, hits = 0, inside = 0, cells = 0, mismatches = 0;
};

// Traces `rays` in packets of 8 and 16 and alone; counts differences.
void compare(const VoxelTree& tree, const std::vector<Ray>& rays, Stats* st, const char* what) {
  const SlabCells handler;
  const VoxelCellCallbacks cb = voxel_cell_callbacks(handler);
  std::vector<VoxelHit> want(rays.size());
  std::vector<uint8_t> want_found(rays.size()), want_occ(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    want_found[i] = voxel_intersect(tree, rays[i], &want[i], handler);
    want_occ[i] = voxel_occluded(tree, rays[i], handler);
  }
  for (const int ps : {8, 16}) {
    std::vector<VoxelHit> got(rays.size());
    std::vector<uint8_t> found(rays.size(), 7), occ(rays.size(), 7);
    voxel_intersect_packets(tree, rays.data(), rays.size(), got.data(), found.data(), ps, cb);
    voxel_occluded_packets(tree, rays.data(), rays.size(), occ.data(), ps, cb);
    for (size_t i = 0; i < rays.size(); ++i) {
      ++st->rays;
      bool same = found[i] == want_found[i] && occ[i] == want_occ[i];
      if (want_found[i]) {
        ++st->hits;
        st->inside += want[i].inside;
        st->cells += want[i].face < 0;
        same = same && same_hit(got[i], want[i]);
      } else {
        same = same && same_hit(got[i], VoxelHit{});
      }
      if (!same) {
        if (st->mismatches < 5) {
          const Ray& r = rays[i];
          UNSCOPED_INFO(what << " packet " << ps << " ray " << i << ": o " << r.o.x << " " << r.o.y << " " << r.o.z
                             << " d " << r.d.x << " " << r.d.y << " " << r.d.z << " t_max " << r.t_max << " single "
                             << int(want_found[i]) << "/" << int(want_occ[i]) << " t " << want[i].t << " v "
                             << want[i].voxel[0] << "," << want[i].voxel[1] << "," << want[i].voxel[2] << " f "
                             << int(want[i].face) << " | packet " << int(found[i]) << "/" << int(occ[i]) << " t "
                             << got[i].t << " v " << got[i].voxel[0] << "," << got[i].voxel[1] << ","
                             << got[i].voxel[2] << " f " << int(got[i].face));
        }
        ++st->mismatches;
      }
    }
  }
}

Vec3f random_dir(Pcg32& rng) { return test::random_direction(rng) * (0.5f + rng.next_float()); }

// Incoherent rays as in test_voxel.cc: origins around and inside the box, some on cell boundaries, some t_max.
std::vector<Ray> random_rays(const VoxelTree& tree, int count, uint64_t seed) {
  Pcg32 rng(seed);
  const Bounds3f b = tree.bounds();
  const Vec3f ext = b.diagonal();
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i) {
    Ray r;
    const bool inside = i % 2 == 0;
    for (int a = 0; a < 3; ++a) {
      const float u = rng.next_float();
      r.o[a] = inside ? b.lo[a] + u * ext[a] : b.lo[a] - 0.3f * ext[a] + 1.6f * u * ext[a];
    }
    if (rng.next_float() < 0.25f) {
      const int a = std::min(2, int(rng.next_float() * 3));
      r.o[a] = std::floor(r.o[a]);
    }
    r.d = random_dir(rng);
    r.t_max = rng.next_float() < 0.2f ? ext.x * rng.next_float() : kInfinity;
    rays.push_back(r);
  }
  return rays;
}

// Coherent packets: pinhole tiles (one origin, 4x4 neighbouring pixels; 8-ray packets take two rows), from eyes
// outside and inside the grid (inside solid voxels too, and on cell boundaries), parallel (orthographic) tiles with
// origins on and off cell boundaries, and tiles of axis-parallel or zero-component directions.
std::vector<Ray> coherent_rays(const VoxelTree& tree, int tiles, uint64_t seed) {
  Pcg32 rng(seed);
  const Bounds3f b = tree.bounds();
  const Vec3f ext = b.diagonal();
  std::vector<Ray> rays;
  for (int t = 0; t < tiles; ++t) {
    const int kind = t % 5;
    Vec3f eye;
    for (int a = 0; a < 3; ++a)
      eye[a] = kind == 1 ? b.lo[a] + rng.next_float() * ext[a] : b.lo[a] - 0.3f * ext[a] + 1.6f * rng.next_float() * ext[a];
    if (kind == 1 && rng.next_float() < 0.5f) {  // an eye on a cell boundary plane
      const int a = int(rng.next_float() * 2.999f);
      eye[a] = std::floor(eye[a]);
    }
    Vec3f fw = random_dir(rng);
    if (kind == 3) {  // axis-parallel tiles and directions with zero components
      const int a = int(rng.next_float() * 2.999f);
      Vec3f v(0, 0, 0);
      v[a] = rng.next_float() < 0.5f ? -1.0f : 1.0f;
      if (rng.next_float() < 0.5f) v[(a + 1) % 3] = rng.next_float() - 0.5f;
      fw = v;
    }
    const Frame f = Frame::from_z(normalize(fw));
    const float spread = kind == 4 ? 0.002f : 0.02f + 0.1f * rng.next_float();
    const float t_max = rng.next_float() < 0.2f ? ext.x * rng.next_float() : kInfinity;
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) {
        Ray r;
        r.t_max = t_max;
        if (kind == 2) {  // orthographic: parallel rays, origins one cell apart on an integer lattice (or not)
          r.o = eye + f.s * float(x) + f.t * float(y);
          if (rng.next_float() < 0.5f)
            for (int a = 0; a < 3; ++a) r.o[a] = std::floor(r.o[a]);
          r.d = fw;
        } else if (kind == 3) {
          r.o = Vec3f(std::floor(eye.x) + 0.5f * float(x), std::floor(eye.y) + 0.5f * float(y), std::floor(eye.z));
          r.d = fw;
        } else {
          r.o = eye;
          r.d = normalize(fw) + f.s * (spread * (float(x) - 1.5f)) + f.t * (spread * (float(y) - 1.5f));
        }
        rays.push_back(r);
      }
  }
  return rays;
}


}  // namespace

TEST_CASE("voxel packets equal single rays on random and coherent rays, every target", "[voxel][simd]") {
  const VoxelGrid sparse = random_grid(1, 40, 0.05f, true);
  const VoxelGrid dense = random_grid(2, 33, 0.5f, true);
  const VoxelGrid terrain = terrain_grid(96);
  const VoxelTree trees[3] = {VoxelTree::build(sparse), VoxelTree::build(dense), VoxelTree::build(terrain)};
  std::vector<Ray> random[3], coherent[3];
  for (int k = 0; k < 3; ++k) {
    random[k] = random_rays(trees[k], 20000, 10 + uint64_t(k));
    coherent[k] = coherent_rays(trees[k], 1500, 20 + uint64_t(k));
  }
  for_each_hwy_target(&voxel_packet_target_name, [&](const std::string& name) {
    Stats rs, cs;
    for (int k = 0; k < 3; ++k) {
      compare(trees[k], random[k], &rs, "random");
      compare(trees[k], coherent[k], &cs, "coherent");
    }
    std::fprintf(stderr,
                 "voxel packets %s: random %ld rays (%ld hits, %ld inside, %ld cells) %ld mismatches; coherent %ld "
                 "rays (%ld hits, %ld inside, %ld cells) %ld mismatches\n",
                 name.c_str(), rs.rays, rs.hits, rs.inside, rs.cells, rs.mismatches, cs.rays, cs.hits, cs.inside,
                 cs.cells, cs.mismatches);
    CHECK(rs.rays + cs.rays >= 100000);
    CHECK(cs.hits > cs.rays / 10);
    CHECK(cs.inside > 100);
    CHECK(cs.cells > 50);
    CHECK(rs.mismatches == 0);
    CHECK(cs.mismatches == 0);
  });
}

TEST_CASE("voxel packets: mixed direction signs, axis-parallel rays and NaN rays in one packet", "[voxel][simd]") {
  const VoxelGrid terrain = terrain_grid(64);
  const VoxelTree tree = VoxelTree::build(terrain);
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = kInfinity;
  Pcg32 rng(99);
  std::vector<Ray> rays;
  for (int p = 0; p < 400; ++p) {
    const Vec3f eye(rng.next_float() * 64, 25 + rng.next_float() * 20, rng.next_float() * 64);
    for (int i = 0; i < 16; ++i) {
      Ray r{eye, Vec3f(std::cos(0.4f * float(i)), -0.5f, std::sin(0.4f * float(i)))};  // signs change in the packet
      switch ((p + i) % 11) {
        case 0: r.d = Vec3f(0, -1, 0); break;          // axis-parallel
        case 1: r.d = Vec3f(-0.0f, -1, 0.0f); break;   // negative zero
        case 2: r.d = Vec3f(1, 0, 0); r.o.y = std::floor(r.o.y); break;  // along a cell boundary plane
        case 3: if (p % 3 == 0) r.o.x = nan; break;
        case 4: if (p % 3 == 1) r.d.z = nan; break;
        case 5: if (p % 3 == 2) r.d.x = inf; break;
        case 6: if (p % 4 == 0) r.t_max = nan; break;
        case 7: if (p % 4 == 1) r.d = Vec3f(0, 0, 0); break;
        case 8: if (p % 4 == 2) r.d.y = 1e-40f; break;  // 1 / d overflows
        default: break;
      }
      rays.push_back(r);
    }
  }
  // Packets whose rays agree in sign except one lane.
  for (int p = 0; p < 400; ++p) {
    const Vec3f eye(rng.next_float() * 64, 25 + rng.next_float() * 20, rng.next_float() * 64);
    const int odd = int(rng.next_float() * 15.99f);
    for (int i = 0; i < 16; ++i) {
      Ray r{eye, Vec3f(0.3f + 0.01f * float(i), -0.6f, 0.2f)};
      if (i == odd) r.d.x = -r.d.x;
      rays.push_back(r);
    }
  }
  for_each_hwy_target(&voxel_packet_target_name, [&](const std::string& name) {
    Stats st;
    compare(tree, rays, &st, "mixed");
    std::fprintf(stderr, "voxel packets %s: mixed/NaN %ld rays (%ld hits) %ld mismatches\n", name.c_str(), st.rays,
                 st.hits, st.mismatches);
    CHECK(st.hits > st.rays / 4);
    CHECK(st.mismatches == 0);
  });
  // Partial packets and bad sizes.
  std::vector<VoxelHit> h(5);
  std::vector<uint8_t> f(5);
  voxel_intersect_packets(tree, rays.data(), 5, h.data(), f.data(), 16);
  for (int i = 0; i < 5; ++i) {
    VoxelHit want;
    CHECK(f[size_t(i)] == voxel_intersect(tree, rays[size_t(i)], &want));
  }
  CHECK_THROWS(voxel_intersect_packets(tree, rays.data(), 5, h.data(), f.data(), 4));
}
