// The shapes composite grains are made from, as data (../shared/spec/002): a ShapeSpec is a list of
// convex parts, each a core given by its vertices in the shape frame, and one dilation radius r that
// every part shares; the grain is the union of the cores each grown by a sphere of radius r. Parts
// may overlap (that is how concave grains are made); mass properties count the overlap once.
//
// Builders for named primitives (box, prism, triangular prism, the up-down cone element) and for the
// seed's letters O, T, Z, K, A, C; shapes read from OBJ and STL files are in shape_files.hpp.
//
// A builder's dimensions are the grain's outer ones, as a grain is measured: each part is the named
// solid with every face moved in by r (its core), so the dilated part fills that solid exactly except
// along its convex edges and corners, which are rounded with radius r; r = 0 gives the sharp solid.
// A builder refuses an r at which some core would lose its inside or some face would vanish.
#pragma once

#include <cstddef>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "systems/bodies/mass_properties.hpp"

namespace gf {

// A shape's bound: parts per shape.
inline constexpr std::size_t kMaxShapeParts = 64;

struct ShapeSpec {
  std::vector<std::vector<Eigen::Vector3d>> parts;  // m, shape frame; each core's points
  double radius = 0;                                 // m, >= 0, shared by every part
  std::vector<CoreKind> kinds = {};                  // each part's kind (member_core.hpp); none: all hulls

