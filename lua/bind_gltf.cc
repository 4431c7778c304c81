// torte.gltf.load(path): a glTF 2.0 file (.gltf with embedded or external buffers, or .glb) read by Debian's
// libtinygltf, as torte objects (docs/formats.md says what is approximated):
//
//   local g = torte.gltf.load("model.glb")
//   scene:add(torte.instance{group = g.group})  -- its meshes (node transforms applied) and punctual lights
//   scene:add(g.emitters)                       -- emissive meshes: area lights belong to the rendered scene
//   local camera = g.cameras[1]                 -- torte cameras in file order; g.materials by name; g.lights
#include <tiny_gltf.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <string_view>
#include <unistd.h>

#include "core/text.h"
#include "file_access.h"
#include "origin.h"
#include "runtime.h"
#include "texture/image_texture_oiio.h"
#include "types.h"

namespace torte::lua {

namespace {

constexpr const char* kFn = "torte.gltf.load";
constexpr double kLumensPerWatt = 683;

// tinygltf hands over every image's encoded bytes (from a file, a data: URI or a buffer view of a .glb); they are
// kept as they are (not decoded) and written to a file only when the image is embedded: OpenImageIO's texture
// cache opens textures by path and reads their tiles when it needs them.
bool keep_image_bytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  image->image.assign(bytes, bytes + std::max(size, 0));
  image->as_is = true;
  return true;
}

// A directory in the system's temporary directory for the embedded images of this process, removed at exit.
class EmbeddedImageDir {
 public:
  ~EmbeddedImageDir() {
    std::error_code ec;
    if (!dir_.empty()) std::filesystem::remove_all(dir_, ec);
  }
  // Writes `bytes` once per content and returns the file's path (the extension tells OpenImageIO the format).
  std::string write(const std::vector<unsigned char>& bytes, const std::string& extension) {
    std::lock_guard lock(mutex_);
    if (dir_.empty()) {
      dir_ = std::filesystem::temp_directory_path() / ("torte-gltf-" + std::to_string(::getpid()));
      std::filesystem::create_directories(dir_);
    }
    const size_t h = std::hash<std::string_view>()(
        std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
    const std::filesystem::path file = dir_ / (std::to_string(h) + "-" + std::to_string(bytes.size()) + extension);
    if (!std::filesystem::exists(file)) {
      const std::filesystem::path partial = file.string() + ".partial";
      std::ofstream out(partial, std::ios::binary);
      out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
      out.close();
      if (!out) throw Error("cannot write an embedded image to " + escape_text(partial.string()));
      std::filesystem::rename(partial, file);
    }
    return file.string();
  }

 private:
  std::mutex mutex_;
  std::filesystem::path dir_;
};

EmbeddedImageDir& embedded_images() {
  static EmbeddedImageDir dir;
  return dir;
}

struct Importer {
  lua_State* L;
  std::string path, dir;
  tinygltf::Model model;
  std::vector<std::shared_ptr<MaterialDesc>> materials;
  std::vector<Rgb> emission;  // per material
  std::vector<TexturePtr> emission_texture;  // per material: the emissive texture (times `emission`), or null
  std::vector<std::vector<std::shared_ptr<const TriangleMesh>>> meshes;  // per mesh, per primitive (null: skipped)
  std::vector<std::vector<int>> mesh_material;
  std::shared_ptr<SceneBuilder> group = std::make_shared<SceneBuilder>();
  std::vector<ShapeDesc> emitters;
  std::vector<std::shared_ptr<CameraDesc>> cameras;
  std::vector<std::shared_ptr<Light>> lights;

  [[noreturn]] void fail(const std::string& problem) const {
    throw Error(std::string(kFn) + ": " + escape_text(path) + ": " + problem);
  }
  void warn(const std::string& problem) const {
    std::fprintf(stderr, "torte: warning: %s: %s: %s\n", kFn, escape_text(path).c_str(), problem.c_str());
  }

