// OBJ reading (include/inbetween/io/obj.hpp).  A light scan of the text finds the line of every
// `v`, `vn` and `f` and checks what tinyobjloader passes over silently (it reads "nan" or a missing
// coordinate as 0, skips faces with fewer than 3 corners, stores corner counts in a byte, and does
// not check face indices against the vertices); tinyobjloader then does the parsing proper, and the
// mesh builder checks the geometry (zero area, repeated vertices, shared edges, normals) and names
// its places through a MeshPlaceNamer that gives the file's lines.
#include "inbetween/io/obj.hpp"
#include "inbetween/math/format.hpp"
#include "inbetween/math/quote.hpp"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <regex>
#include <string>

namespace inbetween {
namespace {

struct LineIndex {
  std::vector<int> vertex_lines;
  std::vector<int> face_lines;
  std::vector<int> face_sizes;
};

// The place "mesh.obj: line 12".
std::vector<LocationStep> at_line(std::string_view source, int line) {
  return {Source{std::string(source)}, TextLine{std::size_t(line)}};
}

// The whitespace-separated tokens of a line after its keyword (tinyobjloader splits on spaces/tabs).
std::vector<std::string> tokens_of(std::string_view line) {
  std::vector<std::string> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    std::size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') ++j;
    if (j > i) out.emplace_back(line.substr(i, j - i));
    i = j;
  }
  return out;
}

Expected<LineIndex> scan_lines(std::string_view text, std::string_view source) {
  LineIndex index;
  int line_no = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    const std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    std::vector<std::string> tok = tokens_of(line);
    if (tok.empty() || tok[0][0] == '#') {
      if (end == text.size()) break;
      continue;
    }
    const std::string& key = tok[0];
    if (key == "v" || key == "vn") {
      if (tok.size() < 4)
        return Error{ErrorCode::wrong_arity,
                     "'" + key + "' needs 3 coordinates, got " + std::to_string(tok.size() - 1), at_line(source, line_no)};
      for (std::size_t k = 1; k < 4; ++k) {
        char* stop = nullptr;
        errno = 0;
        const double x = std::strtod(tok[k].c_str(), &stop);
        if (stop == tok[k].c_str() || *stop != '\0')
          return Error{ErrorCode::parse, "'" + key + "' coordinate " + quote_excerpt(tok[k], 40) + " is not a number",
                       at_line(source, line_no)};
        if (!std::isfinite(x))
          return Error{ErrorCode::not_finite, "'" + key + "' coordinate " + quote_excerpt(tok[k], 40) + " is not finite",
                       at_line(source, line_no)};
      }
      if (key == "v") index.vertex_lines.push_back(line_no);
    } else if (key == "f") {
      const std::size_t corners = tok.size() - 1;
      if (corners < 3 || corners > 255)
        return Error{ErrorCode::wrong_arity,
                     "a face needs 3 to 255 corners, got " + std::to_string(corners), at_line(source, line_no)};
      for (std::size_t k = 1; k < tok.size(); ++k) {
        // Each corner is v, v/vt, v//vn or v/vt/vn; every index present must be a non-zero integer.
        std::size_t start = 0;
        for (int part = 0; start <= tok[k].size(); ++part) {
          const std::size_t slash = std::min(tok[k].find('/', start), tok[k].size());
          const std::string num = tok[k].substr(start, slash - start);
          const bool optional = part == 1;  // v//vn leaves the texture index empty
          if (!(num.empty() && optional)) {
            char* stop = nullptr;
            const long idx = std::strtol(num.c_str(), &stop, 10);
            if (num.empty() || *stop != '\0' || part > 2)
              return Error{ErrorCode::parse, "face corner " + quote_excerpt(tok[k], 40) + " is not of the form v, v/vt, v//vn or v/vt/vn",
                           at_line(source, line_no)};
            if (idx == 0)
              return Error{ErrorCode::invalid_argument,
                           "face corner '" + tok[k] + "' has index 0 (OBJ indices count from 1)", at_line(source, line_no)};
          }
          start = slash + 1;
        }
      }
      index.face_lines.push_back(line_no);
      index.face_sizes.push_back(int(corners));
    }
    if (end == text.size()) break;
  }
  return index;
}

// tinyobjloader puts "line N" in some of its messages; make it the place.
Error from_tinyobj(const std::string& message, std::string_view source) {
  static const std::regex line_re(R"(line (\d+))");
  std::smatch m;
  std::string text = one_line_excerpt(message);
  while (!text.empty() && text.back() == '.') text.pop_back();
  if (std::regex_search(text, m, line_re)) return Error{ErrorCode::parse, text, at_line(source, std::stoi(m[1].str()))};
  return Error{ErrorCode::parse, text, {Source{std::string(source)}}};
}

using V = Vec3d;

