#include "workloads.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "core/error.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "geometry/mesh_io.h"
#include "geometry/subdivide.h"
#include "geometry/triangle.h"

#ifndef TORTE_SHARED_DATA
#define TORTE_SHARED_DATA "../shared/data"
#endif

namespace torte::bench {

namespace {

bool g_full = [] {
  const char* e = std::getenv("TORTE_BENCH_FULL");
  return e && *e && std::string(e) != "0";
}();

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

struct SceneRecipe {
  const char* name;
  const char* file;  // relative to shared_data_dir()
  int levels;        // 1-to-4 subdivision levels
};
// The bunny has 69,451 triangles: 2 levels give 1.11 M, 3 give 4.44 M, 4 give 17.8 M.
constexpr SceneRecipe kRecipes[] = {
    {"bunny", "meshes/bunny/bunny_binary_le.ply", 0},
    {"dragon", "meshes/dragon/dragon_100k_binary_le.ply", 0},
    {"bunny-1m", "meshes/bunny/bunny_binary_le.ply", 2},
    {"bunny-4m", "meshes/bunny/bunny_binary_le.ply", 3},
    {"bunny-16m", "meshes/bunny/bunny_binary_le.ply", 4},
};
// Displacement of the subdivided bunnies: +-5 % of the edge length along the normal (as in PERF-NOTES.md), so
// the grown mesh is not flat-faceted and its BVH is not the trivially perfect one of coplanar triangles.
constexpr float kDisplacement = 0.05f;
constexpr uint64_t kSubdivSeed = 7;

constexpr float kFovDegrees = 40;

void add_box(TriangleMesh& m, Vec3f lo, Vec3f hi) {
  const uint32_t b = uint32_t(m.vertex_count());
  for (int i = 0; i < 8; ++i) m.add_vertex({i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z});
  // Faces as quads (corner bits: 1 = x, 2 = y, 4 = z), each split into two triangles.
  const uint32_t q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : q) {
    m.add_triangle(b + f[0], b + f[1], b + f[2]);
    m.add_triangle(b + f[0], b + f[2], b + f[3]);
  }
}

Vec3f hit_point(const TriangleMesh& m, const Hit& h, Vec3f* ng) {
  const uint32_t* idx = &m.indices[3 * size_t(h.prim)];
  const Vec3f p0 = m.position(idx[0]), p1 = m.position(idx[1]), p2 = m.position(idx[2]);
  *ng = normalize(cross(p1 - p0, p2 - p0));
  return p0 * (1 - h.b1 - h.b2) + p1 * h.b1 + p2 * h.b2;
}

// Fills w.ref (and *hits, the closest hits, when given) with the scalar reference, on all cores.
void compute_reference(const BenchScene& s, Workload& w, std::vector<Hit>* hits = nullptr) {
  const size_t n = w.rays.size();
  w.ref.t.assign(n, kInfinity);
  w.ref.occluded.assign(n, 0);
  if (hits) hits->assign(n, Hit{});
  parallel_for_blocks(size_t(0), n, 4096, [&](IndexRange<size_t> r) {
    for (size_t i = r.begin(); i < r.end(); ++i) {
      const Ray ray = w.rays.ray(i);
      const Hit h = s.reference_closest(ray);
      w.ref.t[i] = h.t;
      if (hits) (*hits)[i] = h;
      w.ref.occluded[i] = s.reference_any(ray);
    }
  });
  w.ref.hits = w.ref.occluded_count = 0;
  w.ref.sum_t = 0;
  for (size_t i = 0; i < n; ++i) {
    if (w.ref.t[i] < kInfinity) ++w.ref.hits, w.ref.sum_t += w.ref.t[i];
    w.ref.occluded_count += w.ref.occluded[i];
    // Closest and any hit must agree on whether something is there.
    if ((w.ref.t[i] < kInfinity) != bool(w.ref.occluded[i]))
      throw Error("bench: scalar reference closest/any hit disagree on " + w.name + " ray " + std::to_string(i));
  }
}

// The scene `name`: the mesh in `path` (torte's PLY / OBJ readers), subdivided `levels` times, framed and boxed.
std::unique_ptr<BenchScene> make_scene(const std::string& name, const std::string& path, int levels) {
  auto s = std::make_unique<BenchScene>();
  s->name = name;
  auto t0 = std::chrono::steady_clock::now();
  {
    TriangleMesh base = load_mesh(path);
    if (base.triangle_count() == 0) throw Error("bench: " + path + " has no triangles");
    // Positions and indices only: the kernels (and Embree) need nothing else.
    base.nx.clear(), base.ny.clear(), base.nz.clear(), base.u.clear(), base.v.clear();
    s->mesh = levels > 0 ? subdivide(base, levels, kDisplacement, kSubdivSeed) : std::move(base);
    s->mesh.nx.clear(), s->mesh.ny.clear(), s->mesh.nz.clear(), s->mesh.u.clear(), s->mesh.v.clear();
  }
  s->model_triangles = s->mesh.triangle_count();
  s->load_seconds = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();

  // Framing: camera on a fixed diagonal looking at the bounds' centre, at the distance where the model's
  // silhouette just fits the image (its outermost vertex 2 % inside the border), so the model covers a large
  // part of the image and most primary rays hit it rather than the walls.
  Bounds3f mb;
  for (size_t i = 0; i < s->mesh.vertex_count(); ++i) mb.extend(s->mesh.position(uint32_t(i)));
  const Vec3f c = mb.center();
  const float r = 0.5f * length(mb.diagonal());
  const float tan_half = std::tan(kFovDegrees * 0.5f * kPi / 180);
  const Vec3f forward = -normalize(Vec3f(0.35f, 0.3f, 1.0f));
  const Vec3f right = normalize(cross(forward, Vec3f(0, 1, 0)));
  const Vec3f up = cross(right, forward);
  // The camera looks along `forward` from eye = aim - forward * dist, with aim = c + right * a + up * b. Vertex q
  // (relative to aim) is inside the image when max(|q.right|, |q.up|) <= (q.forward + dist) tan_half. A few
  // rounds centre the silhouette (a, b) and then find the smallest such dist.
  float a = 0, b = 0, dist = 0;
  for (int round = 0; round < 4; ++round) {
    const Vec3f aim = c + right * a + up * b;
    dist = 0;
    for (size_t i = 0; i < s->mesh.vertex_count(); ++i) {
      const Vec3f q = s->mesh.position(uint32_t(i)) - aim;
      dist = std::max(dist, std::max(std::fabs(dot(q, right)), std::fabs(dot(q, up))) / (0.98f * tan_half) -
                                dot(q, forward));
    }
    if (round == 3) break;
    float u0 = kInfinity, u1 = -kInfinity, v0 = kInfinity, v1 = -kInfinity;  // projected extents
    for (size_t i = 0; i < s->mesh.vertex_count(); ++i) {
      const Vec3f q = s->mesh.position(uint32_t(i)) - aim;
      const float z = dot(q, forward) + dist;
      u0 = std::min(u0, dot(q, right) / z), u1 = std::max(u1, dot(q, right) / z);
      v0 = std::min(v0, dot(q, up) / z), v1 = std::max(v1, dot(q, up) / z);
    }
    a += 0.5f * (u0 + u1) * dist, b += 0.5f * (v0 + v1) * dist;
  }
  const Vec3f eye = c + right * a + up * b - forward * dist;

  // The room: the model stands on the floor; walls 3.5 r from the centre, ceiling 5 r above the floor.
  // A user's mesh of unusual proportions (--mesh) can put the eye beyond a wall: the box then grows to hold it
  // (never the case for the named scenes, whose box is as above).
  Vec3f box_lo(c.x - 3.5f * r, mb.lo.y - 1e-3f * r, c.z - 3.5f * r);
  Vec3f box_hi(c.x + 3.5f * r, mb.lo.y + 5.0f * r, c.z + 3.5f * r);
  const Vec3f margin(0.1f * r, 0.1f * r, 0.1f * r);
  box_lo = min(box_lo, eye - margin), box_hi = max(box_hi, eye + margin);
  add_box(s->mesh, box_lo, box_hi);
  s->mesh.validate("bench scene " + name);
  // Square area light (side 1.5 r) centred over the model, just below the ceiling, facing down.
  const Vec3f light_corner(c.x - 0.75f * r, box_hi.y - 0.05f * r, c.z - 0.75f * r);
  const Vec3f light_e1(1.5f * r, 0, 0), light_e2(0, 0, 1.5f * r);

  s->bvh2.build(triangle_bounds(s->mesh));

  // Primary rays in tile order.
  const int res = image_resolution();
  Workload& prim = s->primary;
  prim.name = "primary";
  for (int ty = 0; ty < res; ty += 8)
    for (int tx = 0; tx < res; tx += 8)
      for (int b = 0; b < 4; ++b)
        for (int y = 0; y < 4; ++y)
          for (int x = 0; x < 4; ++x) {
            const int px = tx + (b & 1) * 4 + x, py = ty + (b >> 1) * 4 + y;
            const float u = (2 * (px + 0.5f) / res - 1) * tan_half;
            const float v = (1 - 2 * (py + 0.5f) / res) * tan_half;
            prim.rays.push({eye, normalize(forward + right * u + up * v), kInfinity});
          }
  std::vector<Hit> hits;
  compute_reference(*s, prim, &hits);

  // Secondary rays from the primary hits (in the same order, so each keeps its pixel's neighbours).
  Workload& diff = s->diffuse;
  Workload& shad = s->shadow;
  diff.name = "diffuse";
  shad.name = "shadow";
  for (size_t i = 0; i < hits.size(); ++i) {
    if (hits[i].prim == kNoHit) continue;
    Vec3f ng;
    const Vec3f p = hit_point(s->mesh, hits[i], &ng);
    const Vec3f d_in(prim.rays.dx[i], prim.rays.dy[i], prim.rays.dz[i]);
    const Vec3f n = face_forward(ng, -d_in);
    Pcg32 rng(mix_bits(i), 0x5eed);
    const Vec3f w = Frame::from_z(n).to_world(sample_cosine_hemisphere({rng.next_float(), rng.next_float()}));
    diff.rays.push({offset_origin(p, ng, w), normalize(w), kInfinity});
    const Vec3f q = light_corner + light_e1 * rng.next_float() + light_e2 * rng.next_float();
    const Vec3f o = offset_origin(p, ng, q - p);
    const float dist = length(q - o);
    shad.rays.push({o, (q - o) / dist, dist});
  }
  compute_reference(*s, diff);
  compute_reference(*s, shad);
  s->setup_seconds = seconds_since(t0);
  return s;
}

std::unique_ptr<BenchScene> g_scene;
std::string g_scene_key;  // what g_scene was made from: "name:<name>" or "mesh:<grow>:<path>"

const BenchScene& cached_scene(const std::string& key, const std::string& name, const std::string& path,
                               int levels) {
  if (!g_scene || g_scene_key != key) {
    g_scene.reset();  // free the previous scene first
    g_scene_key.clear();
    g_scene = make_scene(name, path, levels);
    g_scene_key = key;
    std::fprintf(stderr, "# scene %s: %zu triangles (model %zu + 12 box), load %.2f s, rays+reference %.2f s\n",
                 name.c_str(), g_scene->triangles(), g_scene->model_triangles, g_scene->load_seconds,
                 g_scene->setup_seconds);
  }
  return *g_scene;
}

}  // namespace

