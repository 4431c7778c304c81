// The writing module's entry point (image_module.h): EXR and PNG, which every render writes, without OpenImageIO.
// As in image_module_oiio.cc, the addresses taken here are the module's own functions.
#include "film/image_module.h"
#include "film/image_write_common.h"
#include "film/image_write_exr.h"
#include "film/image_write_png.h"

namespace {

void write_exr_or_png(const torte::Image& image, const std::string& path, const torte::WriteOptions& options) {
  const std::string ext = torte::lower_extension(path);
  if (ext == ".exr") return torte::write_exr(image, path);
  if (ext == ".png") return torte::write_png(image, path, options);
  torte::write_error(path, "internal: the writing module takes .exr and .png only");
}

}  // namespace

extern "C" __attribute__((visibility("default"))) const torte::ImageWriteModuleApi* torte_image_write_module_api() {
  static const torte::ImageWriteModuleApi api{torte::kImageModuleAbi, &write_exr_or_png, &torte::linear_to_srgb,
                                              &torte::srgb_to_linear, &torte::apply_view_transform};
  return &api;
}
