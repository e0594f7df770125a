#include "systems/setup/species_size.hpp"

#include <stdexcept>

#include "engine/field_table.hpp"
#include "engine/number_table.hpp"
#include "engine/user_text.hpp"
#include "systems/setup/scene_fields.hpp"

namespace gf {

namespace {

// `diameters` and `fractions` of a discrete table, each size checked through the diameter's range.
SizeDistribution read_discrete(const SceneNode& t, bool by_mass) {
  const FieldTable& f = kDiameterFields;
  const std::vector<double> d = t.get_doubles(f.field("diameters").key);
  const std::vector<double> w = t.get_doubles(f.field("fractions").key);
  if (d.empty() || d.size() > 100000)
    t.fail("diameters", "give between 1 and 100,000 diameters", "e.g. diameters = [1e-3, 2e-3], fractions = [0.5, 0.5]");
  if (w.size() != d.size())
    t.fail("fractions", std::to_string(w.size()) + " fractions for " + std::to_string(d.size()) + " diameters",
           "give one fraction per diameter");
  for (double x : d)
    if (!f.field("diameters").range.contains(x))
      t.fail("diameters", "diameter " + number_text(x) + " m is not " + f.field("diameters").range.describe(),
             "give diameters in m (is it in mm? " + number_text(x) + " mm is " + number_text(x * 1e-3) + " m)");
  for (double x : w)
    if (!f.field("fractions").range.contains(x))
      t.fail("fractions", "fraction " + number_text(x) + " is not " + f.field("fractions").range.describe(),
             "give each size's share as a number >= 0");
  try {
    return SizeDistribution::discrete(d, w, by_mass);
  } catch (const std::invalid_argument& e) {
    t.fail("fractions", e.what(), "give at least one size a fraction above 0");
  }
}

// A table file of `diameter, fraction` rows.
SizeDistribution read_size_file(const SceneNode& t, bool by_mass) {
  const std::filesystem::path file = t.doc().resolve(t.get_string(kDiameterFields.field("file").key));
  std::vector<double> d, w;
  try {
    for (const NumberRow& r : read_number_table(file, 2, "size table", "diameter, fraction (m, share)")) {
      if (!range::diameter.contains(r.values[0]))
        fail_number_table(file, r.line, "size table: diameter " + number_text(r.values[0]) + " m is not " + range::diameter.describe(),
                          "give diameters in m (is it in mm? " + number_text(r.values[0]) + " mm is " +
                              number_text(r.values[0] * 1e-3) + " m)");
      if (!(r.values[1] >= 0.0))
        fail_number_table(file, r.line, "size table: fraction " + number_text(r.values[1]) + " is negative",
                          "give each size's share as a number >= 0");
      d.push_back(r.values[0]);
      w.push_back(r.values[1]);
    }
    if (d.empty()) fail_number_table(file, 0, "size table: the file has no rows", "give rows of diameter, fraction");
    return SizeDistribution::discrete(d, w, by_mass);
  } catch (const SceneError& e) {
    fail_at_key(t, "file", e);
  } catch (const std::invalid_argument& e) {
    t.fail("file", shown_path(file.string()) + ": size table: " + e.what(), "give at least one size a fraction above 0");
  }
}

// mean, sd and cut-offs of a normal or lognormal law.
SizeDistribution read_continuous(const SceneNode& t, SizeDistribution::Kind kind) {
  const FieldTable& f = kDiameterFields;
  const double mean = read_number(t, f.field("mean")), sd = read_number(t, f.field("sd"));
  const double lo_default = SizeDistribution::default_min(kind, mean, sd);
  const double hi_default = SizeDistribution::default_max(kind, mean, sd);
  if (!t.has("min") && !(lo_default > 0.0))
    t.fail("sd", "mean − 3 sd = " + number_text(lo_default) + " m is not a diameter, so the law needs its own cut-off",
           "give min (m), the smallest diameter to draw, or a smaller sd (is it in mm?)");
  const double lo = t.has("min") ? read_number(t, f.field("min")) : lo_default;
  const double hi = t.has("max") ? read_number(t, f.field("max")) : hi_default;
  if (!(lo < hi)) t.fail("max", "max " + number_text(hi) + " m is not above min " + number_text(lo) + " m", "give min < max");
  if (!range::diameter.contains(hi))
    t.fail("sd", "mean + 3 sd = " + number_text(hi) + " m is not " + range::diameter.describe(), "give max (m), or a smaller sd");
  try {
    return kind == SizeDistribution::Kind::Normal ? SizeDistribution::normal(mean, sd, lo, hi)
                                                  : SizeDistribution::lognormal(mean, sd, lo, hi);
  } catch (const std::invalid_argument& e) {
    t.fail(t.has("min") ? "min" : "max", e.what(), "move the cut-offs towards the mean");
  }
}

}  // namespace

SizeDistribution read_species_size(const SceneNode& species) {
  const Field& diameter = kSpeciesFields.field("diameter");
  if (!species.holds_table(diameter.key)) return SizeDistribution::fixed(read_number(species, diameter));
  const SceneNode t = species.table(diameter.key);
  const FieldTable& f = kDiameterFields;
  const std::string kind = t.get_choice(f.field("distribution").key, {"discrete", "normal", "lognormal", "file"});
  const bool by_mass = read_choice(t, f.field("by"), {"number", "mass"}) == "mass";
  if (kind != "discrete" && kind != "file" && t.has("by"))
    t.fail("by", "'by' says what a discrete table's fractions count; a " + kind + " law has none",
           "remove 'by', or give distribution = \"discrete\"");
  if (kind == "discrete") return read_discrete(t, by_mass);
  if (kind == "file") return read_size_file(t, by_mass);
  return read_continuous(t, kind == "normal" ? SizeDistribution::Kind::Normal : SizeDistribution::Kind::LogNormal);
}

}  // namespace gf
