// A species' grain diameters: one value, or a distribution each grain draws its own diameter from.
//   fixed       every grain the same diameter
//   discrete    diameters with fractions, by number or by mass (a sieve analysis), given in the scene or as
//               a table file of `diameter, fraction` rows
//   normal      mean and standard deviation of the diameter, cut off at [min, max]
//   lognormal   the diameter's own mean and standard deviation (ln d is normal with
//               sigma^2 = ln(1 + sd^2/mean^2) and mu = ln(mean) - sigma^2/2), cut off at [min, max]
// Cut-offs default to three standard deviations of the normal variable (d, or ln d). A cut-off
// distribution is drawn by inverting its distribution function between the cut-offs, so a draw never
// retries and the drawn sample follows the truncated law exactly. The moments are those of the
// truncated law, by number: E[d^k].
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace gf {

struct SizeDistribution {
  enum class Kind { Fixed, Discrete, Normal, LogNormal };
  Kind kind = Kind::Fixed;
  double value = 0;                  // m: the diameter of a fixed size
  std::vector<double> diameters;     // m, ascending: a discrete distribution's sizes
  std::vector<double> cumulative;    // its number fractions summed, the last exactly 1
  double mean = 0, sd = 0;           // m: of the diameter (normal and lognormal)
  double min = 0, max = 0;           // m: the cut-offs (the smallest and largest size for every kind)

  static SizeDistribution fixed(double d);
  // `fractions` by number, or by mass (then divided by d^3: one density within a species); any positive
  // scale (percent is fine). std::invalid_argument for sizes that are not positive or fractions that sum to 0.
  static SizeDistribution discrete(std::vector<double> diameters, std::vector<double> fractions, bool by_mass);
  // std::invalid_argument when the cut-offs hold less than 1e-9 of the law, or min >= max.
  static SizeDistribution normal(double mean, double sd, double min, double max);
  static SizeDistribution lognormal(double mean, double sd, double min, double max);
  // The default cut-offs: three standard deviations of the normal variable (d for normal, ln d for lognormal).
  static double default_min(Kind kind, double mean, double sd);
  static double default_max(Kind kind, double mean, double sd);

  bool is_fixed() const { return kind == Kind::Fixed; }
  double smallest() const { return min; }
  double largest() const { return max; }
  // E[d^k] by number, of the law as cut off.
  double moment(int k) const;
  // The number-mean diameter, E[d].
  double mean_diameter() const { return moment(1); }
  // One diameter (m); a fixed size draws nothing from `rng`.
  double draw(std::mt19937_64& rng) const;
  // "normal, mean 2 mm, sd 0.2 mm, 1.4 to 2.6 mm" (lengths through `length`), for messages and legends.
  std::string describe(std::string (*length)(double)) const;

  // Derived by normal() and lognormal(): the normal variable's parameters and its cut-offs' probabilities.
  double mu = 0, sigma = 0, p_lo = 0, p_hi = 1;
  double to_diameter(double y) const;
  void set_normal_law(double mu_y, double sigma_y);
};

// kg: the mass of a sphere of diameter d (m) and density (kg/m^3), as a species' mass has always been computed.
double sphere_mass(double density, double diameter);

// A double in [0, 1) from the top 53 bits of the engine's output: the same on every standard library
// (std::uniform_real_distribution's output is not).
inline double portable_uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

}  // namespace gf
