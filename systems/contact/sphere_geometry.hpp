// Geometry stage for spheres: turns a candidate pair (sphere-sphere, sphere-wall) into the contact
// a law consumes (contact_law.hpp), with the lever arms the driver needs for the tangential
// torques. Lever arms are L = r - delta/2 on each side (centre to contact point). Written once for
// double and xsimd batches; the drivers call it inside their kernels (one pass over memory), so
// this is the seam where other shapes (dilated polyhedra, plates) produce contacts of their own.
#pragma once

#include "systems/contact/contact_law.hpp"
#include "systems/contact/vec3.hpp"

namespace gf {

template <class T>
struct SphereContact {
  ContactGeometry<T> g;
  T li, lj;  // lever arms, m (lj unused for walls)
};

// Spheres i and j: d = x_j - x_i with its length `dist` and reciprocal `inv` (the caller chooses
// how exactly to compute them), radii, v_ij = v_i - v_j and the spins.
template <class T>
[[gnu::always_inline]] inline SphereContact<T> sphere_sphere(const V3<T>& d, const T& dist, const T& inv, const T& ri, const T& rj,
                                      const V3<T>& vij, const V3<T>& wi, const V3<T>& wj) {
  SphereContact<T> c;
  c.g.n = inv * d;
  c.g.delta = ri + rj - dist;
  c.li = ri - T(0.5) * c.g.delta;
  c.lj = rj - T(0.5) * c.g.delta;
  c.g.v = vij + cross(c.li * wi + c.lj * wj, c.g.n);
  c.g.w = wi - wj;
  return c;
}

// Sphere i at p against a wall at distance `gap` along the unit normal n (from the centre towards
// the surface); the wall turns at wall_w about an axis through wall_o.
template <class T>
[[gnu::always_inline]] inline SphereContact<T> sphere_wall(const V3<T>& p, const V3<T>& n, const T& gap, const T& ri, const V3<T>& vi,
                                    const V3<T>& wi, const V3<T>& wall_w, const V3<T>& wall_o) {
  SphereContact<T> c;
  c.g.n = n;
  c.g.delta = ri - gap;
  c.li = ri - T(0.5) * c.g.delta;
  c.lj = T(0.0);
  const V3<T> contact = p + c.li * n;
  const V3<T> wall_v = cross(wall_w, contact - wall_o);
  c.g.v = vi + cross(c.li * wi, n) - wall_v;
  c.g.w = wi - wall_w;
  return c;
}

// The same for a law that acts before touching (contact_law.hpp, ReachingLaw): the contact point is
// the wall's closest point p + gap n, whose velocity the law takes (omega x r of a turning wall),
// since the mid-overlap point of sphere_wall lies in the gap when the sphere is apart; the lever arm
// is the gap.
template <class T>
[[gnu::always_inline]] inline SphereContact<T> sphere_wall_surface(const V3<T>& p, const V3<T>& n, const T& gap,
                                                                   const T& ri, const V3<T>& vi, const V3<T>& wi,
                                                                   const V3<T>& wall_w, const V3<T>& wall_o) {
  SphereContact<T> c;
  c.g.n = n;
  c.g.delta = ri - gap;
  c.li = gap;
  c.lj = T(0.0);
  const V3<T> wall_v = cross(wall_w, p + gap * n - wall_o);
  c.g.v = vi + cross(gap * wi, n) - wall_v;
  c.g.w = wi - wall_w;
  return c;
}

}  // namespace gf
