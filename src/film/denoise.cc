#include "film/denoise.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "core/vec.h"

namespace torte {

namespace {

const ImageLayer& required_layer(const Image& image, const char* name, size_t channels) {
  const ImageLayer* l = image.layer(name);
  if (!l)
    throw Error(std::string("torte.denoise: the image has no '") + name +
                "' layer (render it with aovs = {\"albedo\", \"normal\", \"depth\"} or denoise = true)");
  if (l->channels.size() != channels || l->values.size() != image.pixels.size() * channels)
    throw Error(std::string("torte.denoise: the '") + name + "' layer does not match the image");
  return *l;
}

float luminance(Rgb c) { return c.luminance(); }

// Albedo below this is treated as 1 when demodulating: dividing by it would amplify noise without bound.
constexpr float kMinAlbedo = 1e-3f;
// The noise estimate takes the median residual over a (2 kMadRadius + 1)^2 window: wide enough that a highlight
// or shadow edge is a minority of it.
constexpr int kMadRadius = 3;
// How far (pixels, along x or y) a pixel that sees an emitter looks for the surface lighting it is rebuilt with
// (see Guide::emits).
constexpr int kEmitterReach = 16;

// The normal weight's cos power for a pixel of glossiness `gloss` (the "glossiness" layer: about cos(theta) for
// a diffuse surface, far above 1 for a glossy one). Bump-mapped glossy metal reflects a different scene in normals
// a few degrees apart (cos^128 from a glossiness of 256); the lighting of a diffuse surface changes slowly with its
// normal, and a strict weight there leaves small curved objects unfiltered (cos^4). Without the layer every pixel
// is taken as glossy, as before the layer existed.
float normal_exponent(float gloss) { return std::clamp(0.5f * gloss, 4.0f, 128.0f); }

struct Guide {
  int w = 0, h = 0;
  std::vector<Rgb> albedo;
  std::vector<Vec3f> normal;
  std::vector<float> depth, depth_slope;  // depth and its largest change to a 4-neighbour (for the depth weight)
  std::vector<float> normal_exponent;     // per pixel, the normal weight's cos power (see normal_exponent())
  // Pixels that see an area light (the "emission" layer, where present): emitted light is much brighter than the
  // lighting next to it, so they are not neighbours of other pixels. The render's coverage of an emitter is noisy
  // (at its outline, and wherever small emitters of different colours share pixels, as 10,000 beads do), so such
  // a pixel is rebuilt as the lighting of the nearest non-emitting pixels (kEmitterReach) times its albedo
  // plus the layer's emission (from the AOV pass's stratified samples); deeper inside an emitter it keeps its value.
  std::vector<uint8_t> emits;
  bool hit(size_t i) const { return std::isfinite(depth[i]); }
};

Guide make_guide(const Image& image) {
  const ImageLayer& a = required_layer(image, "albedo", 3);
  const ImageLayer& n = required_layer(image, "normal", 3);
  const ImageLayer& z = required_layer(image, "depth", 1);
  Guide g;
  g.w = image.width, g.h = image.height;
  const size_t count = image.pixels.size();
  g.albedo.resize(count), g.normal.resize(count), g.depth.resize(count), g.depth_slope.resize(count);
  g.emits.assign(count, 0);
  if (const ImageLayer* e = image.layer("emission")) {
    if (e->channels.size() != 3 || e->values.size() != 3 * count)
      throw Error("torte.denoise: the 'emission' layer does not match the image");
    for (size_t i = 0; i < count; ++i) g.emits[i] = e->at(i)[0] > 0 || e->at(i)[1] > 0 || e->at(i)[2] > 0;
  }
  g.normal_exponent.assign(count, 128.0f);
  if (const ImageLayer* gl = image.layer("glossiness")) {
    if (gl->channels.size() != 1 || gl->values.size() != count)
      throw Error("torte.denoise: the 'glossiness' layer does not match the image");
    for (size_t i = 0; i < count; ++i) g.normal_exponent[i] = normal_exponent(gl->values[i]);
  }
  for (size_t i = 0; i < count; ++i) {
    const float* av = a.at(i);
    const float* nv = n.at(i);
    g.albedo[i] = Rgb(av[0], av[1], av[2]);
    g.normal[i] = Vec3f(nv[0], nv[1], nv[2]);
    g.depth[i] = z.values[i];
  }
  for (int y = 0; y < g.h; ++y)
    for (int x = 0; x < g.w; ++x) {
      const size_t i = size_t(y) * size_t(g.w) + size_t(x);
      float slope = 0;
      const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
      for (int k = 0; k < 4; ++k) {
        if (nx[k] < 0 || ny[k] < 0 || nx[k] >= g.w || ny[k] >= g.h) continue;
        const size_t j = size_t(ny[k]) * size_t(g.w) + size_t(nx[k]);
        if (g.hit(i) && g.hit(j)) slope = std::max(slope, std::fabs(g.depth[j] - g.depth[i]));
      }
      g.depth_slope[i] = slope;
    }
  return g;
}

Rgb demodulate_factor(Rgb albedo) {
  const auto f = [](float a) { return a > kMinAlbedo ? a : 1.0f; };
  return {f(albedo.r), f(albedo.g), f(albedo.b)};
}

// Edge-stopping weight of neighbour j for pixel i at pixel distance `dist`, without the luminance term.
float feature_weight(const Guide& g, size_t i, size_t j, float dist) {
  if (g.hit(i) != g.hit(j) || g.emits[i] != g.emits[j]) return 0;
  if (!g.hit(i)) return 1;  // escaped rays: the sky, smooth by construction
  const float nd = std::max(0.0f, dot(g.normal[i], g.normal[j]));
  const float wn = std::pow(nd, g.normal_exponent[i]);
  const float dz = std::fabs(g.depth[i] - g.depth[j]);
  const float wz = std::exp(-dz / (2 * g.depth_slope[i] * dist + 1e-3f * std::fabs(g.depth[i]) + 1e-6f));
  const Rgb da = g.albedo[i] - g.albedo[j];
  const float wa = std::exp(-(da.r * da.r + da.g * da.g + da.b * da.b) / 0.02f);
  return wn * wz * wa;
}

// Per-pixel variance of the demodulated luminance, robust to structure in the signal: the residual of each pixel
// against its feature-matched 3x3 neighbours is mostly noise, except where the lighting has an edge (a
// highlight, a shadow); the median of the residuals over a 7x7 window ignores those few, where a spread over the
// window would count the edge as noise and let the filter blur it.
std::vector<float> estimate_variance(const Guide& g, const std::vector<Rgb>& light) {
  const int w = g.w, h = g.h;
  std::vector<float> res(light.size()), out(light.size());
  parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * size_t(w) + size_t(x);
      double sw = 0, s1 = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int qx = x + dx, qy = y + dy;
          if ((dx == 0 && dy == 0) || qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
          const size_t j = size_t(qy) * size_t(w) + size_t(qx);
          const float fw = feature_weight(g, i, j, std::sqrt(float(dx * dx + dy * dy)));
          if (fw <= 1e-3f) continue;
          sw += fw, s1 += fw * luminance(light[j]);
        }
      // A residual against n neighbours' mean has variance (1 + 1/n) sigma^2; 8 neighbours assumed.
      res[i] = sw > 0 ? float(std::fabs(luminance(light[i]) - s1 / sw)) : -1.0f;
    }
  });
  parallel_for(0, h, [&](int y) {
    std::vector<float> r;
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * size_t(w) + size_t(x);
      r.clear();
      for (int dy = -kMadRadius; dy <= kMadRadius; ++dy)
        for (int dx = -kMadRadius; dx <= kMadRadius; ++dx) {
          const int qx = x + dx, qy = y + dy;
          if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
          const size_t j = size_t(qy) * size_t(w) + size_t(qx);
          if (res[j] < 0 || feature_weight(g, i, j, std::sqrt(float(dx * dx + dy * dy))) <= 1e-3f) continue;
          r.push_back(res[j]);
        }
      if (r.empty()) { out[i] = 0; continue; }
      std::nth_element(r.begin(), r.begin() + r.size() / 2, r.end());
      const float sigma = 1.4826f * r[r.size() / 2] / std::sqrt(1 + 1 / 8.0f);
      out[i] = sigma * sigma;
    }
  });
  return out;
}

