#include "geometry/mesh_io.h"

#include <cctype>
#include <filesystem>

#include "core/error.h"
#include "geometry/obj.h"
#include "geometry/ply.h"

namespace torte {

TriangleMesh load_mesh(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".ply") return read_ply(path);
  if (ext == ".obj") return read_obj(path).mesh;
  if (ext.empty()) throw Error(path + ": the file name has no extension to tell the mesh format (.ply or .obj)");
  throw Error(path + ": unknown mesh file type '" + ext + "' (supported: .ply, .obj)");
}

}  // namespace torte
