#include "engine/checkpoint_file.hpp"

#include <fstream>
#include <sstream>

#include "engine/atomic_file.hpp"
#include "engine/machine_memory.hpp"
#include "engine/read_file.hpp"
#include "engine/user_text.hpp"

namespace gf {

namespace {

constexpr std::string_view kMagic = "grainflow-checkpoint 1\n";

std::uint64_t fnv1a(std::string_view bytes, std::uint64_t h = 1469598103934665603ull) {
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ull;
  }
  return h;
}

template <class T>
void put(std::string& buf, T v) {
  buf.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

}  // namespace

void CheckpointWriter::raw(const std::string& name, const void* data, std::size_t elem_size, std::size_t count) {
  if (pieces_.empty()) pieces_.push_back(kMagic);
  std::string& head = owned_.emplace_back();
  put(head, static_cast<std::uint32_t>(name.size()));
  head.append(name);
  put(head, static_cast<std::uint64_t>(elem_size));
  put(head, static_cast<std::uint64_t>(count));
  pieces_.push_back(head);
  if (count) pieces_.emplace_back(static_cast<const char*>(data), elem_size * count);
}

std::size_t CheckpointWriter::bytes() const {
  std::size_t n = pieces_.empty() ? kMagic.size() : 0;
  for (std::string_view p : pieces_) n += p.size();
  return n + 8;
}

void CheckpointWriter::write(const std::filesystem::path& file) const {
  std::vector<std::string_view> all = pieces_;
  if (all.empty()) all.push_back(kMagic);
  std::uint64_t h = 1469598103934665603ull;
  for (std::string_view p : all) h = fnv1a(p, h);
  std::string tail;
  put(tail, h);
  all.push_back(tail);
  write_file_atomic(file, all);
}

void CheckpointReader::fail(const std::string& problem, const std::string& fix) const {
  throw CheckpointError(printable(file_.string() + ": " + problem + ". Fix: " + fix));
}

CheckpointReader::CheckpointReader(const std::filesystem::path& file) : file_(file) {
  FileProblem why;
  if (!read_regular_file(file, half_of_memory(), data_, why))
    fail("cannot read the checkpoint: " + why.problem, "give the path of a checkpoint a run wrote (checkpoints/*.gfc)");
  const std::string_view all(data_);
  if (all.substr(0, kMagic.size()) != kMagic)
    fail("not a grainflow checkpoint (or one of another format version)",
         "give a checkpoint written by this version of grainflow");
  if (all.size() < kMagic.size() + 8) fail("the file is truncated", "resume from an earlier checkpoint");
  std::uint64_t stored = 0;
  std::memcpy(&stored, all.data() + all.size() - 8, 8);
  if (fnv1a(all.substr(0, all.size() - 8)) != stored)
    fail("the checksum does not match: the file is truncated or corrupt", "resume from an earlier checkpoint");
  std::size_t p = kMagic.size();
  const std::size_t end = all.size() - 8;
  auto take = [&](std::size_t n) {
    if (end - p < n) fail("a section runs past the end of the file", "resume from an earlier checkpoint");
    const std::size_t at = p;
    p += n;
    return at;
  };
  while (p < end) {
    std::uint32_t len = 0;
    std::memcpy(&len, all.data() + take(4), 4);
    const std::string name(all.substr(take(len), len));
    std::uint64_t elem = 0, count = 0;
    std::memcpy(&elem, all.data() + take(8), 8);
    std::memcpy(&count, all.data() + take(8), 8);
    if (elem != 0 && count > (end - p) / elem) fail("section " + gf::quoted(name) + " runs past the end of the file",
                                                    "resume from an earlier checkpoint");
    sections_[name] = {elem, count, take(elem * count)};
  }
}

std::span<const char> CheckpointReader::need(const std::string& name, std::size_t elem, long long count) const {
  auto it = sections_.find(name);
  if (it == sections_.end())
    fail("section " + gf::quoted(name) + " is missing", "resume with the scene and grainflow version that wrote it");
  const Section& s = it->second;
  if (s.elem != elem || (count >= 0 && s.count != static_cast<std::size_t>(count)))
    fail("section " + gf::quoted(name) + " has " + std::to_string(s.count) + " elements of " + std::to_string(s.elem) +
             " bytes, expected " + (count >= 0 ? std::to_string(count) : std::string("some")) + " of " +
             std::to_string(elem),
         "resume with the scene and grainflow version that wrote it");
  return {data_.data() + s.offset, s.elem * s.count};
}

}  // namespace gf
