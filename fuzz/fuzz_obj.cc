// OBJ/MTL reader (src/geometry/obj.h) on text in memory. An input may carry an MTL file after a line
// "#mtl": it is written to the scratch directory as fuzz.mtl, which the OBJ part can name with "mtllib fuzz.mtl".
// Every input gives either consistent ObjData (the mesh passes validate, per-triangle tables index real
// materials and groups) or a torte::Error naming the file.
#include <filesystem>

#include "core/error.h"
#include "error_checks.h"
#include "fuzz_support.h"
#include "geometry/obj.h"
#include "harness.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  torte::fuzz::init_process();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using torte::fuzz::broken_promise;
  std::string_view text(reinterpret_cast<const char*>(data), size);
  const std::string mtl_path = torte::fuzz::scratch_path("fuzz.mtl");
  constexpr std::string_view kSplit = "\n#mtl\n";
  if (const size_t at = text.find(kSplit); at != std::string_view::npos) {
    torte::fuzz::write_file(mtl_path, text.substr(at + kSplit.size()));
    text = text.substr(0, at);
  } else {
    std::error_code ec;
    std::filesystem::remove(mtl_path, ec);
  }
  const std::string name = "fuzz.obj";
  try {
    const torte::ObjData obj = torte::parse_obj(text, name, torte::fuzz::scratch_dir());
    torte::fuzz::check_mesh(obj.mesh, name);
    const size_t triangles = obj.mesh.triangle_count();
    if (obj.triangle_material.size() != triangles || obj.triangle_group.size() != triangles)
      broken_promise("per-triangle material or group table has the wrong length");
    for (size_t t = 0; t < triangles; ++t) {
      if (obj.triangle_material[t] < -1 || obj.triangle_material[t] >= int64_t(obj.materials.size()))
        broken_promise("triangle " + std::to_string(t) + " names material " + std::to_string(obj.triangle_material[t]));
      if (obj.triangle_group[t] >= obj.groups.size())
        broken_promise("triangle " + std::to_string(t) + " names group " + std::to_string(obj.triangle_group[t]));
    }
  } catch (const torte::Error& e) {
    // MTL errors name the MTL file: below the scratch directory, or an absolute path the OBJ named.
    const std::string_view message = e.what();
    torte::fuzz::check_error_message(message, message.substr(0, 1) == "/" ? std::string_view("/") : name + ":");
  }
  return 0;
}
