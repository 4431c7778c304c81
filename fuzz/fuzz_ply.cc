// PLY reader (src/geometry/ply.h) on bytes in memory: every input either gives a mesh that passes
// TriangleMesh::validate or a torte::Error naming the file.
#include "error_checks.h"
#include "geometry/mesh_normals.h"
#include "geometry/ply.h"
#include "harness.h"
#include "core/error.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) { return 0; }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string name = "fuzz.ply";
  try {
    torte::TriangleMesh mesh = torte::parse_ply(std::string_view(reinterpret_cast<const char*>(data), size), name);
    torte::fuzz::check_mesh(mesh, name);
    torte::compute_smooth_normals(mesh);
  } catch (const torte::Error& e) {
    torte::fuzz::check_error_message(e.what(), name + ":");
  }
  return 0;
}
