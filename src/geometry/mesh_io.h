// Loading triangle meshes from files: the reader is picked by the file's extension.
#pragma once
#include <string>

#include "geometry/mesh.h"

namespace torte {

// Reads a .ply or .obj file (extension compared case-insensitively); an OBJ's materials and groups are dropped
// (use read_obj for them). Throws torte::Error naming the file for a missing or unreadable file, an unknown
// extension or bad content.
TriangleMesh load_mesh(const std::string& path);

// The whole file as bytes. Throws torte::Error("<path>: cannot open ...") when it cannot be read. The readers
// parse from memory because one read and pointer walking is several times faster than stream extraction.
std::string read_file_bytes(const std::string& path);

}  // namespace torte
