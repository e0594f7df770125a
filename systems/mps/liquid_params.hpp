// Physical and numerical parameters of an MPS liquid, shared by every liquid system (a world resource).
#pragma once

#include <array>

#include "systems/mps/collision.hpp"
#include "systems/mps/kernel.hpp"
#include "systems/mps/neighbors.hpp"

namespace gf {

enum class GradientForm { Sum, MinPressure };
enum class PpeSolverKind { ParallelCg, EigenCg };
enum class Preconditioner { Jacobi, IncompleteCholesky, Multigrid };

// The parallel CG's multigrid preconditioner (ppe_multigrid.hpp): nodes grouped by cubes of `aggregate` l0, then
// cubes of twice the side at every coarser level, down to `coarsest` unknowns solved directly.
struct MultigridSettings {
  double aggregate = 2.0;  // l0, side of the finest level's cubes
  int sweeps = 1;          // damped Jacobi sweeps before and after each coarse correction
  double omega = 0.7;      // Jacobi damping
  double correction = 1.5; // the coarse correction's scale (piecewise-constant P undershoots: Braess)
  int cycle = 2;           // visits of the next level per cycle: 1 (V) or 2 (W)
  int coarsest = 128;      // unknowns of the directly solved level, at most
  int reuse = 1;           // solves one hierarchy serves before it is rebuilt
};

struct PpeSettings {
  // The parallel CG is the default: faster end to end than Eigen's CG in every benchmarked tank
  // (bench/mps_step_bench), by using both cores where Eigen's CG runs on one.
  PpeSolverKind kind = PpeSolverKind::ParallelCg;
  Preconditioner preconditioner = Preconditioner::Jacobi;  // Jacobi or multigrid (parallel CG); Jacobi or IC (Eigen)
  MultigridSettings multigrid;
  double tolerance = 1e-8;  // relative residual |b - A p| / |b|
  int max_iterations = 2000;
};

// Prandtl's mixing length in a pipe along x (the liquid's `turbulence = "mixing_length"`, mixing_length.hpp):
// the eddy viscosity nu_t = l_m(y)^2 |S| with Nikuradse's l_m of the wall distance y = R - r.
struct MixingLength {
  bool on = false;
  double cy = 0, cz = 0;  // m, the pipe's axis passes through (., cy, cz)
  double radius = 0;      // m
};

struct LiquidParams {
  MpsConstants k;                         // dim, l0, re, n0, lambda
  double rho = 1000.0;                    // kg/m^3
  double nu = 1e-6;                       // m^2/s, kinematic viscosity
  double eddy_viscosity = 0.0;            // m^2/s, added to nu in the momentum diffusion only (not in drag)
  MixingLength mixing_length;             // a turbulent pipe's eddy viscosity per node, also diffusion only
  std::array<double, 3> gravity{};        // m/s^2
  std::array<double, 3> body_force{};     // m/s^2, extra acceleration (drives periodic flows)
  double gamma = 0.001;                   // Tanaka's weight of the number-density source term
  double beta = 0.97;                     // free surface where n* < beta n0
  bool free_surface = true;               // false: a closed liquid, no node is ever a surface node
  GradientForm gradient = GradientForm::Sum;
  bool clip_negative = true;              // p = max(p, 0) after the solve
  double compressibility = 0.0;           // 1/Pa, alpha of Ikeda's term: lap p - rho alpha / dt^2 p = source
  double skin = 0.0;                      // m, search radius = re + skin
  Periodicity periodic;
  PpeSettings solver;
  CollisionSettings collision;
};

}  // namespace gf
