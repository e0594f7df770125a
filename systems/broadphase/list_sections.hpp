// The neighbour list, the contact springs and the skin's reference positions as checkpoint sections,
// one function for writing and reading alike (Io: the checkpoint's writer or reader adaptor, with
// vector() and column()). `prefix` keeps each kind of checkpoint's names: "" for a serial run,
// "rank." for one rank's state.
#pragma once

#include <cstddef>
#include <string>

namespace gf {

template <class Io, class List, class History, class State>
void list_sections(Io& io, List& list, History& h, State& bp, const std::string& prefix) {
  io.vector(prefix + "neighbors.offsets", list.offsets);
  io.vector(prefix + "neighbors.i", list.i);
  io.vector(prefix + "neighbors.j", list.j);
  io.column(prefix + "neighbors.i_lane", list.i_lane);
  io.column(prefix + "neighbors.j_lane", list.j_lane);
  io.column(prefix + "neighbors.type_pair", list.type_pair);
  io.vector(prefix + "neighbors.key", list.key);
  // The contact history by its component's and fields' names: a checkpoint of a scene with another
  // law lacks them (the readers name both laws first).
  const std::string c = prefix + "history." + h.component;
  io.column(c + ".pair", h.pair);
  for (std::size_t q = 0; q < h.width; ++q) io.column(c + "." + h.fields[q], h.value[q]);
  io.column(c + ".slot", h.slot);
  io.column(prefix + "broadphase.ref_x", bp.ref_x);
  io.column(prefix + "broadphase.ref_y", bp.ref_y);
  io.column(prefix + "broadphase.ref_z", bp.ref_z);
}

}  // namespace gf