std::string shared_data_dir() {
  const char* e = std::getenv("TORTE_SHARED_DATA");
  return e && *e ? e : TORTE_SHARED_DATA;
}

bool shared_data_available(std::string* why) {
  for (const SceneRecipe& r : kRecipes) {
    const std::string p = shared_data_dir() + "/" + r.file;
    if (!std::filesystem::exists(p)) {
      if (why) *why = p + " does not exist (the benchmark meshes live in ../shared/data next to the source dir)";
      return false;
    }
  }
  return true;
}

bool full_run() { return g_full; }
void set_full_run(bool full) { g_full = full; }

std::vector<std::string> scene_names() {
  std::vector<std::string> names;
  if (const char* e = std::getenv("TORTE_BENCH_SCENES"); e && *e) {
    std::stringstream ss(e);
    for (std::string item; std::getline(ss, item, ',');)
      if (!item.empty()) names.push_back(item);
    return names;
  }
  names = {"bunny", "dragon", "bunny-1m"};
  if (full_run()) names.insert(names.end(), {"bunny-4m", "bunny-16m"});
  return names;
}

int image_resolution() {
  const char* e = std::getenv("TORTE_BENCH_RES");
  const int r = e && *e ? std::atoi(e) : 1024;
  if (r < 8 || r % 8 != 0) throw Error("bench: TORTE_BENCH_RES must be a positive multiple of 8");
  return r;
}

