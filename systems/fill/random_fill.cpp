#include "systems/fill/random_fill.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <sstream>

#include "systems/fill/size_distribution.hpp"

namespace gf {
namespace {

using Vec = std::array<double, 3>;

double sphere_volume(double r) { return 4.0 / 3.0 * std::numbers::pi * r * r * r; }

// portable_uniform01 (size_distribution.hpp): a seed means the same fill on every standard library.
double uniform(std::mt19937_64& rng, double a, double b) { return a + (b - a) * portable_uniform01(rng); }

// Unbiased integer in [0, n): reject the top 2^64 mod n values so every remainder is equally likely.
std::uint64_t uniform_below(std::mt19937_64& rng, std::uint64_t n) {
  const std::uint64_t threshold = (0 - n) % n;
  for (;;) {
    const std::uint64_t x = rng();
    if (x >= threshold) return x % n;
  }
}

// Draws sphere centres uniformly over the positions where a sphere of a given radius lies inside
// the region: uniformly in the shrunk box or shrunk cylinder, then region.contains_sphere() has
// the last word (it also applies a cylinder's height limit and absorbs rounding at the edges).
class Sampler {
 public:
  explicit Sampler(const Region& region) : region_(region) {
    if (region.kind == Region::Kind::Cylinder) {
      const Vec& a = region.axis;
      // Any unit vector not parallel to the axis seeds the in-disc basis.
      Vec t = std::abs(a[0]) < 0.9 ? Vec{1.0, 0.0, 0.0} : Vec{0.0, 1.0, 0.0};
      const double ta = t[0] * a[0] + t[1] * a[1] + t[2] * a[2];
      for (int i = 0; i < 3; ++i) e1_[i] = t[i] - ta * a[i];
      const double n = std::sqrt(e1_[0] * e1_[0] + e1_[1] * e1_[1] + e1_[2] * e1_[2]);
      for (int i = 0; i < 3; ++i) e1_[i] /= n;
      e2_ = {a[1] * e1_[2] - a[2] * e1_[1], a[2] * e1_[0] - a[0] * e1_[2],
             a[0] * e1_[1] - a[1] * e1_[0]};
    }
  }

  // Up to kTries draws until one lands inside: a height-cut cylinder rejects part of the shrunk
  // cylinder, and those misses should not use up the caller's overlap attempts. Empty when the
  // region holds (almost) no room for the sphere.
  std::optional<Vec> draw(std::mt19937_64& rng, double r) const {
    constexpr int kTries = 64;
    for (int t = 0; t < kTries; ++t) {
      Vec p;
      if (region_.kind == Region::Kind::Box) {
        for (int i = 0; i < 3; ++i) p[i] = uniform(rng, region_.lo[i] + r, region_.hi[i] - r);
      } else {
        const double half = 0.5 * region_.length - r;
        const double rho = region_.radius - r;
        const double s = uniform(rng, -half, half);
        double q1 = 0.0;
        double q2 = 0.0;
        // Square-to-disc rejection keeps the density uniform over the disc (acceptance pi/4).
        do {
          q1 = uniform(rng, -rho, rho);
          q2 = uniform(rng, -rho, rho);
        } while (q1 * q1 + q2 * q2 > rho * rho);
        for (int i = 0; i < 3; ++i) {
          p[i] = region_.center[i] + s * region_.axis[i] + q1 * e1_[i] + q2 * e2_[i];
        }
      }
      if (region_.contains_sphere(p, r)) return p;
    }
    return std::nullopt;
  }

 private:
  const Region& region_;
  Vec e1_{}, e2_{};
};

// Uniform cell grid over the region's bounding box with an intrusive linked list per cell
// (head per cell, next per grain): insertion is O(1) and allocates nothing beyond the arrays
// reserved up front, which a counting sort cannot offer while grains arrive one at a time.
class Grid {
 public:
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

  Grid(const Vec& lo, const Vec& hi, double cell, std::size_t max_cells, std::size_t capacity) {
    // Cell = largest diameter keeps a query to at most 3 cells a side; a sparse fill of a huge
    // region would make that grid enormous, so coarsen it then (queries stay exact either way,
    // because they cover every cell the reach touches).
    const double volume = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
    cell = std::max(cell, std::cbrt(volume / static_cast<double>(max_cells)));
    // A flat slab rounds its thin side up to one cell, which the volume estimate does not see.
    for (;;) {
      double cells = 1.0;
      for (int i = 0; i < 3; ++i) cells *= std::max(1.0, std::ceil((hi[i] - lo[i]) / cell));
      if (cells <= static_cast<double>(max_cells)) break;
      cell *= 1.25;
    }
    inv_cell_ = 1.0 / cell;
    lo_ = lo;
    for (int i = 0; i < 3; ++i) {
      n_[i] = std::max(1L, static_cast<long>(std::ceil((hi[i] - lo[i]) * inv_cell_)));
    }
    head_.assign(static_cast<std::size_t>(n_[0] * n_[1] * n_[2]), kNone);
    grains_.reserve(capacity);
    next_.reserve(capacity);
  }