  // Element `i` of accessor `a` as up to 4 floats (normalized integers mapped to [0, 1] or [-1, 1]).
  struct View {
    const unsigned char* data = nullptr;
    size_t stride = 0, count = 0;
    int type = 0, components = 0;
    bool normalized = false;
  };
  View view(int index, const char* what) const {
    if (index < 0 || size_t(index) >= model.accessors.size()) fail(std::string(what) + ": no accessor " + std::to_string(index));
    const tinygltf::Accessor& a = model.accessors[size_t(index)];
    if (a.sparse.isSparse) fail(std::string(what) + ": sparse accessors are not supported");
    if (a.bufferView < 0 || size_t(a.bufferView) >= model.bufferViews.size())
      fail(std::string(what) + ": accessor " + std::to_string(index) + " has no buffer view");
    const tinygltf::BufferView& bv = model.bufferViews[size_t(a.bufferView)];
    if (bv.buffer < 0 || size_t(bv.buffer) >= model.buffers.size()) fail(std::string(what) + ": bad buffer index");
    const tinygltf::Buffer& b = model.buffers[size_t(bv.buffer)];
    View v;
    v.type = a.componentType;
    v.components = tinygltf::GetNumComponentsInType(uint32_t(a.type));
    const int size = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
    if (v.components <= 0 || size <= 0) fail(std::string(what) + ": bad accessor type");
    const size_t elem = size_t(v.components) * size_t(size);
    v.stride = bv.byteStride ? bv.byteStride : elem;
    v.count = a.count;
    v.normalized = a.normalized;
    const uint64_t need = a.count == 0 ? 0 : uint64_t(a.byteOffset) + v.stride * (a.count - 1) + elem;
    if (bv.byteOffset + bv.byteLength > b.data.size() || need > bv.byteLength)
      fail(std::string(what) + ": accessor " + std::to_string(index) + " reaches past the end of its buffer");
    v.data = b.data.data() + bv.byteOffset + a.byteOffset;
    return v;
  }
  static double component(const View& v, size_t i, int c) {
    const unsigned char* p = v.data + i * v.stride;
    switch (v.type) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p + 4 * c, 4); return f; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return v.normalized ? p[c] / 255.0 : p[c];
      case TINYGLTF_COMPONENT_TYPE_BYTE: { const int8_t x = int8_t(p[c]); return v.normalized ? std::max(x / 127.0, -1.0) : x; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t x; std::memcpy(&x, p + 2 * c, 2); return v.normalized ? x / 65535.0 : x; }
      case TINYGLTF_COMPONENT_TYPE_SHORT: { int16_t x; std::memcpy(&x, p + 2 * c, 2); return v.normalized ? std::max(x / 32767.0, -1.0) : x; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t x; std::memcpy(&x, p + 4 * c, 4); return x; }
      default: return 0;
    }
  }