  CoreKind kind(std::size_t part) const { return part < kinds.size() ? kinds[part] : CoreKind::hull; }
};

// The parts as members for voxel_mass_properties and body_frame_members.
std::vector<DilatedPolyhedron> shape_members(const ShapeSpec& shape);

// The box holding the shape's cores (m, shape frame; grown by the radius, it holds the shape), and the
// largest distance from `centre` to a core (plus the radius, a sphere about `centre` holding the shape).
struct ShapeBox {
  Eigen::Vector3d lo, hi;
};
ShapeBox core_box(const ShapeSpec& shape);
double shape_reach(const ShapeSpec& shape, const Eigen::Vector3d& centre);

// ---- Primitives ----------------------------------------------------------------------------------
// Each throws std::invalid_argument for a dimension that is not positive and finite, a negative or
// non-finite r, or an r too large for the solid (see above).

// A box with edges along x, y, z, centred on the origin.
ShapeSpec box_shape(const Eigen::Vector3d& edges, double radius);

// A right prism: the convex polygon `section` (counter-clockwise in the xy plane, 3 to
// kMaxCoreVertices / 2 corners, none straight) extruded along z over [-length/2, length/2].
ShapeSpec prism_shape(std::span<const Eigen::Vector2d> section, double length, double radius);

// A right prism over an equilateral triangle of edge `side`: centroid on the z axis, one corner on
// +y, extruded along z over [-length/2, length/2].
ShapeSpec triangular_prism_shape(double side, double length, double radius);

// An ellipsoid of semi-axes (a, b, c) along x, y, z, centred on the origin: one member whose core is
// the ellipsoid of semi-axes a - r, b - r, c - r (member_core.hpp), so the grain's extent along each
// axis is the one given (with r = 0 the ellipsoid itself; with r > 0 its offset surface, rounder
// than an ellipsoid where it is most curved). Throws std::invalid_argument for a semi-axis not above r.
ShapeSpec ellipsoid_shape(const Eigen::Vector3d& semi_axes, double radius);

// Spheres of radius `radius` (> 0) centred at `centres` (1 to kMaxShapeParts of them), each a
// member with a point core: one centre is a sphere, several a clump (the multi-sphere
// approximation of a shape), the spheres free to overlap (the mass properties count the union).
ShapeSpec spheres_shape(std::span<const Eigen::Vector3d> centres, double radius);

// The concave "upward-downward cone" element of the seed's hopper case, which names and shows it but
// gives no dimensions (so they are parameters), read as two cones joined at their tips or bases:
// two parts on the z axis, each a regular n-gonal frustum (a pyramid when neck_radius is 0) of axial
// length `height` with `facets` side faces around the axis, its wide end's corners on a circle of
// base_radius and its narrow end's on one of neck_radius, at angles 2 pi k / facets from +x.
// Joined at the narrow ends (the default), an hourglass: the parts meet on the neck's plane z = 0,
// each flaring away from it, so the element is concave (waisted); with r > 0 each part's rim is
// rounded on its own, leaving a groove about r deep round the neck. Joined at the wide ends, a
// double frustum (a double pyramid when pointed): convex, but still two parts. Throws
// std::invalid_argument for facets outside [3, kMaxCoreVertices / 2], a neck not narrower than the
// base, or a pointed neck joined at the narrow ends, where the parts would touch at a single point.
struct UpDownCone {
  enum class Join { narrow_ends, wide_ends };
  double base_radius = 0;  // m
  double neck_radius = 0;  // m, < base_radius; 0: pointed
  double height = 0;       // m, of each part
  int facets = 12;
  Join join = Join::narrow_ends;
};
ShapeSpec up_down_cone_shape(const UpDownCone& cone, double radius);

// ---- Letters -------------------------------------------------------------------------------------
// The seed's packing shapes, flat letters made of boxes: x across the letter, y up it, z through it;
// the letter's outline fills [-width/2, width/2] x [-height/2, height/2] x [-depth/2, depth/2] (with
// r > 0 its convex edges are rounded, so the acute corners of slanted strokes recede a little). Every
// stroke is `stroke` wide (measured across the stroke) and `depth` deep. Upright strokes and bars are
// boxes; slanted strokes are slanted boxes (a box sheared along its length, a parallelepiped) whose
// ends are horizontal, so they end flush with the letter's outline. Strokes overlap where they meet.
// The seed gives L = 100 mm, W = 30 mm, H = 180 mm: read here as width, depth and height, with W also
// the stroke (the defaults below). Layouts (s = stroke, L = width, H = height):
//   O  a ring around a rectangular hole (L - 2s) x (H - 2s): left and right columns s x H, top and
//      bottom bars L x s; the bars overlap the columns in the four s x s corners.
//   T  a bar L x s along the top, a stem s x H down the middle; they overlap in s x s.
//   Z  top and bottom bars L x s; a slanted stroke from the bottom-left corner (its lower end on
//      y = -H/2, flush with x = -L/2) to the top-right one (its upper end on y = H/2, flush with
//      x = L/2), overlapping each bar by its own width times s.
//   K  a stem s x H on the left; two slanted arms from the stem's middle to the top-right and
//      bottom-right corners, their inner ends on y = 0 starting at x = -L/2 (inside the stem), so
//      the arms overlap the stem and meet each other along y = 0.
//   A  two slanted legs from the bottom corners (flush with x = -L/2 and x = L/2 on y = -H/2) to the
//      apex, each leg's top end flush with x = +s/2 (left leg) or -s/2 (right leg) on y = H/2, so the
//      legs overlap at the apex; a crossbar s high centred at y = -H/4 between the legs' centre
//      lines, leaving a triangular hole above it.
//   C  a column s x H on the left, top and bottom bars L x s; open on the right (+x), the mouth
//      (L - s) x (H - 2s); the bars overlap the column in s x s.
// A slanted stroke's horizontal width w solves w dy / sqrt((X - w)^2 + dy^2) = s (its width across
// the stroke is s), X its horizontal extent and dy its rise.
// Throws std::invalid_argument for a letter other than those six, a size that is not positive and
// finite, a stroke with 2 stroke >= width or 3 stroke >= height, a depth or r the cores cannot keep.
struct LetterSize {
  double width = 0.100;   // m, L
  double height = 0.180;  // m, H
  double depth = 0.030;   // m, W
  double stroke = 0.030;  // m
};
ShapeSpec letter_shape(char letter, const LetterSize& size, double radius);

}  // namespace gf
