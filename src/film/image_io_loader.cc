// The executables' side of image I/O (image_module.h): each function of image_io.h and image_texture_oiio.h
// loads its module on first use and forwards to it: EXR and PNG output and the view transforms to the small
// writing module, everything else to the OpenImageIO module, so a run that reads no image never pays for
// OpenImageIO's shared libraries. Errors of the readers and writers pass through unchanged.
#include <dlfcn.h>
#include <unistd.h>

#include <climits>
#include <mutex>
#include <string>
#include <thread>

#include "core/error.h"
#include "core/text.h"
#include "film/image_module.h"
#include "texture/image_texture_oiio.h"

namespace torte {

namespace {

// Next to the executable first (build/torte, an installed copy), then where the build put it (tests and tools
// live in subdirectories of the build).
std::string next_to_executable(const char* name) {
  char buf[PATH_MAX];
  const ssize_t n = ::readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return {};
  std::string dir(buf, size_t(n));
  dir.resize(dir.rfind('/') + 1);
  return dir + name;
}

// The table that the module's entry point `entry_name` returns, checked against this executable's headers.
template <class Api>
const Api* load_module(const char* name, const char* build_path, const char* entry_name) {
  std::string tried;
  void* handle = nullptr;
  for (const std::string& path : {next_to_executable(name), std::string(build_path)}) {
    if (path.empty() || ::access(path.c_str(), R_OK) != 0) continue;
    // RTLD_LAZY: binding all of OpenImageIO's dependencies' functions up front doubled the load time; the modules
    // are linked with --no-undefined, so nothing of torte's can be missing.
    handle = ::dlopen(path.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (handle) break;
    tried = path + ": " + ::dlerror();
  }
  if (!handle) throw Error("cannot load the image module " + (tried.empty() ? std::string(build_path) : tried));
  using Entry = const Api* (*)();
  const auto entry = reinterpret_cast<Entry>(::dlsym(handle, entry_name));
  const Api* api = entry ? entry() : nullptr;
  if (!api || api->abi != kImageModuleAbi)
    throw Error("the image module " + std::string(build_path) + " does not match this executable (rebuild it)");
  // If the executable exported these forwarding functions, the module would have bound to them: endless recursion.
  if (api->write_image == &write_image) throw Error("the image module resolved to the executable's loader");
  return api;
}

// A throw leaves a once_flag unset: the next call retries.
const ImageModuleApi& module() {
  static std::once_flag once;
  static const ImageModuleApi* api = nullptr;
  std::call_once(once, [] {
    api = load_module<ImageModuleApi>(TORTE_IMAGE_MODULE_NAME, TORTE_IMAGE_MODULE_PATH, "torte_image_module_api");
  });
  return *api;
}

const ImageWriteModuleApi& write_module() {
  static std::once_flag once;
  static const ImageWriteModuleApi* api = nullptr;
  std::call_once(once, [] {
    api = load_module<ImageWriteModuleApi>(TORTE_WRITE_MODULE_NAME, TORTE_WRITE_MODULE_PATH,
                                           "torte_image_write_module_api");
  });
  return *api;
}

bool written_by_write_module(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".exr" || ext == ".png";
}

}  // namespace

void preload_image_io() {
  // Joined when the process exits (a static's destructor), so the loader thread never outlives main: the leak
  // checker and the dynamic linker's own exit then see no load in flight. A failure is left for the use that needs
  // the module (call_once then tries again and throws there).
  struct Loader {
    std::thread thread;
    ~Loader() {
      if (thread.joinable()) thread.join();
    }
  };
  static Loader loader;
  static std::once_flag started;
  std::call_once(started, [] {
    loader.thread = std::thread([] {
      try {
        write_module();  // what saving a render needs; the OpenImageIO module only if something reads an image
      } catch (...) {
      }
    });
  });
}

void write_image(const Image& image, const std::string& path, const WriteOptions& options) {
  if (written_by_write_module(path)) return write_module().write_image(image, path, options);
  module().write_image(image, path, options);
}

Image read_image(const std::string& path) { return module().read_image(path); }

std::shared_ptr<const ImageSource> open_image_texture(const std::string& path, const ImageTextureOptions& options) {
  return module().open_image_texture(path, options);
}

void invalidate_image_texture(const std::string& path) { module().invalidate_image_texture(path); }

void apply_view_transform(ViewTransform view, float exposure, const Image& image, std::vector<float>& out) {
  write_module().apply_view_transform(view, exposure, image, out);
}

float linear_to_srgb(float v) { return write_module().linear_to_srgb(v); }
float srgb_to_linear(float v) { return write_module().srgb_to_linear(v); }

}  // namespace torte
