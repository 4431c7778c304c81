// The image-I/O module's entry point (image_module.h): a table of the real implementations in image_io.cc and
// image_texture_oiio.cc. Executables export their own symbols (-rdynamic) so that the module shares their
// torte_core state (memory limit, stderr redirection); the loader's forwarding functions of the same names are
// kept out of that export (--exclude-libs), so the addresses taken here are the module's own.
#include "film/image_module.h"

#include "texture/image_texture_oiio.h"

extern "C" __attribute__((visibility("default"))) const torte::ImageModuleApi* torte_image_module_api() {
  static const torte::ImageModuleApi api{torte::kImageModuleAbi, &torte::write_image, &torte::read_image,
                                         &torte::open_image_texture, &torte::invalidate_image_texture};
  return &api;
}
