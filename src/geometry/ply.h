// Stanford PLY reader: ascii, binary_little_endian and binary_big_endian.
//
// Vertex properties x y z (any scalar type, any order), optional nx ny nz and uvs (u v, s t, texture_u texture_v
// or texture_s texture_t); faces from the list property vertex_indices (or vertex_index), polygons fan-
// triangulated from their first vertex. Other elements and properties, including list properties on vertices,
// are skipped. Normals are renormalized (zero ones stay zero: the renderer then uses the geometric normal).
#pragma once
#include <functional>
#include <string>
#include <string_view>

#include "geometry/mesh.h"

namespace torte {

// Throws torte::Error("<path>: ...") naming what is wrong, e.g. "mesh.ply: vertex 1234 of 50002: file ends early".
TriangleMesh read_ply(const std::string& path);
/// Told, now and then while parsing, that the bytes before a point of the data will not be read again.
using PlyRelease = std::function<void(const char*)>;
// The same for bytes already in memory; `name` starts every error message. read_ply passes `release` to hand the
// file's pages back as the mesh grows (core/file_read.h: FileBytes).
TriangleMesh parse_ply(std::string_view data, const std::string& name, const PlyRelease& release = {});
/// Writes `mesh` (placed meshes as placed, in world space) as binary little-endian PLY: float x y z, nx ny nz
/// and u v when it has them, faces as uchar-counted uint lists. read_ply gives the same values back. Streams
/// the body in blocks, so nothing of the mesh's size is allocated. Throws torte::Error("<path>: <reason>") when
/// the file cannot be written.
void write_ply(const TriangleMesh& mesh, const std::string& path);

}  // namespace torte