  // Texture `index` of the file (nullptr for -1), its channels from `first_channel` on as R, G, B. An image that
  // cannot be read is a warning and no texture (the material's factor alone), as other renderers do.
  std::shared_ptr<const ImageSource> image_source(int index, bool color, int first_channel = 0,
                                                  bool quiet = false) const {
    if (index < 0) return nullptr;
    if (size_t(index) >= model.textures.size()) fail("no texture " + std::to_string(index));
    const int source = model.textures[size_t(index)].source;
    if (source < 0 || size_t(source) >= model.images.size()) fail("texture " + std::to_string(index) + " has no image");
    const tinygltf::Image& image = model.images[size_t(source)];
    ImageTextureOptions o;
    if (!color) o.color_space = ImageTextureOptions::ColorSpace::Linear;
    o.first_channel = first_channel;
    try {
      std::string file;
      if (!image.uri.empty() && !image.uri.starts_with("data:")) {
        file = (std::filesystem::path(dir) / image.uri).string();
        check_read(L, file, kFn);
      } else {
        if (image.image.empty()) {
          warn("image " + std::to_string(source) + " holds no data (the texture is ignored)");
          return nullptr;
        }
        const std::string mime = !image.mimeType.empty() ? image.mimeType : image.uri.substr(5, image.uri.find(';') - 5);
        const std::string ext = mime == "image/png" ? ".png" : mime == "image/jpeg" ? ".jpg" : mime == "image/webp" ? ".webp" : "";
        if (ext.empty()) {
          warn("image " + std::to_string(source) + " has the unsupported type " + quote_text(mime) + " (ignored)");
          return nullptr;
        }
        file = embedded_images().write(image.image, ext);
      }
      return open_image_texture(file, o);
    } catch (const Error& e) {
      if (!quiet) warn(std::string(e.what()) + " (the texture is ignored)");
      return nullptr;
    }
  }
  TexturePtr texture(int index, bool color) const {
    auto src = image_source(index, color);
    return src ? texture::image(src) : nullptr;
  }
  // One channel of a linear texture as a float texture times `factor` (glTF's metallic-roughness image).
  TexturePtr channel(int index, int c, float factor) const {
    auto src = image_source(index, false, c);
    if (!src) return nullptr;
    TexturePtr t = texture::image_scalar(src);
    return factor == 1.0f ? t : texture::scale(t, factor);
  }

