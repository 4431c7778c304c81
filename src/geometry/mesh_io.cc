#include "geometry/mesh_io.h"

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include "core/error.h"
#include "geometry/obj.h"
#include "geometry/ply.h"

namespace torte {

std::string read_file_bytes(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw Error(path + ": cannot open: it is a directory");
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), std::fclose);
  if (!f) throw Error(path + ": cannot open (" + std::strerror(errno) + ")");
  std::string bytes;
  // One read of the size seen at open time, then short reads until the end, in case the file grew.
  if (std::fseek(f.get(), 0, SEEK_END) == 0) {
    const long size = std::ftell(f.get());
    std::rewind(f.get());
    if (size > 0) {
      bytes.resize(size_t(size));
      bytes.resize(std::fread(bytes.data(), 1, bytes.size(), f.get()));
    }
  }
  char chunk[1 << 16];
  for (size_t n; (n = std::fread(chunk, 1, sizeof chunk, f.get())) > 0;) bytes.append(chunk, n);
  if (std::ferror(f.get())) throw Error(path + ": read error (" + std::strerror(errno) + ")");
  return bytes;
}

TriangleMesh load_mesh(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".ply") return read_ply(path);
  if (ext == ".obj") return read_obj(path).mesh;
  if (ext.empty()) throw Error(path + ": the file name has no extension to tell the mesh format (.ply or .obj)");
  throw Error(path + ": unknown mesh file type '" + ext + "' (supported: .ply, .obj)");
}

}  // namespace torte