// The luminance the edge-stopping weights compare: the median of the pixel and its feature-matched 4-neighbours.
// A firefly (one rare bright sample) is then compared as what its neighbours are, so its energy is spread over
// them instead of kept in place; a highlight's corner, or a line one pixel wide, has two of its four neighbours
// at its level and keeps its value (a 3x3 median would round a small highlight's corners off). A pixel whose
// own luminance lies more than kKeepSigmas standard deviations (`var`, per pixel; none when empty) from that
// median keeps it: its samples agree on a value its neighbours do not have, a glint of bump-mapped metal one
// pixel wide, where a firefly's few bright samples leave its variance as large as its difference.
constexpr float kKeepSigmas = 2;
std::vector<float> median_guide(const Guide& g, const std::vector<Rgb>& light, const std::vector<float>& var) {
  const int w = g.w, h = g.h;
  std::vector<float> out(light.size());
  parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * size_t(w) + size_t(x);
      float v[5] = {luminance(light[i])};
      int n = 1;
      const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
      for (int k = 0; k < 4; ++k) {
        if (nx[k] < 0 || ny[k] < 0 || nx[k] >= w || ny[k] >= h) continue;
        const size_t j = size_t(ny[k]) * size_t(w) + size_t(nx[k]);
        if (feature_weight(g, i, j, 1) > 1e-3f) v[n++] = luminance(light[j]);
      }
      std::nth_element(v, v + n / 2, v + n);
      const float d = luminance(light[i]) - v[n / 2];
      out[i] = !var.empty() && d * d > kKeepSigmas * kKeepSigmas * var[i] ? luminance(light[i]) : v[n / 2];
    }
  });
  return out;
}

