// The tables of entry points of the two image modules, which image_io_loader.cc dlopens on first use:
// - libtorte_io.so (image_io.cc and the *_oiio.cc and *_ocio.cc files, linked with OpenImageIO and OpenColorIO):
//   reading images and textures, and writing the formats of image_io.h other than EXR and PNG. Executables do
//   not link it: OIIO's ~250 shared libraries cost ~0.2 s of dynamic linking per process start and ~120 MB of
//   resident memory once loaded.
// - libtorte_write.so (image_write_*.cc and view_transform_ocio.cc, linked with OpenEXR, libpng and OpenColorIO,
//   a dozen libraries): writing EXR and PNG, which every render does, and the view transforms.
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
  void (*invalidate_image_texture)(const std::string&);
};

// Bumped whenever a table in this file or a signature in it changes.
inline constexpr int kImageModuleAbi = 5;

struct ImageWriteModuleApi {
  int abi;  // kImageModuleAbi of the module's build
  void (*write_image)(const Image&, const std::string&, const WriteOptions&);  // .exr and .png only
  float (*linear_to_srgb)(float);
  float (*srgb_to_linear)(float);
  void (*apply_view_transform)(ViewTransform, float, const Image&, std::vector<float>&);
};

}  // namespace torte

/// Each module's one exported C entry point: its table of functions.
extern "C" const torte::ImageModuleApi* torte_image_module_api();
extern "C" const torte::ImageWriteModuleApi* torte_image_write_module_api();
