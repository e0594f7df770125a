// The FluidNodes table: MPS liquid particles and the wall and dummy particles that bound them, one row each,
// as named structure-of-arrays columns. Kinds follow Koshizuka's boundary treatment (seed 003):
//   fluid  (0): moves, pressure from the PPE;
//   wall   (1): fixed, pressure solved in the PPE ("type 1");
//   dummy  (2): fixed, outside the wall layer, counted in the number density, pressure extrapolated ("type 2").
// 2D scenes use x and y only (z stays 0, w stays 0).
#pragma once

#include <cstdint>
#include <string_view>
#include <tuple>

#include "engine/column.hpp"

namespace gf {

enum NodeKind : std::int32_t { kFluid = 0, kWall = 1, kDummy = 2 };

// Every row is owned (the liquid does not yet run in several domains: no ghost rows).
struct FluidNodes {
  static constexpr std::string_view kName = "fluid_nodes";
  int dim = 2;
  ColumnD x, y, z;     // m
  ColumnD u, v, w;     // m/s
  ColumnD p;           // Pa
  ColumnD n;           // particle number density (dimensionless, kernel sum)
  ColumnD div;         // 1/s, divergence of the predicted velocity (PPE source)
  ColumnD ax, ay, az;  // m/s^2, scratch: viscous + body acceleration, then the pressure-gradient acceleration
  Column<std::int32_t> kind;
  Column<std::uint8_t> surface;  // 1: free-surface node, Dirichlet p = 0

  auto columns() { return std::tie(x, y, z, u, v, w, p, n, div, ax, ay, az, kind, surface); }
  std::size_t size() const { return x.size(); }
  std::size_t owned_rows() const { return size(); }
  std::size_t rows() const { return size(); }
  std::size_t bytes() {
    std::size_t b = 0;
    std::apply([&b](auto&... c) { ((b += c.bytes()), ...); }, columns());
    return b;
  }
  void resize(std::size_t rows) {
    std::apply([rows](auto&... c) { (c.resize(rows), ...); }, columns());
  }
  void push(NodeKind k, double px, double py, double pz) {
    const std::size_t r = size();
    resize(r + 1);
    x[r] = px;
    y[r] = py;
    z[r] = pz;
    kind[r] = k;
  }
  std::size_t count(NodeKind k) const {
    std::size_t c = 0;
    for (std::size_t i = 0; i < size(); ++i) c += kind[i] == k;
    return c;
  }
};

}  // namespace gf