  void insert(const Vec& p, double r) {
    const auto idx = static_cast<std::uint32_t>(grains_.size());
    grains_.push_back({p[0], p[1], p[2], r});
    const std::size_t c = flat(cell_of(p[0], 0), cell_of(p[1], 1), cell_of(p[2], 2));
    next_.push_back(head_[c]);
    head_[c] = idx;
  }

  // True when a sphere (p, r) overlaps a stored one; `reach` bounds r + any stored radius.
  bool overlaps(const Vec& p, double r, double reach) const {
    long a[3], b[3];
    for (int i = 0; i < 3; ++i) {
      a[i] = cell_of(p[i] - reach, i);
      b[i] = cell_of(p[i] + reach, i);
    }
    for (long z = a[2]; z <= b[2]; ++z) {
      for (long y = a[1]; y <= b[1]; ++y) {
        for (long x = a[0]; x <= b[0]; ++x) {
          for (std::uint32_t j = head_[flat(x, y, z)]; j != kNone; j = next_[j]) {
            const Stored& g = grains_[j];
            const double dx = p[0] - g.x;
            const double dy = p[1] - g.y;
            const double dz = p[2] - g.z;
            const double sum = r + g.r;
            if (dx * dx + dy * dy + dz * dz < sum * sum) return true;
          }
        }
      }
    }
    return false;
  }

 private:
  struct Stored {
    double x, y, z, r;
  };

  // Clamped, so grains just outside the box (existing ones within reach) land in the edge cells,
  // where every query that can touch them also looks.
  long cell_of(double v, int i) const {
    const double c = std::floor((v - lo_[i]) * inv_cell_);
    return static_cast<long>(std::clamp(c, 0.0, static_cast<double>(n_[i] - 1)));
  }
  std::size_t flat(long x, long y, long z) const {
    return static_cast<std::size_t>((z * n_[1] + y) * n_[0] + x);
  }

