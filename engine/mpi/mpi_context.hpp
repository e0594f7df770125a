// MPI for one process: initialisation and finalisation, the rank and size, the communicator, and the
// typed collectives the decomposition's exchanges use. Through Open MPI's C API.
//
// Threads stay inside each rank (oneTBB tasks, xsimd kernels): MPI is initialised with
// MPI_THREAD_FUNNELED and only the thread that made the context calls it. The single-process
// program does not use this class; a program that does may still run as one rank, with or
// without mpirun.
#pragma once

// The C API only: without these, mpi.h in C++ also declares the removed C++ bindings, whose
// symbols live in a library not linked here.
#ifndef OMPI_SKIP_MPICXX
#define OMPI_SKIP_MPICXX 1
#endif
#ifndef MPICH_SKIP_MPICXX
#define MPICH_SKIP_MPICXX 1
#endif
#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gf {

class MpiContext {
 public:
  // Initialises MPI unless it already is (then this context only borrows MPI_COMM_WORLD). Sets
  // MPI_COMM_WORLD's errors to return codes, which the helpers throw as std::runtime_error.
  MpiContext(int* argc, char*** argv);
  // Finalises MPI if this context initialised it.
  ~MpiContext();
  MpiContext(const MpiContext&) = delete;
  MpiContext& operator=(const MpiContext&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  MPI_Comm comm() const { return comm_; }
  void barrier() const;

  // Element r of the result is what rank r sent to this one (MPI_Alltoall).
  std::vector<int> alltoall(const std::vector<int>& send) const;
  // Sends send[r] (bytes) to rank r for every rank; returns, per rank, what it sent here. Each
  // message is at most 2 GiB (an int count of bytes).
  std::vector<std::vector<std::byte>> exchange(const std::vector<std::vector<std::byte>>& send) const;
  // The same with the ranks this one talks to given (`peers`, this rank left out): point-to-point
  // messages with them alone, no collective over all ranks, so its cost follows the peers, not the
  // rank count. The relation must be symmetric (each peer lists this rank) and every rank of the
  // communicator must make the call. A non-empty message for a rank outside `peers` is
  // std::invalid_argument (before anything is sent).
  std::vector<std::vector<std::byte>> exchange(const std::vector<std::vector<std::byte>>& send,
                                               const std::vector<int>& peers) const;
  // Every rank's bytes on `root` (element r from rank r); an empty list on the other ranks
  // (MPI_Gatherv). At most 2 GiB in all.
  std::vector<std::vector<std::byte>> gather(const std::vector<std::byte>& send, int root = 0) const;
  std::int64_t sum(std::int64_t value) const;
  double sum(double value) const;
  double max(double value) const;
  std::int64_t max(std::int64_t value) const;

 private:
  MPI_Comm comm_ = MPI_COMM_WORLD;
  int rank_ = 0;
  int size_ = 1;
  bool owns_ = false;
};

}  // namespace gf
