// Images beyond pixels: AOV requests of torte.render{} (aovs, aov_samples, denoise; render/aov_pass.h),
// image.layers and image:layer(name), and torte.denoise (film/denoise.h).
#include <algorithm>
#include <string>
#include <vector>

#include "film/denoise.h"
#include "render/aov_pass.h"
#include "types.h"

namespace torte::lua {

std::vector<Aov> parse_aov_names(const std::vector<std::string>& names, const std::string& where) {
  std::vector<Aov> out;
  for (const std::string& n : names) {
    Aov a;
    if (!parse_aov(n, a)) throw Error(where + ": unknown AOV '" + n + "' (known: " + kAovChoices + ")");
    if (std::find(out.begin(), out.end(), a) == out.end()) out.push_back(a);
  }
  return out;
}

AovRequest read_aov_request(KwArgs& kw, int spp) {
  AovRequest r;
  lua_State* L = kw.state();
  kw.push("aovs");
  if (!lua_isnil(L, -1)) {
    if (!lua_istable(L, -1)) {
      lua_pop(L, 1);
      kw.fail("aovs", std::string("must be a list of names (") + kAovChoices + ")");
    }
    std::vector<std::string> names;
    const lua_Integer n = luaL_len(L, -1);
    for (lua_Integer i = 1; i <= n; ++i) {
      lua_geti(L, -1, i);
      if (lua_type(L, -1) != LUA_TSTRING) {
        lua_pop(L, 2);
        kw.fail("aovs", "entry " + std::to_string(i) + " is not a name");
      }
      names.push_back(lua_tostring(L, -1));
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
    try {
      r.aovs = parse_aov_names(names, "aovs");
    } catch (const Error& e) {
      kw.fail("aovs", std::string(e.what()).substr(6));
    }
  } else {
    lua_pop(L, 1);
  }
  r.denoise = kw.boolean("denoise", false);
  // AOVs need far fewer samples than light: they only average over the pixel footprint and lens.
  r.samples = kw.integer("aov_samples", std::min(spp, 16));
  if (r.samples < 1 || r.samples > 4096) kw.fail("aov_samples", "must be in [1, 4096], got " + std::to_string(r.samples));
  return r;
}

void add_aovs(RenderedImage& img, const Scene& scene, const Camera& camera, const RenderSettings& s,
              AovRequest request, const std::atomic<bool>* cancel) {
  std::vector<Aov> aovs = request.aovs;
  if (request.denoise)
    for (Aov a : {Aov::Albedo, Aov::Normal, Aov::Depth, Aov::Emission})
      if (std::find(aovs.begin(), aovs.end(), a) == aovs.end()) aovs.push_back(a);
  const auto counted = std::find(aovs.begin(), aovs.end(), Aov::Samples);
  const bool samples = counted != aovs.end();
  if (samples) aovs.erase(counted);
  if (!aovs.empty()) img.image.layers = render_aovs(scene, camera, s, aovs, request.samples, cancel);
  if (samples)
    img.image.layers.push_back(samples_layer(s.width, s.height, img.pixel_spp, img.stats.spp_reached));
  if (aovs.empty()) return;
  if (request.denoise) img.image = denoise(img.image);
}

namespace {

// image:layer(name) -> an image of that layer: three channels as R, G, B; one channel as grey.
int image_layer(lua_State* L) {
  auto img = to_object<RenderedImage>(L, 1);
  if (!img) throw Error("image:layer must be called with ':' on an image");
  const std::string name = luaL_checkstring(L, 2);
  const ImageLayer* layer = img->image.layer(name);
  if (!layer) {
    std::string known;
    for (const ImageLayer& l : img->image.layers) known += (known.empty() ? "" : ", ") + l.name;
    throw Error("image:layer: the image has no layer '" + name + "' (it has: " + (known.empty() ? "none" : known) +
                ")");
  }
  auto out = std::make_shared<RenderedImage>();
  out->image = Image(img->image.width, img->image.height);
  out->image.attributes = img->image.attributes;
  const size_t k = layer->channels.size();
  for (size_t i = 0; i < out->image.pixels.size(); ++i) {
    const float* v = layer->at(i);
    out->image.pixels[i] = k >= 3 ? Rgb(v[0], v[1], v[2]) : Rgb(v[0]);
  }
  out->stats = img->stats;
  push_object(L, std::move(out));
  return 1;
}

// torte.denoise(image [, {strength = 1, iterations = 5}]) -> a new image (film/denoise.h).
int l_denoise(lua_State* L) {
  auto img = to_object<RenderedImage>(L, 1);
  if (!img) throw Error("torte.denoise expects an image, got " + type_name(L, 1));
  DenoiseOptions o;
  if (!lua_isnoneornil(L, 2)) {
    KwArgs kw(L, 2, "torte.denoise");
    o.strength = float(kw.number("strength", o.strength));
    o.iterations = kw.integer("iterations", o.iterations);
    kw.finish();
  }
  auto out = std::make_shared<RenderedImage>(*img);
  out->image = denoise(img->image, o);
  push_object(L, std::move(out));
  return 1;
}

}  // namespace

bool push_image_field(lua_State* L, const RenderedImage& img, const std::string& key) {
  if (key == "layers") {
    lua_createtable(L, int(img.image.layers.size()), 0);
    for (size_t i = 0; i < img.image.layers.size(); ++i) {
      lua_pushstring(L, img.image.layers[i].name.c_str());
      lua_seti(L, -2, lua_Integer(i + 1));
    }
    return true;
  }
  return false;
}

void open_images(lua_State* L, int torte_index) {
  // image:layer joins the methods open_render gave the image metatable.
  luaL_getmetatable(L, LuaName<RenderedImage>::value);
  lua_getfield(L, -1, "__methods");
  lua_pushcfunction(L, guarded<image_layer>);
  lua_setfield(L, -2, "layer");
  lua_pop(L, 2);
  const luaL_Reg fns[] = {{"denoise", guarded<l_denoise>}, {nullptr, nullptr}};
  lua_pushvalue(L, torte_index);
  set_functions(L, fns);
  lua_pop(L, 1);
}

}  // namespace torte::lua
