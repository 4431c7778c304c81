// The light BVH's descent (light/light_bvh.h), one receiver at a time against a whole queue in vector lanes:
//   light_bvh/<lights>/sample   LightBvh::sample per receiver, as shade_queue called it before sample_batch
//   light_bvh/<lights>/batch    LightBvh::sample_batch over the queue (simd/light_bvh_batch.h)
// Lights: `beads`, 10,000 point lights on a 100 x 100 grid at heights 0.4-1.2 over a floor that holds the receivers
// (as scenes/many-lights.lua; its groups have normals everywhere: the short path of the importance), and `voxel`,
// 8,192 one-sided axis-aligned unit faces scattered through a 64^3 block with receivers of axis normals among
// them (a voxel world's emitting patches; their cones of normals take the full cone bound at every node).
// Queues of 4096 receivers, as the renderer shades them. Msamples = light choices per second of CPU time. Both
// cases give the same choices, bit for bit where the scalar code has no fused multiply-adds (the test of the
// batch descent checks it on every target); each case checks its choices against the other's.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/rng.h"
#include "light/emissive_patches.h"
#include "light/light_bvh.h"

using namespace torte;

namespace {

constexpr size_t kQueue = 4096;

struct Setup {
  std::vector<Light> lights;
  std::vector<float> power;
  std::unique_ptr<LightBvh> bvh;
  std::vector<Vec3f> p, n;
  std::vector<float> u;
};

const Setup& beads() {
  static const Setup s = [] {
    Setup s;
    for (int i = 0; i < 100; ++i)
      for (int j = 0; j < 100; ++j) {
        Light l;
        l.kind = LightKind::Point;
        const float h = float(((i * 73856093) ^ (j * 19349663)) % 1000) / 1000;
        l.position = {-10 + 20 * (i + 0.5f) / 100, 0.4f + 0.8f * h, -10 + 20 * (j + 0.5f) / 100};
        l.radiance = Rgb(1.2f);
        s.lights.push_back(l);
      }
    const EmitterView view{{}, {}, {}, {0, 0, 0}, 20};
    for (const Light& l : s.lights) s.power.push_back(light_power(view, l));
    s.bvh = std::make_unique<LightBvh>(view, s.lights, s.power);
    Pcg32 rng(3);
    for (size_t k = 0; k < kQueue; ++k) {
      s.p.push_back({rng.next_float() * 24 - 12, 0, rng.next_float() * 24 - 12});
      s.n.push_back({0, 1, 0});
      s.u.push_back(rng.next_float());
    }
    return s;
  }();
  return s;
}

const Setup& voxel() {
  static const Setup s = [] {
    Setup s;
    auto patches = std::make_shared<EmissivePatches>();
    Pcg32 rng(5);
    const Vec3f axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int i = 0; i < 8192; ++i) {
      const Vec3f o(float(rng.next_u32() % 64), float(rng.next_u32() % 64), float(rng.next_u32() % 64));
      const int a = int(rng.next_u32() % 3);
      const float sign = rng.next_u32() % 2 ? 1.0f : -1.0f;
      patches->add_parallelogram(o, axes[(a + 1) % 3], axes[(a + 2) % 3], axes[a] * sign, Rgb(2.0f), false);
    }
    patches->finish();
    Light l;
    l.kind = LightKind::Patches;
    l.patches = patches;
    s.lights.push_back(l);
    const EmitterView view{{}, {}, {}, {32, 32, 32}, 56};
    s.power.push_back(light_power(view, l));
    s.bvh = std::make_unique<LightBvh>(view, s.lights, s.power);
    for (size_t k = 0; k < kQueue; ++k) {
      s.p.push_back({rng.next_float() * 64, rng.next_float() * 64, rng.next_float() * 64});
      s.n.push_back(axes[rng.next_u32() % 3] * (rng.next_u32() % 2 ? 1.0f : -1.0f));
      s.u.push_back(rng.next_float());
    }
    return s;
  }();
  return s;
}

void BM_LightBvh(benchmark::State& state, const Setup& (*setup)(), bool batch) {
  const Setup& s = setup();
  std::vector<int> light(kQueue), other(kQueue);
  std::vector<float> pmf(kQueue);
  std::vector<uint32_t> part(kQueue);
  for (auto _ : state) {
    if (batch) {
      s.bvh->sample_batch(kQueue, s.p.data(), s.n.data(), s.u.data(), light.data(), pmf.data(), part.data());
    } else {
      for (size_t k = 0; k < kQueue; ++k) light[k] = s.bvh->sample(s.p[k], s.n[k], s.u[k], &pmf[k], &part[k]);
    }
    benchmark::DoNotOptimize(light.data());
    benchmark::ClobberMemory();
  }
  // The other way's choices: the same lights (a wrong kernel would not pass for a fast one).
  if (batch) {
    for (size_t k = 0; k < kQueue; ++k) other[k] = s.bvh->sample(s.p[k], s.n[k], s.u[k], &pmf[k], &part[k]);
  } else {
    s.bvh->sample_batch(kQueue, s.p.data(), s.n.data(), s.u.data(), other.data(), pmf.data(), part.data());
  }
  size_t differ = 0, none = 0;
  for (size_t k = 0; k < kQueue; ++k) differ += light[k] != other[k], none += light[k] < 0;
  if (differ > 0) state.SkipWithError((std::to_string(differ) + " choices differ between sample and batch").c_str());
  state.counters["Msamples"] =
      benchmark::Counter(double(kQueue) * double(state.iterations()) * 1e-6, benchmark::Counter::kIsRate);
  state.counters["nodes"] = double(s.bvh->node_count());
  state.counters["no_light%"] = 100.0 * double(none) / double(kQueue);
}

[[maybe_unused]] const bool registered = [] {
  for (const auto& [name, setup] : {std::pair{"beads", &beads}, std::pair{"voxel", &voxel}}) {
    benchmark::RegisterBenchmark((std::string("light_bvh/") + name + "/sample").c_str(), BM_LightBvh, setup, false)
        ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark((std::string("light_bvh/") + name + "/batch").c_str(), BM_LightBvh, setup, true)
        ->Unit(benchmark::kMicrosecond);
  }
  return true;
}();

}  // namespace