// For each pixel, the nearest pixel that sees a surface and no emitter (-1: none), by a forward and a backward
// sweep in which each pixel keeps the nearest of its swept neighbours' answers (nearly Euclidean). Linear in the
// pixels, where searching squares of growing size would cost a frame filled by one emitter its area many times.
std::vector<int32_t> nearest_surface(const Guide& g) {
  const int w = g.w, h = g.h;
  std::vector<int32_t> seed(size_t(w) * size_t(h), -1);
  for (size_t i = 0; i < seed.size(); ++i)
    if (!g.emits[i] && g.hit(i)) seed[i] = int32_t(i);
  const auto relax = [&](int x, int y, int nx, int ny) {
    if (nx < 0 || ny < 0 || nx >= w || ny >= h) return;
    const int32_t s = seed[size_t(ny) * size_t(w) + size_t(nx)];
    if (s < 0) return;
    int32_t& mine = seed[size_t(y) * size_t(w) + size_t(x)];
    const auto dist2 = [&](int32_t t) {
      const int64_t dx = t % w - x, dy = t / w - y;
      return dx * dx + dy * dy;
    };
    if (mine < 0 || dist2(s) < dist2(mine)) mine = s;
  };
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      relax(x, y, x - 1, y), relax(x, y, x - 1, y - 1), relax(x, y, x, y - 1), relax(x, y, x + 1, y - 1);
    }
    for (int x = w - 1; x >= 0; --x) relax(x, y, x + 1, y);
  }
  for (int y = h - 1; y >= 0; --y) {
    for (int x = w - 1; x >= 0; --x) {
      relax(x, y, x + 1, y), relax(x, y, x + 1, y + 1), relax(x, y, x, y + 1), relax(x, y, x - 1, y + 1);
    }
    for (int x = 0; x < w; ++x) relax(x, y, x - 1, y);
  }
  return seed;
}

}  // namespace

