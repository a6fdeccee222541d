#pragma once
/// Wavefront OBJ meshes for paths on a surface: `v` positions, `f` faces (polygons triangulated),
/// `vn` normals when every vertex has one.  Read with tinyobjloader (kept inside the .cpp); each
/// `v` and `f` line's number is remembered so that every error names the line (docs/paths.md).
///
/// Vertices count from 0 in the order of the file's `v` lines (OBJ's own indices count from 1).
/// A polygon is split as a fan from the first corner from which every fan triangle turns the same
/// way as the polygon's Newell normal (its first corner for a convex polygon); a polygon that is
/// star-shaped from none of its corners is an error.  A vertex's normal is the normalised sum of
/// the `vn` its face corners name (Blender's flat "s off" export names each face's normal at its
/// corners, so the sum is the angle-free average of the faces around it); when some vertex has no
/// `vn`, all normals are computed by the mesh builder instead (area-weighted).
/// Errors (location {Source{source_name}, TextLine{N}}, "<source_name>: line N", or the source alone for a mesh with no vertex
/// or face): a `v`/`vn` line with fewer than 3 numbers or a NaN/infinite one, a face with fewer
/// than 3 or more than 255 corners, an index 0 or not a number, a face that names a vertex the file
/// does not have, a face with zero area or a repeated vertex, an edge shared by three faces, and
/// anything tinyobjloader refuses.

#include <string_view>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/paths/triangle_mesh.hpp"

namespace inbetween {

/// An OBJ file read but not yet built: the raw mesh and, for messages, the line of each vertex and
/// of each triangle (the line of the face it was split from).
struct ObjRawMesh {
  RawMesh<double> mesh;             ///< positions, triangles, normals (empty when not all given)
  std::vector<int> vertex_lines;    ///< line of vertex i's `v`, from 1
  std::vector<int> triangle_lines;  ///< line of triangle i's `f`, from 1
};

/// Parses OBJ text (no build; errors as in the file comment except those of the builder).
Expected<ObjRawMesh> parse_obj_raw(std::string_view text, std::string_view source_name);

/// Parses and builds: the builder's errors name the line (of the vertex's `v`, of the face's `f`)
/// through a MeshPlaceNamer.
Expected<TriangleMesh<double>> parse_obj(std::string_view text, std::string_view source_name);

}  // namespace inbetween
