#include "engine/mpi/mpi_context.hpp"

#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

namespace gf {

namespace {

void check(int code, const char* what) {
  if (code == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int len = 0;
  MPI_Error_string(code, text, &len);
  throw std::runtime_error(std::string(what) + " failed: " + std::string(text, static_cast<std::size_t>(len)));
}

int byte_count(std::size_t bytes) {
  if (bytes > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw std::length_error("an MPI message of " + std::to_string(bytes) + " bytes exceeds 2 GiB");
  return static_cast<int>(bytes);
}

}  // namespace

MpiContext::MpiContext(int* argc, char*** argv) {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) {
    int provided = 0;
    check(MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
    owns_ = true;
  }
  // Errors come back as codes (thrown as exceptions here) instead of aborting every rank.
  MPI_Comm_set_errhandler(comm_, MPI_ERRORS_RETURN);
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

MpiContext::~MpiContext() {
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (owns_ && !finalised) MPI_Finalize();
}

void MpiContext::barrier() const { check(MPI_Barrier(comm_), "MPI_Barrier"); }

std::vector<int> MpiContext::alltoall(const std::vector<int>& send) const {
  if (send.size() != static_cast<std::size_t>(size_)) throw std::invalid_argument("alltoall needs one value per rank");
  std::vector<int> recv(send.size());
  check(MPI_Alltoall(send.data(), 1, MPI_INT, recv.data(), 1, MPI_INT, comm_), "MPI_Alltoall");
  return recv;
}

std::vector<std::vector<std::byte>> MpiContext::exchange(const std::vector<std::vector<std::byte>>& send) const {
  const auto p = static_cast<std::size_t>(size_);
  if (send.size() != p) throw std::invalid_argument("exchange needs one message per rank");
  std::vector<int> scount(p), sdispl(p), rdispl(p);
  std::vector<std::byte> sbuf;
  for (std::size_t r = 0; r < p; ++r) {
    sdispl[r] = byte_count(sbuf.size());
    scount[r] = byte_count(send[r].size());
    sbuf.insert(sbuf.end(), send[r].begin(), send[r].end());
  }
  const std::vector<int> rcount = alltoall(scount);
  std::size_t total = 0;
  for (std::size_t r = 0; r < p; ++r) {
    rdispl[r] = byte_count(total);
    total += static_cast<std::size_t>(rcount[r]);
  }
  std::vector<std::byte> rbuf(total);
  check(MPI_Alltoallv(sbuf.data(), scount.data(), sdispl.data(), MPI_BYTE, rbuf.data(), rcount.data(), rdispl.data(),
                      MPI_BYTE, comm_),
        "MPI_Alltoallv");
  std::vector<std::vector<std::byte>> out(p);
  for (std::size_t r = 0; r < p; ++r)
    out[r].assign(rbuf.begin() + rdispl[r], rbuf.begin() + rdispl[r] + rcount[r]);
  return out;
}

std::vector<std::vector<std::byte>> MpiContext::exchange(const std::vector<std::vector<std::byte>>& send,
                                                      const std::vector<int>& peers) const {
  const auto p = static_cast<std::size_t>(size_);
  if (send.size() != p) throw std::invalid_argument("exchange needs one message per rank");
  std::vector<char> peer(p, 0);
  for (const int r : peers) {
    if (r < 0 || r >= size_ || r == rank_) throw std::invalid_argument("a peer is not another rank");
    peer[static_cast<std::size_t>(r)] = 1;
  }
  for (std::size_t r = 0; r < p; ++r)
    if (!peer[r] && static_cast<int>(r) != rank_ && !send[r].empty())
      throw std::invalid_argument("a message for rank " + std::to_string(r) + ", which is not a peer");
  constexpr int kSizeTag = 7101, kDataTag = 7102;
  std::vector<std::vector<std::byte>> out(p);
  out[static_cast<std::size_t>(rank_)] = send[static_cast<std::size_t>(rank_)];
  const std::size_t n = peers.size();
  std::vector<std::uint64_t> ssize(n), rsize(n);
  std::vector<MPI_Request> req(2 * n);
  for (std::size_t k = 0; k < n; ++k) {
    ssize[k] = send[static_cast<std::size_t>(peers[k])].size();
    check(MPI_Irecv(&rsize[k], 1, MPI_UINT64_T, peers[k], kSizeTag, comm_, &req[k]), "MPI_Irecv");
    check(MPI_Isend(&ssize[k], 1, MPI_UINT64_T, peers[k], kSizeTag, comm_, &req[n + k]), "MPI_Isend");
  }
  check(MPI_Waitall(static_cast<int>(req.size()), req.data(), MPI_STATUSES_IGNORE), "MPI_Waitall");
  for (std::size_t k = 0; k < n; ++k) {
    auto& in = out[static_cast<std::size_t>(peers[k])];
    in.resize(static_cast<std::size_t>(rsize[k]));
    const auto& mine = send[static_cast<std::size_t>(peers[k])];
    check(MPI_Irecv(in.data(), byte_count(in.size()), MPI_BYTE, peers[k], kDataTag, comm_, &req[k]), "MPI_Irecv");
    check(MPI_Isend(mine.data(), byte_count(mine.size()), MPI_BYTE, peers[k], kDataTag, comm_, &req[n + k]),
          "MPI_Isend");
  }
  check(MPI_Waitall(static_cast<int>(req.size()), req.data(), MPI_STATUSES_IGNORE), "MPI_Waitall");
  return out;
}

std::vector<std::vector<std::byte>> MpiContext::gather(const std::vector<std::byte>& send, int root) const {
  const int count = byte_count(send.size());
  const bool here = rank_ == root;
  std::vector<int> counts(here ? static_cast<std::size_t>(size_) : 0), displs(counts.size());
  check(MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, root, comm_), "MPI_Gather");
  std::size_t total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    displs[r] = byte_count(total);
    total += static_cast<std::size_t>(counts[r]);
  }
  byte_count(total);
  std::vector<std::byte> all(total);
  check(MPI_Gatherv(send.data(), count, MPI_BYTE, all.data(), counts.data(), displs.data(), MPI_BYTE, root, comm_),
        "MPI_Gatherv");
  std::vector<std::vector<std::byte>> out(counts.size());
  for (std::size_t r = 0; r < counts.size(); ++r)
    out[r].assign(all.begin() + displs[r], all.begin() + displs[r] + counts[r]);
  return out;
}

std::int64_t MpiContext::sum(std::int64_t value) const {
  std::int64_t out = 0;
  check(MPI_Allreduce(&value, &out, 1, MPI_INT64_T, MPI_SUM, comm_), "MPI_Allreduce");
  return out;
}

double MpiContext::sum(double value) const {
  double out = 0;
  check(MPI_Allreduce(&value, &out, 1, MPI_DOUBLE, MPI_SUM, comm_), "MPI_Allreduce");
  return out;
}

double MpiContext::max(double value) const {
  double out = 0;
  check(MPI_Allreduce(&value, &out, 1, MPI_DOUBLE, MPI_MAX, comm_), "MPI_Allreduce");
  return out;
}

std::int64_t MpiContext::max(std::int64_t value) const {
  std::int64_t out = 0;
  check(MPI_Allreduce(&value, &out, 1, MPI_INT64_T, MPI_MAX, comm_), "MPI_Allreduce");
  return out;
}

}  // namespace gf
