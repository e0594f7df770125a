// A section's keys as a table: each key with its unit, the values it accepts, its default and its
// meaning. The section's reader reads its numbers through the table (the range checked and the
// default taken are the table's), and the manual's key reference is generated from the same tables
// (tests/scene_fields_test.cpp fails when a page's table differs), so the reader and the reference
// cannot drift apart.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/scene.hpp"

namespace gf {

struct FieldTable;

inline constexpr Range kAnyNumber{-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                                  true, true};
inline constexpr Range kPositiveNumber{0, std::numeric_limits<double>::infinity(), true, true};      // > 0
inline constexpr Range kNonNegativeNumber{0, std::numeric_limits<double>::infinity(), false, true};  // >= 0
inline constexpr Range kFraction{0, 1, false, false};                                                 // [0, 1]
inline constexpr double kNoDefault = std::numeric_limits<double>::quiet_NaN();

// Physical intervals. Every number a scene gives has a lower and an upper bound: far outside any granular or
// liquid flow, but tight enough that a denormal (1e-320), a stand-in for infinity (1e300) or a unit slip is
// refused at the line where it is typed, not reported later as an instability.
namespace range {
inline constexpr Range length{1e-9, 1e4, false, false};           // m: a nanometre to 10 km
inline constexpr Range length_or_zero{0, 1e4, false, false};      // m
inline constexpr Range diameter{1e-8, 100, false, false};         // m: 10 nm to a 100 m coarse-grained parcel
inline constexpr Range density{10, 1e6, false, false};            // kg/m³: lighter than expanded foam is a slip
inline constexpr Range modulus{1e3, 1e13, false, false};          // Pa: a soft gel to past diamond (1.2e12)
inline constexpr Range stiffness{1e-9, 1e15, false, false};       // N/m
inline constexpr Range stiffness_or_zero{0, 1e15, false, false};  // N/m
inline constexpr Range torsion_or_zero{0, 1e12, false, false};    // N m/rad
inline constexpr Range coefficient{0, 100, false, false};         // friction and other factors
inline constexpr Range positive_factor{1e-6, 1e6, false, false};  // a dimensionless scale that must not vanish
inline constexpr Range speed{1e-9, 1e5, false, false};            // m/s
inline constexpr Range speed_or_zero{0, 1e5, false, false};       // m/s
inline constexpr Range time_step{1e-15, 1e3, false, false};       // s: a femtosecond to a quarter hour
inline constexpr Range time_span{0, 1e12, false, false};          // s: durations and start times
inline constexpr Range angle_span{0, 1e12, false, false};         // rad
inline constexpr Range kinematic_viscosity{0, 1e3, false, false}; // m²/s: water is 1e-6
inline constexpr Range compressibility{0, 1, false, false};       // 1/Pa
}  // namespace range

struct Field {
  std::string_view key;
  std::string_view unit;               // empty: none ("—" in the reference)
  Range range = kAnyNumber;            // a number's accepted interval, as the reader checks it
  std::string_view values;             // the accepted values in words where they are not a number's interval
                                       // ("`box`, `cylinder`", "three numbers"); starting with "and" or "(",
                                       // a further condition after the interval ("and ≥ `run.dt`"); for a
                                       // number, other words replace the interval's ("0, or ≥ `run.dt`")
  double fallback = kNoDefault;        // a number's default; NaN: none, or the words of `default_text`
  std::string_view default_text;       // the default in words; empty with no fallback: "required"
  std::string_view meaning;
  const FieldTable* include = nullptr;  // a sub-table whose keys follow `key` as a prefix ("region.")
};

struct FieldTable {
  std::string_view section;  // as the manual's heading names it: "[[feed]]"
  std::string_view page;     // the manual page that holds its reference: "mixers.md"
  std::span<const Field> fields;

  // The field named `key`; std::logic_error for a key the table lacks (a reader's mistake).
  const Field& field(std::string_view key) const;
  // The reference: the header, the rule and a row per key, sub-tables expanded in place.
  std::string markdown() const;
};

// A number through its field: required, or with the field's default when the field has one. A value
// outside the field's interval that would fit it in a neighbouring unit (2.5 kg/m³: g/cm³; 70 Pa: GPa) is
// refused with that unit named.
double read_number(const SceneNode& t, const Field& f);
// A number through its field that falls back on `inherited` where one is given (an override table's
// key defaults to the value it overrides) and otherwise on the field's default.
double read_number(const SceneNode& t, const Field& f, const double* inherited);
// An integer through its field, its range's bounds inclusive.
std::int64_t read_integer(const SceneNode& t, const Field& f);
// true or false through its field: required, or the field's `default_text` ("true" or "false").
bool read_bool(const SceneNode& t, const Field& f);
// One of `choices` through its field: required, or the field's `default_text` (a choice written
// `"name"` in backticks, as the reference shows it).
std::string read_choice(const SceneNode& t, const Field& f, std::vector<std::string> choices);

}  // namespace gf
