#include "geometry/mesh_io.h"

#include "core/error.h"
#include "core/text.h"
#include "geometry/obj.h"
#include "geometry/ply.h"

namespace torte {

TriangleMesh load_mesh(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".ply") return read_ply(path);
  if (ext == ".obj") return read_obj(path).mesh;
  if (ext.empty()) throw Error(path + ": the file name has no extension to tell the mesh format (.ply or .obj)");
  throw Error(path + ": unknown mesh file type '" + ext + "' (supported: .ply, .obj)");
}

}  // namespace torte