  void read_materials() {
    for (const tinygltf::Material& m : model.materials) {
      const auto& pbr = m.pbrMetallicRoughness;
      Rgb base(0.8f);
      if (pbr.baseColorFactor.size() >= 3)
        base = Rgb(float(pbr.baseColorFactor[0]), float(pbr.baseColorFactor[1]), float(pbr.baseColorFactor[2]));
      base = Rgb(std::clamp(base.r, 0.0f, 1.0f), std::clamp(base.g, 0.0f, 1.0f), std::clamp(base.b, 0.0f, 1.0f));
      const float rough = std::clamp(float(pbr.roughnessFactor), 0.0f, 1.0f);
      const float metal = std::clamp(float(pbr.metallicFactor), 0.0f, 1.0f);
      TexturePtr tex = texture(pbr.baseColorTexture.index, true);
      if (tex && base != Rgb(1)) tex = texture::multiply(tex, texture::constant(base));
      // glTF packs roughness in G and metalness in B of one linear image, each scaling its factor.
      const int mr = pbr.metallicRoughnessTexture.index;
      TexturePtr rough_tex = channel(mr, 1, rough), metal_tex = channel(mr, 2, metal);
      // glTF's alpha = roughness^2 is torte's remapped roughness.
      RoughnessInput roughness;
      roughness.u = roughness.v = {std::max(rough, 0.001f), rough_tex};
      auto dielectric = std::make_shared<MaterialDesc>();
      dielectric->type = MaterialType::CoatedDiffuse;  // glTF's dielectric: diffuse under an IOR 1.5 coat
      dielectric->color = {base, tex};
      dielectric->eta = {1.5f, nullptr};
      dielectric->roughness = roughness;
      // A conductor whose normal-incidence Fresnel reflectance is the base colour factor: k = 0 and
      // eta = (1 + sqrt(F0)) / (1 - sqrt(F0)) per channel (not expressible as a texture of the base colour).
      auto conductor = std::make_shared<MaterialDesc>();
      conductor->type = MaterialType::Conductor;
      auto eta = [](float f0) { const float s = std::sqrt(std::min(f0, 0.98f)); return (1 + s) / (1 - s); };
      conductor->eta_rgb = {Rgb(eta(base.r), eta(base.g), eta(base.b)), nullptr};
      conductor->k = {Rgb(0), nullptr};
      conductor->roughness = roughness;
      // Metallic between 0 and 1 (or a texture of it): a stochastic mix of the two, unbiased for glTF's blend.
      std::shared_ptr<MaterialDesc> desc;
      if (metal_tex) desc = make_mix(dielectric, conductor, {metal, metal_tex});
      else if (metal <= 0) desc = dielectric;
      else if (metal >= 1) desc = conductor;
      else desc = make_mix(dielectric, conductor, {metal, nullptr});
      // The normal texture: +x right and +y up in the image, which is along torte's dp/dv (v = 1 - glTF's v).
      if (TexturePtr normals = texture(m.normalTexture.index, false))
        desc = make_normal_map(desc, {Rgb(0.5f, 0.5f, 1.0f), normals}, float(m.normalTexture.scale));
      // Outermost, so it applies to whatever material this became. alphaMode MASK: a cut-out where the base
      // colour's alpha (factor times the texture's A) is below alphaCutoff; BLEND: present with probability alpha
      // (unbiased for the blend, and needs no sorting).
      if (m.alphaMode == "MASK" || m.alphaMode == "BLEND") {
        const float factor = pbr.baseColorFactor.size() >= 4 ? std::clamp(float(pbr.baseColorFactor[3]), 0.0f, 1.0f) : 1.0f;
        TexturePtr alpha;  // images without an alpha channel are opaque
        if (auto src = image_source(pbr.baseColorTexture.index, false, 3, true)) {
          alpha = texture::image_scalar(src);
          if (factor != 1.0f) alpha = texture::scale(alpha, factor);
        }
        auto masked = std::make_shared<MaterialDesc>(*desc);
        masked->alpha_masked = true;
        masked->alpha = {factor, alpha};
        masked->alpha_cutoff = m.alphaMode == "MASK" ? std::clamp(float(m.alphaCutoff), 0.0f, 1.0f) : 0.5f;
        masked->alpha_stochastic = m.alphaMode == "BLEND";
        desc = masked;
      }
      materials.push_back(desc);
      Rgb e;
      if (m.emissiveFactor.size() >= 3)
        e = Rgb(float(m.emissiveFactor[0]), float(m.emissiveFactor[1]), float(m.emissiveFactor[2]));
      if (auto it = m.extensions.find("KHR_materials_emissive_strength"); it != m.extensions.end() &&
                                                                          it->second.Has("emissiveStrength"))
        e = e * float(it->second.Get("emissiveStrength").GetNumberAsDouble());
      if (!e.is_finite() || e.r < 0 || e.g < 0 || e.b < 0 || e.max_component() > kMaxEmission)
        fail("material " + quote_text(m.name) + ": emissive factor must be finite, non-negative and at most 1e20");
      // The emissive texture (sRGB colour) times the factor: the area light's radiance at each point.
      emission_texture.push_back(e.is_black() ? nullptr : texture(m.emissiveTexture.index, true));
      emission.push_back(e);
    }
  }

