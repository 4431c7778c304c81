// Loading triangle meshes from files: the reader is picked by the file's extension.
#pragma once
#include <string>

#include "core/file_read.h"  // read_file_bytes, which the readers parse from
#include "geometry/mesh.h"

namespace torte {

// Reads a .ply or .obj file (extension compared case-insensitively); an OBJ's materials and groups are dropped
// (use read_obj for them). Throws torte::Error naming the file for a missing, unreadable, non-regular or
// over-large file (core/file_read.h), an unknown extension or bad content. The readers parse from memory (one
// read and pointer walking is several times faster than stream extraction).
TriangleMesh load_mesh(const std::string& path);

}  // namespace torte
