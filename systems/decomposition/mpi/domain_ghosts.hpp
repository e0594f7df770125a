// Ghost rows of a domain decomposition: copies of other ranks' owned rows near this rank's box.
//
// At a neighbour rebuild (after migration) each rank sends every other rank the owned rows whose
// centre lies within `reach` (largest diameter + skin: the farthest a listed pair's partner can be)
// of that rank's box; they become ghost rows after the owned ones (n_owned, then the ghosts by
// sending rank, in the sender's row order), all core columns copied. As for periodic images, the
// neighbour list pairs owned rows with ghost rows, and between rebuilds `refresh_domain_ghosts`
// copies the owners' position, velocity and spin into the ghosts before the contacts.
//
// Two shells: with GhostShell::full a rank holds every neighbour's rows within reach, so each
// pair across ranks is evaluated on both sides and each rank keeps its own side (ghost forces are
// discarded). With GhostShell::half a rank holds only the rows of lower-numbered ranks, so each pair
// across ranks is evaluated once, on the higher rank, and `fold_domain_ghost_forces` sends the
// partner side left on the ghosts back to their owners, which add it (as PeriodicFold does for
// images), in sending-rank then row order.
//
// The messages go to the neighbouring boxes only: the ranks whose boxes lie within `reach` of this
// rank's box (box_peers), point to point, so a rank's exchange costs what its neighbours hold, not
// what the rank count is.
//
// Periodic faces (make_domain_ghosts with a PeriodicBox): a row is also sent, shifted by whole box
// lengths, to the ranks whose boxes lie within reach of it across the faces, and its ghost there
// stands at its position plus that shift (refresh adds it each step). A rank holds its own rows'
// copies across the faces too, for the shifts whose first nonzero component is positive only, as
// periodic images are made (periodic_images.hpp): a pair across a face between two rows of one rank
// is then listed once, and one between two ranks on the higher, as any pair across a cut. Each
// length of the box exceeds twice the reach (the scene loader's rule), so a pair has one shift.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/grains.hpp"
#include "engine/mpi/mpi_context.hpp"
#include "systems/decomposition/rcb.hpp"

namespace gf {

enum class GhostShell { full, half };

struct DomainGhosts {
  std::vector<std::vector<std::uint32_t>> send;  // per rank (this one's own images included): the owned rows it holds copies of
  std::vector<std::vector<std::array<double, 3>>> shift;  // per rank, beside send: each copy's shift (m); empty without faces
  std::vector<std::size_t> first, count;         // per rank: its ghost rows here (from n_owned)
  std::vector<int> peers;                        // the ranks whose boxes lie within reach of this one
  std::size_t size() const;
};

// Replaces the table's ghost rows by the rows of other ranks within `reach` (m) of this rank's box
// (with `periodic`, also across its faces, and this rank's own images; half shell only). Collective.
void make_domain_ghosts(Grains& g, const Rcb& rcb, double reach, const MpiContext& mpi, DomainGhosts& gh,
                        GhostShell shell = GhostShell::full, const PeriodicBox* periodic = nullptr);

// Position, velocity and spin of every ghost row from its owner.
void refresh_domain_ghosts(Grains& g, const DomainGhosts& gh, const MpiContext& mpi);

// Adds each ghost row's Force and Torque into its owner's row, on the owner's rank.
void fold_domain_ghost_forces(Grains& g, const DomainGhosts& gh, const MpiContext& mpi);

}  // namespace gf