  void read_meshes() {
    for (size_t mi = 0; mi < model.meshes.size(); ++mi) {
      meshes.emplace_back();
      mesh_material.emplace_back();
      for (size_t pi = 0; pi < model.meshes[mi].primitives.size(); ++pi) {
        const tinygltf::Primitive& p = model.meshes[mi].primitives[pi];
        const std::string what = "mesh " + std::to_string(mi) + " primitive " + std::to_string(pi);
        mesh_material.back().push_back(p.material);
        if (p.material >= int(materials.size())) fail(what + ": no material " + std::to_string(p.material));
        if (p.mode != -1 && p.mode != TINYGLTF_MODE_TRIANGLES) {
          warn(what + ": only triangle lists are read (mode " + std::to_string(p.mode) + " skipped)");
          meshes.back().push_back(nullptr);
          continue;
        }
        const auto pos = p.attributes.find("POSITION");
        if (pos == p.attributes.end()) fail(what + ": no POSITION attribute");
        const View vp = view(pos->second, (what + " POSITION").c_str());
        if (vp.type != TINYGLTF_COMPONENT_TYPE_FLOAT || vp.components != 3) fail(what + ": POSITION must be float VEC3");
        TriangleMesh mesh;
        for (size_t i = 0; i < vp.count; ++i)
          mesh.add_vertex({float(component(vp, i, 0)), float(component(vp, i, 1)), float(component(vp, i, 2))});
        if (auto n = p.attributes.find("NORMAL"); n != p.attributes.end()) {
          const View vn = view(n->second, (what + " NORMAL").c_str());
          if (vn.count != vp.count || vn.components != 3) fail(what + ": NORMAL must be VEC3, one per position");
          for (size_t i = 0; i < vn.count; ++i) {
            Vec3f v(float(component(vn, i, 0)), float(component(vn, i, 1)), float(component(vn, i, 2)));
            const float len = length(v);
            v = len > 0 && std::isfinite(len) ? v / len : Vec3f();
            mesh.nx.push_back(v.x), mesh.ny.push_back(v.y), mesh.nz.push_back(v.z);
          }
        }
        if (auto t = p.attributes.find("TEXCOORD_0"); t != p.attributes.end()) {
          const View vt = view(t->second, (what + " TEXCOORD_0").c_str());
          if (vt.count != vp.count || vt.components != 2) fail(what + ": TEXCOORD_0 must be VEC2, one per position");
          for (size_t i = 0; i < vt.count; ++i)  // glTF's v runs down the image, torte's up
            mesh.u.push_back(float(component(vt, i, 0))), mesh.v.push_back(1 - float(component(vt, i, 1)));
        }
        if (p.indices >= 0) {
          const View vi = view(p.indices, (what + " indices").c_str());
          if (vi.components != 1 || (vi.type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                                     vi.type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                                     vi.type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
            fail(what + ": indices must be unsigned byte, short or int scalars");
          for (size_t i = 0; i < vi.count; ++i) mesh.indices.push_back(uint32_t(component(vi, i, 0)));
        } else {
          for (size_t i = 0; i < vp.count; ++i) mesh.indices.push_back(uint32_t(i));
        }
        if (mesh.indices.size() % 3 != 0) fail(what + ": the index count is not a multiple of 3");
        try {
          mesh.validate(what);
        } catch (const Error& e) {
          fail(e.what());
        }
        meshes.back().push_back(std::make_shared<const TriangleMesh>(std::move(mesh)));
      }
    }
  }

  static Transform local(const tinygltf::Node& n) {
    if (n.matrix.size() == 16) {  // column-major
      Mat4 m;
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) m.m[r][c] = float(n.matrix[size_t(4 * c + r)]);
      return Transform(m);
    }
    Transform t;
    if (n.translation.size() == 3) t = translate(Vec3f(float(n.translation[0]), float(n.translation[1]), float(n.translation[2])));
    if (n.rotation.size() == 4) {  // unit quaternion (x, y, z, w)
      const float x = float(n.rotation[0]), y = float(n.rotation[1]), z = float(n.rotation[2]), w = float(n.rotation[3]);
      Mat4 m;
      m.m[0][0] = 1 - 2 * (y * y + z * z), m.m[0][1] = 2 * (x * y - z * w), m.m[0][2] = 2 * (x * z + y * w);
      m.m[1][0] = 2 * (x * y + z * w), m.m[1][1] = 1 - 2 * (x * x + z * z), m.m[1][2] = 2 * (y * z - x * w);
      m.m[2][0] = 2 * (x * z - y * w), m.m[2][1] = 2 * (y * z + x * w), m.m[2][2] = 1 - 2 * (x * x + y * y);
      t = t * Transform(m);
    }
    if (n.scale.size() == 3) t = t * scale(Vec3f(float(n.scale[0]), float(n.scale[1]), float(n.scale[2])));
    return t;
  }

  void node(int index, const Transform& parent, int depth) {
    if (index < 0 || size_t(index) >= model.nodes.size()) fail("no node " + std::to_string(index));
    if (depth > 64) fail("nodes nest more than 64 levels (a cycle?)");
    const tinygltf::Node& n = model.nodes[size_t(index)];
    const Transform world = parent * local(n);
    const float det = world.determinant3();
    if (!(std::fabs(det) >= 1e-20f) || !std::isfinite(det)) fail("node " + std::to_string(index) + ": singular or non-finite transform");
    if (n.mesh >= 0) {
      if (size_t(n.mesh) >= meshes.size()) fail("node " + std::to_string(index) + ": no mesh " + std::to_string(n.mesh));
      for (size_t pi = 0; pi < meshes[size_t(n.mesh)].size(); ++pi) {
        if (!meshes[size_t(n.mesh)][pi]) continue;
        ShapeDesc s;
        s.kind = ShapeDesc::Kind::Mesh;
        s.mesh = meshes[size_t(n.mesh)][pi];
        s.transform = world;
        s.origin = std::string(kFn) + " node " + std::to_string(index);
        const int mat = mesh_material[size_t(n.mesh)][pi];
        if (mat >= 0) {
          s.material = materials[size_t(mat)];
          s.emission = emission[size_t(mat)];
          s.emission_texture = emission_texture[size_t(mat)];
        }
        s.two_sided = mat >= 0 && model.materials[size_t(mat)].doubleSided;
        if (s.emission.is_black()) group->add_shape(s);
        else emitters.push_back(s);
      }
    }
    if (n.camera >= 0) camera(n.camera, world);
    if (auto it = n.extensions.find("KHR_lights_punctual"); it != n.extensions.end() && it->second.Has("light"))
      light(it->second.Get("light").GetNumberAsInt(), world);
    for (int c : n.children) node(c, world, depth + 1);
  }

  void camera(int index, const Transform& world) {
    if (size_t(index) >= model.cameras.size()) fail("no camera " + std::to_string(index));
    const tinygltf::Camera& c = model.cameras[size_t(index)];
    auto d = std::make_shared<CameraDesc>();
    // glTF cameras look down -z with +x to the right; torte's look down +z with +x to the left.
    d->camera_to_world = world * scale(Vec3f(-1, 1, -1));
    if (c.type == "orthographic") {
      d->kind = CameraKind::Orthographic;
      d->extent = float(2 * c.orthographic.ymag);
      if (!(d->extent > 0)) fail("camera " + std::to_string(index) + ": ymag must be positive");
    } else {
      d->fov_degrees = float(c.perspective.yfov * 180 / kPi);
      if (!(d->fov_degrees > 0 && d->fov_degrees < 180)) fail("camera " + std::to_string(index) + ": yfov must be in (0, pi)");
    }
    cameras.push_back(d);
  }

  void light(int index, const Transform& world) {
    if (index < 0 || size_t(index) >= model.lights.size()) fail("no light " + std::to_string(index));
    const tinygltf::Light& g = model.lights[size_t(index)];
    auto l = std::make_shared<Light>();
    l->origin = std::string(kFn) + " light " + std::to_string(index);
    Rgb color(1);
    if (g.color.size() >= 3) color = Rgb(float(g.color[0]), float(g.color[1]), float(g.color[2]));
    // glTF's candela (point, spot) and lux (directional) are photometric; torte's intensities are radiometric
    // (W/sr, W/m^2): 683 lm/W, the luminous efficacy at 555 nm, as Blender's exporter converts its watts.
    l->radiance = color * float(g.intensity / kLumensPerWatt);
    if (!l->radiance.is_finite() || l->radiance.r < 0 || l->radiance.g < 0 || l->radiance.b < 0)
      fail("light " + std::to_string(index) + ": colour and intensity must be finite and non-negative");
    l->position = world.apply_point(Vec3f());
    const Vec3f dir = world.apply_vector(Vec3f(0, 0, -1));  // lights shine down their node's -z
    if (g.type == "directional" || g.type == "spot") {
      if (!(length(dir) > 0)) fail("light " + std::to_string(index) + ": degenerate direction");
      l->direction = normalize(dir);
    }
    if (g.type == "point") l->kind = LightKind::Point;
    else if (g.type == "directional") l->kind = LightKind::Distant;
    else if (g.type == "spot") {
      l->kind = LightKind::Spot;
      const double outer = g.spot.outerConeAngle, inner = std::min(g.spot.innerConeAngle, outer);
      if (!(outer > 0 && outer <= kPi / 2)) fail("light " + std::to_string(index) + ": outerConeAngle must be in (0, pi/2]");
      l->cos_total = float(std::cos(outer));
      l->cos_falloff_start = float(std::cos(std::max(inner, 0.0)));
    } else {
      fail("light " + std::to_string(index) + ": unknown type " + quote_text(g.type));
    }
    lights.push_back(l);
    group->add_light(*l);
  }

  void load() {
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(keep_image_bytes, nullptr);
    std::string err, warning;
    const bool binary = path.size() >= 4 && (path.ends_with(".glb") || path.ends_with(".GLB"));
    const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warning, path)
                           : loader.LoadASCIIFromFile(&model, &err, &warning, path);
    if (!ok) {
      std::string first = err.substr(0, err.find('\n'));
      if (first.empty()) first = "cannot be read as glTF";
      fail(first);
    }
    read_materials();
    read_meshes();
    const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (size_t(scene) < model.scenes.size())
      for (int n : model.scenes[size_t(scene)].nodes) node(n, Transform(), 0);
    else if (!model.scenes.empty()) fail("no scene " + std::to_string(scene));
  }
};

