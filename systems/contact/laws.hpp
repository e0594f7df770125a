// The contact laws a scene can name in `[contact] model`. Adding a law: its header (see
// contact_law.hpp for what it declares, its key table among it), its test, and its name in this list.
#pragma once

#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "systems/contact/hertz_mindlin.hpp"
#include "systems/contact/linear_spring_dashpot.hpp"
#include "systems/contact/representative_volume.hpp"

namespace gf {

template <class... L>
struct LawList {};

using ContactLaws = LawList<LinearSpringDashpot, HertzMindlin, RepresentativeVolume>;

// The registered laws that act in contact only (TouchingLaws) and those that act before touching
// (ReachingLaws, contact_law.hpp). The drivers instantiate the two kinds in separate translation
// units: instantiated beside a reaching law, the others' kernels were inlined differently by GCC (its
// budget of growth is per unit), and they are to compile to the code they had.
template <class A, class B>
struct JoinLaws;
template <class... A, class... B>
struct JoinLaws<LawList<A...>, LawList<B...>> {
  using type = LawList<A..., B...>;
};
template <bool Reaching, class List>
struct FilterLaws {
  using type = LawList<>;
};
template <bool Reaching, class H, class... T>
struct FilterLaws<Reaching, LawList<H, T...>> {
  using rest = typename FilterLaws<Reaching, LawList<T...>>::type;
  using type = std::conditional_t<ReachingLaw<H> == Reaching, typename JoinLaws<LawList<H>, rest>::type, rest>;
};
using TouchingLaws = FilterLaws<false, ContactLaws>::type;
using ReachingLaws = FilterLaws<true, ContactLaws>::type;

// Calls f.template operator()<Law>() for the registered law named `name`; false when none is.
template <class F, class... L>
bool with_law_in(LawList<L...>, std::string_view name, F&& f) {
  return ((L::name == name ? (f.template operator()<L>(), true) : false) || ...);
}
template <class F>
bool with_law(std::string_view name, F&& f) {
  return with_law_in(ContactLaws{}, name, f);
}

template <class... L>
std::vector<std::string> law_names_in(LawList<L...>) {
  return {std::string(L::name)...};
}
inline std::vector<std::string> law_names() { return law_names_in(ContactLaws{}); }

// Every law's key tables ([contact], then [contact.wall] where a law has its own), for the manual.
template <class... L>
std::vector<const FieldTable*> law_field_tables_in(LawList<L...>) {
  std::vector<const FieldTable*> out;
  auto add = [&]<class Law>() {
    out.push_back(Law::fields);
    if constexpr (requires { Law::wall_fields; }) out.push_back(Law::wall_fields);
  };
  (add.template operator()<L>(), ...);
  return out;
}
inline std::vector<const FieldTable*> law_field_tables() { return law_field_tables_in(ContactLaws{}); }

}  // namespace gf