// Fan triangulation from the first corner whose fan turns with the Newell normal.
bool triangulate(const std::vector<int>& poly, const std::vector<V>& pos, std::vector<std::array<int, 3>>& out) {
  const std::size_t n = poly.size();
  if (n == 3) {
    out.push_back({poly[0], poly[1], poly[2]});
    return true;
  }
  V newell{};
  for (std::size_t i = 0; i < n; ++i) {
    const V& a = pos[std::size_t(poly[i])];
    const V& b = pos[std::size_t(poly[(i + 1) % n])];
    newell += V{(a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y)};
  }
  for (std::size_t s = 0; s < n; ++s) {
    bool ok = true;
    for (std::size_t i = 1; i + 1 < n && ok; ++i) {
      const V& a = pos[std::size_t(poly[s])];
      const V& b = pos[std::size_t(poly[(s + i) % n])];
      const V& c = pos[std::size_t(poly[(s + i + 1) % n])];
      ok = dot(cross(V(b - a), V(c - a)), newell) > 0;
    }
    if (!ok) continue;
    for (std::size_t i = 1; i + 1 < n; ++i) out.push_back({poly[s], poly[(s + i) % n], poly[(s + i + 1) % n]});
    return true;
  }
  return false;
}

}  // namespace

Expected<ObjRawMesh> parse_obj_raw(std::string_view text, std::string_view source_name) {
  auto index = scan_lines(text, source_name);
  if (!index) return index.error();
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;  // polygons are split here, where their line is known
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(std::string(text), std::string(), config)) return from_tinyobj(reader.Error(), source_name);
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  ObjRawMesh out;
  const std::size_t nv = attrib.vertices.size() / 3;
  if (nv != index->vertex_lines.size())
    return Error{ErrorCode::parse,
                 "read " + std::to_string(nv) + " vertices but the file has " + std::to_string(index->vertex_lines.size()) +
                     " 'v' lines", {Source{std::string(source_name)}}};
  out.vertex_lines = index->vertex_lines;
  out.mesh.vertices.resize(nv);
  for (std::size_t i = 0; i < nv; ++i)
    out.mesh.vertices[i] = {attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]};
  std::vector<V> normal_sum(nv, V{});
  std::vector<char> has_normal(nv, 0);
  std::size_t face = 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    std::size_t corner = 0;
    for (unsigned char count : shape.mesh.num_face_vertices) {
      if (face >= index->face_lines.size() || int(count) != index->face_sizes[face])
        return Error{ErrorCode::parse, "the faces read do not match the file's 'f' lines", {Source{std::string(source_name)}}};
      const int line = index->face_lines[face];
      std::vector<int> poly;
      for (std::size_t k = 0; k < count; ++k, ++corner) {
        const tinyobj::index_t& ix = shape.mesh.indices[corner];
        // OBJ's indices (from 1, or negative: relative to the last vertex so far) are the reader's to
        // translate, so the reader says what is wrong with them in the file's own terms.
        if (ix.vertex_index < 0)
          return Error{ErrorCode::invalid_argument, "face names a relative vertex index before the file's first vertex",
                       at_line(source_name, line)};
        if (std::size_t(ix.vertex_index) >= nv)
          return Error{ErrorCode::invalid_argument,
                       "face names vertex " + std::to_string(ix.vertex_index + 1) + " (counting from 1), but the file has " +
                           std::to_string(nv) + " vertices",
                       at_line(source_name, line)};
        if (ix.normal_index >= 0) {
          if (std::size_t(ix.normal_index) * 3 + 2 >= attrib.normals.size())
            return Error{ErrorCode::invalid_argument,
                         "face names normal " + std::to_string(ix.normal_index + 1) + " (counting from 1), but the file has " +
                             std::to_string(attrib.normals.size() / 3) + " normals",
                         at_line(source_name, line)};
          const std::size_t vn = std::size_t(ix.normal_index) * 3;
          normal_sum[std::size_t(ix.vertex_index)] += V{attrib.normals[vn], attrib.normals[vn + 1], attrib.normals[vn + 2]};
          has_normal[std::size_t(ix.vertex_index)] = 1;
        }
        poly.push_back(ix.vertex_index);
      }
      if (!triangulate(poly, out.mesh.vertices, out.mesh.triangles))
        return Error{ErrorCode::invalid_argument,
                     "the polygon cannot be split into triangles from any of its corners (it is not star-shaped, or "
                     "its corners are collinear)",
                     at_line(source_name, line)};
      out.triangle_lines.resize(out.mesh.triangles.size(), line);
      ++face;
    }
  }
  if (face != index->face_lines.size())
    return Error{ErrorCode::parse, "the faces read do not match the file's 'f' lines", {Source{std::string(source_name)}}};
  if (nv > 0 && std::all_of(has_normal.begin(), has_normal.end(), [](char c) { return c != 0; }))
    out.mesh.normals = std::move(normal_sum);
  return out;
}

Expected<TriangleMesh<double>> parse_obj(std::string_view text, std::string_view source_name) {
  auto raw = parse_obj_raw(text, source_name);
  if (!raw) return raw.error();
  // The builder names its places through this: a vertex or a normal by its `v` line, a triangle by
  // the line of the face it was split from, a whole member by the file.
  const MeshPlaceNamer place = [&](std::string_view member, std::size_t index) {
    const std::vector<LocationStep> file{Source{std::string(source_name)}};
    if (index == kWholeMeshMember) return file;
    const std::vector<int>& lines = member == "triangles" ? raw->triangle_lines : raw->vertex_lines;
    return index < lines.size() ? at_line(source_name, lines[index]) : file;
  };
  return build_triangle_mesh(raw->mesh, place);
}

}  // namespace inbetween