  double inv_cell_ = 0.0;
  Vec lo_{};
  long n_[3] = {1, 1, 1};
  std::vector<std::uint32_t> head_;
  std::vector<std::uint32_t> next_;
  std::vector<Stored> grains_;
};

std::string describe_progress(const std::vector<FillSpecies>& species, const std::vector<std::size_t>& placed,
                              const std::vector<PlacedGrain>& out, double region_volume) {
  std::ostringstream os;
  double placed_volume = 0.0;
  double requested_volume = 0.0;
  os << "placed";
  for (std::size_t s = 0; s < species.size(); ++s) {
    os << (s == 0 ? " " : ", ") << placed[s] << " of " << species[s].count << " of species " << species[s].type
       << (species[s].radii.empty() ? " (radius " : " (radius up to ") << species[s].radius << " m)";
    if (species[s].radii.empty()) requested_volume += static_cast<double>(species[s].count) * sphere_volume(species[s].radius);
    for (double r : species[s].radii) requested_volume += sphere_volume(r);
  }
  for (const PlacedGrain& p : out) placed_volume += sphere_volume(p.radius);
  os << "; solid fraction reached " << placed_volume / region_volume << " of "
     << requested_volume / region_volume << " requested (sphere volume / region volume "
     << region_volume << " m^3)";
  return os.str();
}

}  // namespace

std::vector<PlacedGrain> place_random(const Region& region, std::vector<FillSpecies> species,
                                      std::uint64_t seed, std::span<const PlacedGrain> existing,
                                      std::size_t max_attempts_per_grain) {
  if (const std::string why = region.problem(); !why.empty()) {
    throw FillError("random fill: bad region: " + why);
  }
  if (max_attempts_per_grain == 0) {
    throw FillError("random fill: max_attempts_per_grain is 0. Fix: allow at least 1 attempt");
  }
  std::size_t total = 0;
  double r_max = 0.0;
  for (const FillSpecies& s : species) {
    if (!(s.radius > 0.0) || !std::isfinite(s.radius)) {
      std::ostringstream os;
      os << "random fill: species " << s.type << " has radius " << s.radius
         << " m. Fix: give a finite radius > 0 in m";
      throw FillError(os.str());
    }
    if (!s.radii.empty() && s.radii.size() != s.count)
      throw FillError("random fill: species " + std::to_string(s.type) + " lists " + std::to_string(s.radii.size()) +
                      " radii for " + std::to_string(s.count) + " grains. Fix: give one radius per grain");
    for (double r : s.radii)
      if (!(r > 0.0) || !std::isfinite(r) || r > s.radius)
        throw FillError("random fill: species " + std::to_string(s.type) + " has a grain of radius " +
                        std::to_string(r) + " m outside (0, " + std::to_string(s.radius) +
                        "]. Fix: give radii > 0, the largest as the species' radius");
    total += s.count;
    if (s.count > 0) r_max = std::max(r_max, s.radius);
  }
  std::vector<PlacedGrain> out;
  if (total == 0) return out;
  if (total + existing.size() >= std::numeric_limits<std::uint32_t>::max()) {
    throw FillError("random fill: more than 2^32 grains requested. Fix: fill in several regions");
  }

  std::mt19937_64 rng(seed);

  // Placement order: grains, largest radius first (stable, so equal radii keep the caller's order before
  // the shuffle, which makes the result independent of sort internals); a species of a size distribution
  // gives each grain its own radius.
  struct Item {
    double r;
    std::uint32_t s;
  };
  std::vector<Item> order;
  order.reserve(total);
  for (std::uint32_t s = 0; s < species.size(); ++s)
    for (std::size_t c = 0; c < species[s].count; ++c)
      order.push_back({species[s].radii.empty() ? species[s].radius : species[s].radii[c], s});
  std::stable_sort(order.begin(), order.end(), [](const Item& a, const Item& b) { return a.r > b.r; });
  for (std::size_t first = 0; first < order.size();) {
    std::size_t e = first;
    while (e < order.size() && order[e].r == order[first].r) ++e;
    // Fisher-Yates over this equal-radius group only.
    for (std::size_t i = e - first; i > 1; --i) {
      const std::size_t j = uniform_below(rng, i);
      std::swap(order[first + i - 1], order[first + j]);
    }
    first = e;
  }

  // Existing grains matter only within reach of the bounding box; they may be larger than any
  // species, so they take part in choosing the cell size and the query reach.
  const Vec lo = region.bbox_lo();
  const Vec hi = region.bbox_hi();
  double r_big = r_max;
  std::vector<std::uint32_t> near;
  for (std::uint32_t k = 0; k < existing.size(); ++k) {
    const PlacedGrain& e = existing[k];
    bool in_reach = true;
    for (int i = 0; i < 3; ++i) {
      in_reach = in_reach && e.x[i] + e.radius > lo[i] - r_max && e.x[i] - e.radius < hi[i] + r_max;
    }
    if (in_reach) {
      near.push_back(k);
      r_big = std::max(r_big, e.radius);
    }
  }
  Grid grid(lo, hi, 2.0 * r_big, std::max<std::size_t>(std::size_t{1} << 16, 8 * total),
            near.size() + total);
  for (std::uint32_t k : near) grid.insert(existing[k].x, existing[k].radius);

  const Sampler sampler(region);
  std::vector<std::size_t> placed(species.size(), 0);
  out.reserve(total);
  for (std::size_t n = 0; n < total; ++n) {
    const FillSpecies& sp = species[order[n].s];
    const double radius = order[n].r;
    const double reach = radius + r_big;
    bool done = false;
    std::size_t outside = 0;
    for (std::size_t attempt = 0; attempt < max_attempts_per_grain && !done; ++attempt) {
      const std::optional<Vec> p = sampler.draw(rng, radius);
      if (!p) {
        ++outside;
        continue;
      }
      if (grid.overlaps(*p, radius, reach)) continue;
      grid.insert(*p, radius);
      out.push_back({*p, sp.type, radius});
      ++placed[order[n].s];
      done = true;
    }
    if (!done) {
      std::ostringstream os;
      os << "random fill: could not place grain " << n + 1 << " of " << total << " (species "
         << sp.type << ", radius " << radius << " m) in " << max_attempts_per_grain
         << " attempts";
      if (outside == max_attempts_per_grain) {
        os << ", because the region has (almost) no room for a sphere of this radius";
      }
      os << "; " << describe_progress(species, placed, out, region.volume());
      if (!near.empty()) os << " (not counting " << near.size() << " existing grains nearby)";
      os << ". Fix: lower the count, enlarge the region, or fill in layers (random placement "
            "of equal spheres jams near solid fraction 0.38; let each layer settle before the "
            "next)";
      throw FillError(os.str());
    }
  }
  return out;
}

std::size_t count_for_volume_fraction(const Region& region, double fraction, double radius) {
  if (!(fraction >= 0.0) || !std::isfinite(fraction)) {
    std::ostringstream os;
    os << "volume fraction " << fraction << " is not a finite number >= 0. Fix: give a solid "
       << "fraction such as 0.3";
    throw FillError(os.str());
  }
  if (!(radius > 0.0) || !std::isfinite(radius)) {
    std::ostringstream os;
    os << "radius " << radius << " m is not a finite number > 0. Fix: give a radius in m";
    throw FillError(os.str());
  }
  return static_cast<std::size_t>(std::llround(fraction * region.volume() / sphere_volume(radius)));
}

}  // namespace gf
