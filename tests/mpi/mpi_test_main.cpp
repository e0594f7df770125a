// Catch2's main for the tests that run under mpirun: MPI is initialised around the session, and
// the tests reach the communicator through test_world().
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "tests/mpi/mpi_test_support.hpp"

namespace {
const gf::MpiContext* world = nullptr;
}

const gf::MpiContext& gf::test::test_world() { return *world; }

int main(int argc, char** argv) {
  gf::MpiContext mpi(&argc, &argv);
  world = &mpi;
  return Catch::Session().run(argc, argv);
}