Check check_closest(const Reference& ref, const float* t, size_t n, float rel_tol) {
  Check c;
  c.rays = n;
  for (size_t i = 0; i < n; ++i) {
    const float a = ref.t[i], b = t[i];
    const bool ha = a < kInfinity, hb = b < kInfinity;
    if (hb) ++c.hits, c.sum_t += b;
    if (ha != hb || (ha && std::fabs(a - b) > rel_tol * std::max(std::fabs(a), std::fabs(b)))) ++c.mismatches;
  }
  return c;
}

Check check_closest(const Reference& ref, const Hit* hits, size_t n, float rel_tol) {
  Check c;
  c.rays = n;
  for (size_t i = 0; i < n; ++i) {
    const float a = ref.t[i], b = hits[i].t;
    const bool ha = a < kInfinity, hb = hits[i].prim != kNoHit && b < kInfinity;
    if (hb) ++c.hits, c.sum_t += b;
    if (ha != hb || (ha && std::fabs(a - b) > rel_tol * std::max(std::fabs(a), std::fabs(b)))) ++c.mismatches;
  }
  return c;
}

Check check_any(const Reference& ref, const uint8_t* occluded, size_t n) {
  Check c;
  c.rays = n;
  for (size_t i = 0; i < n; ++i) {
    const bool b = occluded[i] != 0;
    c.hits += b;
    if (b != bool(ref.occluded[i])) ++c.mismatches;
  }
  return c;
}

