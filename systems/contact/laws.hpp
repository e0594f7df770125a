// The contact laws a scene can name in `[contact] model`. Adding a law: its header (see
// contact_law.hpp for what it declares), its test, and its name in this list.
#pragma once

#include <string>
#include <string_view>

#include "systems/contact/hertz_mindlin.hpp"
#include "systems/contact/linear_spring_dashpot.hpp"

namespace gf {

template <class... L>
struct LawList {};

using ContactLaws = LawList<LinearSpringDashpot, HertzMindlin>;

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

}  // namespace gf
