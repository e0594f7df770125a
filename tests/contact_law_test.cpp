// Interface checks of every registered contact law (systems/contact/laws.hpp), in the manner of
// waLBerla mesa_pd's: a law compiles against exactly what contact_law.hpp says a law may see (a
// contact's geometry, its type pair's constants, its own history and dt, for double and for
// xsimd batches), declares a history that fits the drivers' records, and keeps its promises:
// no force and zero history where the contact is open, and the declared history layout's width
// is the history the law reads and writes.
#include <catch2/catch.hpp>

#include <array>
#include <concepts>
#include <string>

#include "engine/simd.hpp"
#include "systems/contact/contact_table.hpp"
#include "systems/contact/laws.hpp"
#include "systems/walls/walls.hpp"

namespace {

// What a law must declare; anything else it needs it must get through these.
template <class L>
concept ContactLaw = requires(const gf::ContactBody<typename L::Material>& a, const typename L::Params& p,
                              const gf::SceneNode& node) {
  { L::name } -> std::convertible_to<std::string_view>;
  { L::title } -> std::convertible_to<std::string_view>;
  { L::read_material(node) } -> std::same_as<typename L::Material>;
  { L::read_params(node, &p, true) } -> std::same_as<typename L::Params>;
  { L::constants(a, a, p) } -> std::same_as<std::array<double, L::kConstants>>;
  { L::critical_terms(a, a, p) } -> std::same_as<std::vector<gf::StepTerm>>;
  { L::history() } -> std::same_as<gf::HistoryLayout>;
  requires L::kConstants <= gf::kMaxConstants;
  requires L::kHistory <= gf::kMaxHistory;
  requires L::kHistory <= sizeof(gf::WallSprings::s) / sizeof(double);
} && requires(const gf::ContactGeometry<double>& gd, const std::array<double, L::kConstants>& kd,
              std::array<double, L::kHistory>& hd, const gf::ContactGeometry<gf::BatchD>& gb,
              const std::array<gf::BatchD, L::kConstants>& kb, std::array<gf::BatchD, L::kHistory>& hb) {
  { L::evaluate(true, gd, kd, 1.0, hd) } -> std::same_as<gf::ContactForce<double>>;
  { L::evaluate(gb.delta > gf::BatchD(0.0), gb, kb, gf::BatchD(1.0), hb) } -> std::same_as<gf::ContactForce<gf::BatchD>>;
};

template <class... L>
constexpr bool all_laws(gf::LawList<L...>) {
  return (ContactLaw<L> && ...);
}
static_assert(all_laws(gf::ContactLaws{}), "every registered law declares what contact_law.hpp lists");

// An open contact (negative overlap) with some loaded history and motion, for any law.
template <class L>
void check_open_contact() {
  gf::ContactGeometry<double> g{{0.0, 1.0, 0.0}, -1e-6, {0.1, -0.2, 0.3}, {1.0, 2.0, 3.0}};
  std::array<double, L::kConstants> k;
  k.fill(1.0);
  std::array<double, L::kHistory> h;
  h.fill(1e-6);
  const gf::ContactForce<double> f = L::evaluate(false, g, k, 1e-5, h);
  for (double v : h) CHECK(v == 0.0);
  for (const gf::V3<double>& v : {f.force, f.force_t, f.torque_i, f.torque_j}) {
    CHECK(v.x == 0.0);
    CHECK(v.y == 0.0);
    CHECK(v.z == 0.0);
  }
  CHECK(L::history().fields.size() == L::kHistory);
  CHECK(L::constant_names.size() == L::kConstants);
}

template <class... L>
void check_all_open(gf::LawList<L...>) {
  (check_open_contact<L>(), ...);
}

}  // namespace

TEST_CASE("contact laws: an open contact has no force and no history, and the layout declares the history",
          "[contact][law]") {
  check_all_open(gf::ContactLaws{});
}

TEST_CASE("contact laws: every registered law is named uniquely and found by name", "[contact][law]") {
  const std::vector<std::string> names = gf::law_names();
  REQUIRE(names.size() >= 2);
  for (const std::string& n : names) {
    int found = 0;
    CHECK(gf::with_law(n, [&]<class L>() { found += L::name == n; }));
    CHECK(found == 1);
  }
  CHECK_FALSE(gf::with_law("no_such_law", []<class L>() {}));
}
