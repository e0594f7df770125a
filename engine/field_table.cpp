#include "engine/field_table.hpp"

#include <algorithm>
#include <stdexcept>

namespace gf {

namespace {

bool is_number(const Field& f) {
  return f.range.lo != kAnyNumber.lo || f.range.hi != kAnyNumber.hi || f.range.lo_open != kAnyNumber.lo_open ||
         f.range.hi_open != kAnyNumber.hi_open;
}

// One row's cells appended piece by piece (GCC 12 misreads long chains of string + string_view).
void row(const Field& f, std::string_view prefix, std::string& out) {
  out.append("| `").append(prefix).append(f.key).append("` | ");
  out.append(f.unit.empty() ? std::string_view("—") : f.unit).append(" | ");
  const bool adds = f.values.empty() || f.values.starts_with("and ") || f.values.starts_with("(");
  if (is_number(f) && adds) {
    out.append(f.range.describe());
    if (!f.values.empty()) out.append(" ").append(f.values);
  } else if (is_number(f)) {
    out.append(f.values);  // the interval in words, where they say more than the interval
  } else {
    out.append(f.values.empty() ? std::string_view("any number") : f.values);
  }
  out.append(" | ");
  if (!f.default_text.empty()) out.append(f.default_text);
  else if (!std::isnan(f.fallback)) out.append(short_number(f.fallback));
  else out.append("required");
  out.append(" | ").append(f.meaning).append(" |\n");
}

void rows(const FieldTable& t, const std::string& prefix, std::string& out) {
  for (const Field& f : t.fields) {
    if (f.include) {
      std::string deeper = prefix;
      deeper.append(f.key);
      rows(*f.include, deeper, out);
    } else {
      row(f, prefix, out);
    }
  }
}

}  // namespace

const Field& FieldTable::field(std::string_view key) const {
  for (const Field& f : fields)
    if (f.key == key) return f;
  throw std::logic_error("the key table of " + std::string(section) + " has no key '" + std::string(key) + "'");
}

std::string FieldTable::markdown() const {
  std::string out = "| key | unit | range | default | meaning |\n|---|---|---|---|---|\n";
  rows(*this, "", out);
  return out;
}

namespace {

// Units a value is often typed in by mistake, and the factor that turns that unit into the field's.
struct UnitSlip {
  std::string_view unit, typed;
  double factor;
};
constexpr UnitSlip kUnitSlips[] = {
    {"kg/m³", "g/cm³", 1e3}, {"m", "mm", 1e-3}, {"Pa", "GPa", 1e9}, {"Pa", "MPa", 1e6},
};

// "is it in g/cm³? 2.5 g/cm³ is 2500 kg/m³": where the value fits the interval in a unit often typed by
// mistake; empty where none fits.
std::string unit_slip(const Field& f, double v) {
  for (const UnitSlip& u : kUnitSlips)
    if (f.unit == u.unit && f.range.contains(v * u.factor)) {
      std::string s = "is it in ";
      s.append(u.typed).append("? ").append(number_text(v)).append(" ").append(u.typed).append(" is ");
      s.append(number_text(v * u.factor)).append(" ").append(f.unit).append("; otherwise ");
      return s;
    }
  return {};
}

// The number at `f`'s key, or `fallback` where absent (NaN: required), checked against `f`'s interval.
double read_checked(const SceneNode& t, const Field& f, double fallback) {
  const bool given = t.has(f.key);
  const double v = std::isnan(fallback) ? t.get_double(f.key, Range::any()) : t.get_double(f.key, fallback, Range::any());
  if (!given || f.range.contains(v)) return v;  // a default may lie outside (`stop`'s infinity: no end)
  std::string problem = "value ";
  problem.append(number_text(v));
  if (!f.unit.empty()) problem.append(" ").append(f.unit);
  problem.append(" is out of range: it must be ").append(f.range.describe());
  std::string fix = unit_slip(f, v);
  fix.append("set `").append(f.key).append("` to a value that is ").append(f.range.describe());
  t.fail(f.key, problem, fix);
}

}  // namespace

double read_number(const SceneNode& t, const Field& f) { return read_checked(t, f, f.fallback); }

double read_number(const SceneNode& t, const Field& f, const double* inherited) {
  return read_checked(t, f, inherited ? *inherited : f.fallback);
}

std::int64_t read_integer(const SceneNode& t, const Field& f) {
  const auto lo = static_cast<std::int64_t>(f.range.lo), hi = static_cast<std::int64_t>(f.range.hi);
  if (std::isnan(f.fallback)) return t.get_int(f.key, lo, hi);
  return t.get_int(f.key, static_cast<std::int64_t>(f.fallback), lo, hi);
}

bool read_bool(const SceneNode& t, const Field& f) {
  if (f.default_text.empty()) return t.get_bool(f.key);
  if (f.default_text != "true" && f.default_text != "false")
    throw std::logic_error("the key '" + std::string(f.key) + "' reads true or false but defaults to '" +
                           std::string(f.default_text) + "'");
  return t.get_bool(f.key, f.default_text == "true");
}

std::string read_choice(const SceneNode& t, const Field& f, std::vector<std::string> choices) {
  if (f.default_text.empty()) return t.get_choice(f.key, std::move(choices));
  std::string_view d = f.default_text;
  if (d.size() < 4 || d.substr(0, 2) != "`\"" || d.substr(d.size() - 2) != "\"`")
    throw std::logic_error("the key '" + std::string(f.key) + "' reads a choice but defaults to '" + std::string(d) + "'");
  std::string fallback(d.substr(2, d.size() - 4));
  if (std::find(choices.begin(), choices.end(), fallback) == choices.end())
    throw std::logic_error("the key '" + std::string(f.key) + "' defaults to '" + fallback + "', not one of its choices");
  return t.get_choice(f.key, std::move(choices), std::move(fallback));
}

}  // namespace gf
