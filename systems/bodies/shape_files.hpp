// Shapes of composite grains read from files: the convex parts of a Wavefront OBJ or STL file, each
// part a core (the convex hull of its vertices) grown by the dilation radius (body_shapes.hpp).
// Reading is strict and bounded: every error names the file, the line (or STL triangle) and a fix.
#pragma once

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

#include "systems/bodies/body_shapes.hpp"

namespace gf {

// The bytes of a shape file (a part has at most kMaxCoreVertices vertices, so a file that holds a
// valid shape is far smaller).
inline constexpr std::size_t kMaxShapeFileBytes = std::size_t{8} << 20;

// "<file>:<line>: <problem>. Fix: <fix>" (no line where the whole file is at fault; binary STL names
// the triangle instead).
class ShapeFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Convex parts from a Wavefront OBJ file: each `o` or `g` group is one part. A core is the convex
// hull of its vertices, so faces are not needed: when the file has faces (`f`), a group's part is
// the vertices its faces use (exporters often list every vertex first and the groups' faces after);
// when it has none, the `v` lines that follow the group's statement (before it, the unnamed group).
// A group named again continues. `v` takes x y z, optionally w or r g b after them (ignored);
// `vn vt vp s l p usemtl mtllib` and comments are read past; any other statement is an error.
// Strict, each a ShapeFileError naming the file and line: a malformed line, a non-finite number, a
// face index out of range, a line over 64 KiB, more than kMaxCoreVertices distinct vertices or
// 16 kMaxCoreVertices face triangles in a part, more than kMaxShapeParts parts; a part spanning no
// volume (4 vertices not in one plane are needed; 1 to 3 points, or points on a line or in a plane,
// only with radius > 0: a sphere, a capsule, a plate); a part that is not convex: a vertex strictly
// inside its hull, or a face with the part's vertices on both sides of its plane (both within 1e-6
// of the part's size; a flat part's outline is not checked). Duplicate vertices count once.
ShapeSpec read_obj_shape(const std::filesystem::path& file, double radius);
ShapeSpec parse_obj_shape(std::string_view text, const std::string& name, double radius);

// Convex parts from an STL file, ASCII or binary (binary when the size is 84 + 50 n for the n in its
// header, else ASCII, which must start with `solid`; a binary file is one solid). Each connected
// component of a solid's triangles (triangles sharing a corner, corners equal when their coordinates
// are) is one part, so a file may hold several parts, in one solid or in several. Vertices of
// different solids never merge: convex parts that touch at a corner belong in separate solids, since
// in one solid they would form one component, which the convexity check refuses. The same checks as
// for OBJ; ASCII errors name the line, binary ones the triangle (counted from 1).
ShapeSpec read_stl_shape(const std::filesystem::path& file, double radius);
ShapeSpec parse_stl_shape(std::string_view bytes, const std::string& name, double radius);

// By the file's extension, .obj or .stl (either case).
ShapeSpec read_shape_file(const std::filesystem::path& file, double radius);

}  // namespace gf