int l_gltf_load(lua_State* L) {
  if (lua_type(L, 1) != LUA_TSTRING) throw Error(std::string(kFn) + " expects a file name, got " + type_name(L, 1));
  Importer im{L, resolve_script_path(L, lua_tostring(L, 1)), "", {}, {}, {}, {}, {}, {}, std::make_shared<SceneBuilder>(), {}, {}, {}};
  im.dir = std::filesystem::path(im.path).parent_path().string();
  check_read(L, im.path, kFn);
  im.load();
  lua_createtable(L, 0, 5);
  push_object(L, im.group);
  lua_setfield(L, -2, "group");
  lua_createtable(L, int(im.emitters.size()), 0);
  for (size_t i = 0; i < im.emitters.size(); ++i) {
    push_object(L, std::make_shared<ShapeDesc>(im.emitters[i]));
    lua_rawseti(L, -2, lua_Integer(i + 1));
  }
  lua_setfield(L, -2, "emitters");
  lua_createtable(L, int(im.cameras.size()), 0);
  for (size_t i = 0; i < im.cameras.size(); ++i) {
    push_object(L, im.cameras[i]);
    lua_rawseti(L, -2, lua_Integer(i + 1));
  }
  lua_setfield(L, -2, "cameras");
  lua_createtable(L, int(im.lights.size()), 0);
  for (size_t i = 0; i < im.lights.size(); ++i) {
    push_object(L, im.lights[i]);
    lua_rawseti(L, -2, lua_Integer(i + 1));
  }
  lua_setfield(L, -2, "lights");
  lua_newtable(L);
  for (size_t i = 0; i < im.materials.size(); ++i) {
    push_object(L, im.materials[i]);
    const std::string& name = im.model.materials[i].name;
    lua_setfield(L, -2, (name.empty() ? "material" + std::to_string(i) : name).c_str());
  }
  lua_setfield(L, -2, "materials");
  return 1;
}

}  // namespace

void open_gltf(lua_State* L, int torte_index) {
  const luaL_Reg fns[] = {{"load", guarded<l_gltf_load>}, {nullptr, nullptr}};
  push_subtable(L, torte_index, "gltf");
  set_functions(L, fns);
  lua_pop(L, 1);
}

}  // namespace torte::lua
