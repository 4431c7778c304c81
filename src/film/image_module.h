// The table of entry points of the image-I/O module (libtorte_io.so: image_io.cc and the *_oiio.cc and *_ocio.cc
// files, linked with OpenImageIO and OpenColorIO). Executables do not link either: OIIO's ~250 shared libraries
// cost ~0.2 s of dynamic linking per process start, so image_io_loader.cc dlopens the module on the first image
// read or write.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "film/image.h"
#include "film/image_io.h"
#include "film/view_transform.h"
#include "texture/image_texture.h"

namespace torte {

struct ImageModuleApi {
  int abi;  // kImageModuleAbi of the module's build; the loader refuses a module built from other headers
  void (*write_image)(const Image&, const std::string&, const WriteOptions&);
  Image (*read_image)(const std::string&);
  std::shared_ptr<const ImageSource> (*open_image_texture)(const std::string&, const ImageTextureOptions&);
  float (*linear_to_srgb)(float);
  float (*srgb_to_linear)(float);
  void (*invalidate_image_texture)(const std::string&);
  void (*apply_view_transform)(ViewTransform, float, const Image&, std::vector<float>&);
};

// Bumped whenever ImageModuleApi or a signature in it changes.
inline constexpr int kImageModuleAbi = 3;

}  // namespace torte

/// The module's one exported C entry point: its table of functions.
extern "C" const torte::ImageModuleApi* torte_image_module_api();