std::vector<Bounds3f> triangle_bounds(const TriangleMesh& mesh) {
  std::vector<Bounds3f> b(mesh.triangle_count());
  parallel_for_blocks(size_t(0), b.size(), 16384, [&](IndexRange<size_t> r) {
    for (size_t t = r.begin(); t < r.end(); ++t) b[t] = mesh.triangle_bounds(t);
  });
  return b;
}

template <int N>
TorteAccel<N> build_torte(const TriangleMesh& mesh, const BvhBuildOptions& options) {
  TorteAccel<N> a;
  const std::vector<Bounds3f> bounds = triangle_bounds(mesh);
  a.bvh = build_wide_bvh<N>(bounds, options);
  a.leaves = make_triangle_leaves(a.bvh, mesh, options.parallel);
  return a;
}
template TorteAccel<4> build_torte<4>(const TriangleMesh&, const BvhBuildOptions&);
template TorteAccel<8> build_torte<8>(const TriangleMesh&, const BvhBuildOptions&);

const Workload& BenchScene::workload(const std::string& n) const {
  if (n == "primary") return primary;
  if (n == "diffuse") return diffuse;
  if (n == "shadow") return shadow;
  throw Error("bench: unknown workload '" + n + "'");
}

const TorteAccel<4>& BenchScene::wide4() const {
  if (!wide4_) wide4_ = std::make_unique<TorteAccel<4>>(build_torte<4>(mesh));
  return *wide4_;
}
const TorteAccel<8>& BenchScene::wide8() const {
  if (!wide8_) wide8_ = std::make_unique<TorteAccel<8>>(build_torte<8>(mesh));
  return *wide8_;
}

Hit BenchScene::reference_closest(const Ray& ray) const {
  Hit hit;
  const WatertightRay wr(ray);
  Ray r = ray;
  bvh2.intersect(r, [&](uint32_t p, Ray& rr) {
    const uint32_t* idx = &mesh.indices[3 * size_t(p)];
    TriangleHit th;
    if (!intersect_triangle(wr, rr.t_max, mesh.position(idx[0]), mesh.position(idx[1]), mesh.position(idx[2]), &th))
      return false;
    rr.t_max = th.t;
    hit = {th.t, p, th.b1, th.b2};
    return true;
  });
  return hit;
}

bool BenchScene::reference_any(const Ray& ray) const {
  const WatertightRay wr(ray);
  return bvh2.occluded(ray, [&](uint32_t p, const Ray& rr) {
    const uint32_t* idx = &mesh.indices[3 * size_t(p)];
    return intersect_triangle(wr, rr.t_max, mesh.position(idx[0]), mesh.position(idx[1]), mesh.position(idx[2]),
                              nullptr);
  });
}

const BenchScene& get_scene(const std::string& name) {
  const SceneRecipe* recipe = nullptr;
  for (const SceneRecipe& r : kRecipes)
    if (name == r.name) recipe = &r;
  if (!recipe) throw Error("bench: unknown scene '" + name + "'");
  return cached_scene("name:" + name, name, shared_data_dir() + "/" + recipe->file, recipe->levels);
}

const BenchScene& get_mesh_scene(const std::string& path, int grow) {
  if (grow < 0) throw Error("bench: --grow must be >= 0");
  std::string name = std::filesystem::path(path).filename().string();
  if (grow > 0) name += "-grow" + std::to_string(grow);
  return cached_scene("mesh:" + std::to_string(grow) + ":" + path, name, path, grow);
}

void release_scene() {
  g_scene.reset();
  g_scene_key.clear();
}

}  // namespace torte::bench
