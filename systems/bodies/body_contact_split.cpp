#include "systems/bodies/body_contact_split.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

#include "systems/bodies/body_contact.hpp"

namespace gf {

namespace {

class Writer {
 public:
  explicit Writer(std::vector<std::byte>& out) : out_(out) {}
  template <class T>
  void put(const T& v) {
    const auto* p = reinterpret_cast<const std::byte*>(&v);
    out_.insert(out_.end(), p, p + sizeof(T));
  }
  void put(const Eigen::Vector3d& v) { put(v.x()), put(v.y()), put(v.z()); }
  void put(const double* v, std::size_t n) {
    const auto* p = reinterpret_cast<const std::byte*>(v);
    out_.insert(out_.end(), p, p + n * sizeof(double));
  }

 private:
  std::vector<std::byte>& out_;
};

class Reader {
 public:
  explicit Reader(std::span<const std::byte> in) : in_(in) {}
  template <class T>
  T get() {
    T v;
    take(&v, sizeof v);
    return v;
  }
  Eigen::Vector3d vec() {
    const double x = get<double>(), y = get<double>(), z = get<double>();
    return {x, y, z};
  }
  void get(double* v, std::size_t n) { take(v, n * sizeof(double)); }
  bool done() const { return at_ == in_.size(); }

 private:
  void take(void* p, std::size_t n) {
    if (in_.size() - at_ < n) throw std::runtime_error("a body-contact record from another process is cut short");
    std::memcpy(p, in_.data() + at_, n);
    at_ += n;
  }
  std::span<const std::byte> in_;
  std::size_t at_ = 0;
};

std::size_t checked_index(std::uint64_t i, std::size_t n, const char* what) {
  if (i >= n)
    throw std::runtime_error(std::string("a body-contact record from another process names ") + what + " " +
                             std::to_string(i) + ", past the last of " + std::to_string(n) +
                             ": the processes do not hold the same bodies (run one build of grainflow_mpi on every rank)");
  return static_cast<std::size_t>(i);
}

}  // namespace

std::uint64_t body_state_hash(const Bodies& b) {
  // 64-bit words through a multiply-xorshift mix: every bit of every word reaches the result.
  std::uint64_t h = 0x9E3779B97F4A7C15ull ^ b.n;
  for (const ColumnD* c : {&b.pos.x, &b.pos.y, &b.pos.z, &b.q.w, &b.q.x, &b.q.y, &b.q.z, &b.vel.x, &b.vel.y,
                           &b.vel.z, &b.omega.x, &b.omega.y, &b.omega.z})
    for (std::size_t i = 0; i < b.n; ++i) {
      std::uint64_t w;
      std::memcpy(&w, &(*c)[i], sizeof w);
      h = (h ^ w) * 0xBF58476D1CE4E5B9ull;
      h ^= h >> 29;
    }
  return h;
}

SplitBlocks split_blocks(const BodyContactSplit& split) {
  if (split.ranks < 1 || split.rank < 0 || split.rank >= split.ranks)
    throw std::invalid_argument("a body-contact split of rank " + std::to_string(split.rank) + " among " +
                                std::to_string(split.ranks) + " processes");
  return {static_cast<std::size_t>(split.rank), static_cast<std::size_t>(split.ranks)};
}

std::vector<std::byte> pack_outcomes(std::uint64_t hash, std::span<const ContactOutcome> pairs, std::size_t pair_width,
                                     std::span<const ContactOutcome> walls, const MemberWallHistory& springs,
                                     const SplitBlocks& mine) {
  std::vector<std::byte> out;
  Writer w(out);
  w.put(hash);
  std::uint64_t n = 0;
  for (std::size_t k = mine.offset; k < pairs.size(); k += mine.stride) n += pairs[k].touching;
  w.put(n);
  for (std::size_t k = mine.offset; k < pairs.size(); k += mine.stride) {
    const ContactOutcome& o = pairs[k];
    if (!o.touching) continue;
    w.put(static_cast<std::uint32_t>(k)), w.put(o.delta), w.put(o.force), w.put(o.torque_a), w.put(o.torque_b);
    w.put(o.history.data(), pair_width);
  }
  n = 0;
  for (std::size_t m = mine.offset; m < walls.size(); m += mine.stride) n += walls[m].touching;
  w.put(n);
  const std::size_t planes = springs.planes;
  for (std::size_t m = mine.offset; m < walls.size(); m += mine.stride) {
    const ContactOutcome& o = walls[m];
    if (!o.touching) continue;
    w.put(static_cast<std::uint32_t>(m)), w.put(o.delta), w.put(o.force), w.put(o.torque_a);
    std::uint32_t touching = 0;
    for (std::size_t p = 0; p < planes; ++p) touching += springs.touching[m * planes + p];
    w.put(touching);
    for (std::size_t p = 0; p < planes; ++p)
      if (springs.touching[m * planes + p]) {
        w.put(static_cast<std::uint32_t>(p));
        w.put(springs.value.data() + (m * planes + p) * springs.width, springs.width);
        w.put(springs.load.data() + (m * planes + p) * MemberWallHistory::kLoad, MemberWallHistory::kLoad);
      }
  }
  return out;
}

std::uint64_t unpack_outcomes(std::span<const std::byte> bytes, std::span<ContactOutcome> pairs, std::size_t pair_width,
                              std::span<ContactOutcome> walls, MemberWallHistory& springs) {
  Reader r(bytes);
  const auto hash = r.get<std::uint64_t>();
  for (std::uint64_t n = r.get<std::uint64_t>(); n > 0; --n) {
    ContactOutcome& o = pairs[checked_index(r.get<std::uint32_t>(), pairs.size(), "list pair")];
    o.touching = true;
    o.delta = r.get<double>();
    o.force = r.vec(), o.torque_a = r.vec(), o.torque_b = r.vec();
    r.get(o.history.data(), pair_width);
  }
  for (std::uint64_t n = r.get<std::uint64_t>(); n > 0; --n) {
    const std::size_t m = checked_index(r.get<std::uint32_t>(), walls.size(), "member");
    ContactOutcome& o = walls[m];
    o.touching = true;
    o.delta = r.get<double>();
    o.force = r.vec(), o.torque_a = r.vec();
    for (std::uint32_t t = r.get<std::uint32_t>(); t > 0; --t) {
      const std::size_t p = checked_index(r.get<std::uint32_t>(), springs.planes, "plane");
      springs.touching[m * springs.planes + p] = 1;
      r.get(springs.at(m, p), springs.width);
      r.get(springs.load_at(m, p), MemberWallHistory::kLoad);
    }
  }
  if (!r.done()) throw std::runtime_error("a body-contact record from another process has bytes past its end");
  return hash;
}

bool share_outcomes(const BodyContactSplit& split, std::uint64_t hash, std::span<ContactOutcome> pairs,
                    std::size_t pair_width, std::span<ContactOutcome> walls, MemberWallHistory& springs,
                    const SplitBlocks& mine) {
  std::vector<std::vector<std::byte>> all = split.share(pack_outcomes(hash, pairs, pair_width, walls, springs, mine));
  if (all.size() != static_cast<std::size_t>(split.ranks))
    throw std::runtime_error("the body contacts' share returned " + std::to_string(all.size()) + " parts for " +
                             std::to_string(split.ranks) + " processes");
  const std::size_t cells = springs.planes;
  for (std::size_t m = 0; m < walls.size(); ++m) {
    if (mine.mine(m)) continue;
    std::fill_n(springs.touching.begin() + static_cast<std::ptrdiff_t>(m * cells), cells, std::uint8_t{0});
    std::fill_n(springs.value.begin() + static_cast<std::ptrdiff_t>(m * cells * springs.width), cells * springs.width, 0.0);
  }
  bool same = true;
  for (std::size_t r = 0; r < all.size(); ++r)
    if (static_cast<int>(r) != split.rank) same = unpack_outcomes(all[r], pairs, pair_width, walls, springs) == hash && same;
  return same;
}

}  // namespace gf
