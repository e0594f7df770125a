// Feeds and outlets (flow_systems.hpp) for a run on several ranks.
//
// The flow's bookkeeping (FlowState: each feed's debt, events and fed mass, each outlet's next check
// and discharged mass, the residence log's batches) is the same on every rank, so every rank agrees on
// when an event or a check is due and any rank can find a leaving grain's entry time.
//
// Feed: at an event every rank sends every other its owned grains near the feed's region; each rank
// then places the event's grains as one process would (feed_events, with the other ranks' grains as
// `elsewhere`: the placement depends on the set of grains near the region, not on their order), so
// every rank draws the same grains with the same ids, and keeps those whose centre lies in its box.
// They join the table at the rebuild the queue forces in the same step, every rank rebuilding.
//
// Outlet: each rank counts out its own grains in the region (outlet_pass), every rank receives every
// rank's records in rank order, and each applies them to its residence log and outlet state alike,
// and keeps them in FlowState::exits (so every rank knows when there are records to write; rank 0
// writes residence.csv, the others drop them).
#pragma once

#include <cstddef>

#include "engine/grains.hpp"
#include "engine/mpi/mpi_context.hpp"
#include "systems/decomposition/rcb.hpp"
#include "systems/flow/flow_systems.hpp"

namespace gf {

// The feed events due at time t (collective when one is due, which every rank sees alike); this
// rank keeps the queued grains that `rcb` gives it. A rank whose rows and queued grains pass
// max_grains stops the run (check_feed_room).
void rank_feed_events(Grains& g, const FlowSpec& spec, FlowState& s, const Rcb& rcb, const MpiContext& mpi,
                      double t, std::size_t max_grains);

// The outlet checks due at time t (collective when one is due): grains in an outlet queued for
// removal on their rank, the records shared and appended to s.exits on every rank alike.
void rank_outlet_pass(Grains& g, const FlowSpec& spec, FlowState& s, const MpiContext& mpi, double t);

}  // namespace gf