Image denoise(const Image& image, const DenoiseOptions& options) {
  if (!(options.strength > 0 && options.strength <= 100))
    throw Error("torte.denoise: 'strength' must be in (0, 100], got " + std::to_string(options.strength));
  if (options.iterations < 1 || options.iterations > 10)
    throw Error("torte.denoise: 'iterations' must be in [1, 10], got " + std::to_string(options.iterations));
  if (image.width <= 0 || image.height <= 0 || image.pixels.size() != size_t(image.width) * size_t(image.height))
    throw Error("torte.denoise: the image is empty");
  const Guide g = make_guide(image);
  const size_t count = image.pixels.size();
  const int w = g.w, h = g.h;

  // Lighting = colour / albedo (non-finite samples, which the film should not hold, count as black).
  std::vector<Rgb> light(count), next(count);
  for (size_t i = 0; i < count; ++i) {
    const Rgb c = image.pixels[i].is_finite() ? image.pixels[i] : Rgb(0);
    const Rgb f = demodulate_factor(g.albedo[i]);
    light[i] = Rgb(c.r / f.r, c.g / f.g, c.b / f.b);
  }
  std::vector<float> var = estimate_variance(g, light), next_var(count);
  // The render's own variance of each pixel's mean (the "variance" layer), in the units of `light`: it tells a
  // glint whose samples agree from a firefly for the first pass's median guide (see median_guide). The filter's
  // tolerance keeps the estimate above, from the neighbours: 16 samples' own variance is too noisy for that.
  std::vector<float> sample_var;
  if (const ImageLayer* v = image.layer("variance")) {
    if (v->channels.size() != 1 || v->values.size() != count)
      throw Error("torte.denoise: the 'variance' layer does not match the image");
    sample_var.resize(count);
    for (size_t i = 0; i < count; ++i) {
      const float lc = image.pixels[i].is_finite() ? luminance(image.pixels[i]) : 0.0f, ll = luminance(light[i]);
      const float k = lc > 1e-6f ? ll / lc : 1 / std::max(kMinAlbedo, luminance(demodulate_factor(g.albedo[i])));
      sample_var[i] = v->values[i] * k * k;
    }
  }

  constexpr float kKernel[5] = {1 / 16.0f, 1 / 4.0f, 3 / 8.0f, 1 / 4.0f, 1 / 16.0f};
  const float sigma_l = 2 * options.strength;
  for (int it = 0; it < options.iterations; ++it) {
    const int step = 1 << it;
    // Later passes judge glints by the variance the filter has carried along.
    const std::vector<float> guide = median_guide(g, light, it == 0 ? sample_var : var);
    parallel_for(0, h, [&](int y) {
      for (int x = 0; x < w; ++x) {
        const size_t i = size_t(y) * size_t(w) + size_t(x);
        const float li = guide[i];
        const float tol = sigma_l * std::sqrt(var[i]) + 1e-6f;
        Rgb sum;
        float sw = 0, svar = 0;
        for (int ky = 0; ky < 5; ++ky)
          for (int kx = 0; kx < 5; ++kx) {
            const int dx = (kx - 2) * step, dy = (ky - 2) * step;
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            const size_t j = size_t(qy) * size_t(w) + size_t(qx);
            float wt = kKernel[kx] * kKernel[ky];
            if (j != i) {
              wt *= feature_weight(g, i, j, std::sqrt(float(dx * dx + dy * dy)));
              wt *= std::exp(-std::fabs(li - guide[j]) / tol);
            }
            if (wt <= 0) continue;
            sum += light[j] * wt;
            sw += wt;
            svar += wt * wt * var[j];
          }
        next[i] = sum / sw;  // sw > 0: the centre tap always counts
        next_var[i] = svar / (sw * sw);
      }
    });
    light.swap(next);
    var.swap(next_var);
  }

  // See Guide::emits.
  const ImageLayer* emission = image.layer("emission");
  const std::vector<int32_t> surface = nearest_surface(g);
  const auto emitter_pixel = [&](size_t i) {
    if (!g.hit(i)) return image.pixels[i];
    // The lighting of non-emitting surfaces around pixel c (normals like pixel i's weigh most): next to the
    // emitter, the best guess of what the emitter's own surface reflects.
    const auto lighting_around = [&](size_t c, Rgb* lighting) {
      const int x = int(c % size_t(w)), y = int(c / size_t(w));
      Rgb sum;
      float sw = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int qx = x + dx, qy = y + dy;
          if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
          const size_t j = size_t(qy) * size_t(w) + size_t(qx);
          if (g.emits[j] || !g.hit(j)) continue;
          const float wt = std::pow(std::max(0.0f, dot(g.normal[i], g.normal[j])), 64.0f) + 1e-6f;
          sum += light[j] * wt, sw += wt;
        }
      if (sw > 0) *lighting = sum / sw;
      return sw > 0;
    };
    Rgb lighting;
    bool found = lighting_around(i, &lighting);
    if (!found && surface[i] >= 0) {
      const size_t s = size_t(surface[i]);
      const int dx = int(s % size_t(w)) - int(i % size_t(w)), dy = int(s / size_t(w)) - int(i / size_t(w));
      found = std::max(std::abs(dx), std::abs(dy)) <= kEmitterReach && lighting_around(s, &lighting);
    }
    if (!found) return image.pixels[i];  // deep inside a large emitter
    const float* e = emission->at(i);
    return lighting * g.albedo[i] + Rgb(e[0], e[1], e[2]);
  };
  Image out(w, h);
  out.attributes = image.attributes;
  out.layers = image.layers;
  ImageLayer noisy{"noisy", {"R", "G", "B"}, std::vector<float>(3 * count)};
  for (size_t i = 0; i < count; ++i) {
    out.pixels[i] = g.emits[i] ? emitter_pixel(i) : light[i] * demodulate_factor(g.albedo[i]);
    noisy.values[3 * i] = image.pixels[i].r, noisy.values[3 * i + 1] = image.pixels[i].g;
    noisy.values[3 * i + 2] = image.pixels[i].b;
  }
  std::erase_if(out.layers, [](const ImageLayer& l) { return l.name == "noisy"; });
  out.layers.push_back(std::move(noisy));
  return out;
}

}  // namespace torte
