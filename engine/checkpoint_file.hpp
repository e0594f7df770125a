// Checkpoint files: named binary sections with a checksum, written atomically.
//
// Layout: the magic line "grainflow-checkpoint 1\n", then per section a little-endian record
// {u32 name length, name, u64 element size, u64 element count, raw bytes}, then the FNV-1a 64 hash
// of everything before it. Raw bytes are the in-memory representation: a checkpoint is read back
// by the same build on the same kind of machine (it is for resuming runs, not for exchanging
// states; final_state.csv is the portable state).
#pragma once

#include <cstdint>
#include <cstring>
#include <deque>
#include <string_view>
#include <filesystem>
#include <map>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "engine/column.hpp"

namespace gf {

// Any unreadable, truncated, corrupt or mismatched checkpoint. what() names the file and the fix.
class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class CheckpointWriter {
 public:
  template <class T>
  void value(const std::string& name, const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    // Values are often temporaries: copied.
    const std::string& copy = owned_.emplace_back(reinterpret_cast<const char*>(&v), sizeof(T));
    raw(name, copy.data(), sizeof(T), 1);
  }
  template <class T>
  void column(const std::string& name, const Column<T>& c) {
    raw(name, c.data(), sizeof(T), c.size());
  }
  template <class T>
  void vector(const std::string& name, const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    raw(name, v.data(), sizeof(T), v.size());
  }
  // A temporary vector is copied.
  template <class T>
  void vector(const std::string& name, std::vector<T>&& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const std::string& copy = owned_.emplace_back(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
    raw(name, copy.data(), sizeof(T), v.size());
  }
  // Columns and vectors are not copied: their storage must stay unchanged until write().
  void raw(const std::string& name, const void* data, std::size_t elem_size, std::size_t count);

  // Write, flush and rename over `file` (engine/atomic_file): a crash leaves the old checkpoint.
  void write(const std::filesystem::path& file) const;
  std::size_t bytes() const;

 private:
  std::deque<std::string> owned_;          // record headers and small values, at stable addresses
  std::vector<std::string_view> pieces_;  // the file in order, without its checksum
};

class CheckpointReader {
 public:
  // Reads and verifies the whole file (magic, record structure, checksum).
  explicit CheckpointReader(const std::filesystem::path& file);

  bool has(const std::string& name) const { return sections_.count(name) != 0; }
  template <class T>
  T value(const std::string& name) const {
    static_assert(std::is_trivially_copyable_v<T>);
    T v;
    std::memcpy(&v, need(name, sizeof(T), 1).data(), sizeof(T));
    return v;
  }
  // Resizes the column to the stored count and fills it.
  template <class T>
  void column(const std::string& name, Column<T>& c) const {
    const auto b = need(name, sizeof(T), -1);
    c.resize(b.size() / sizeof(T));
    if (!b.empty()) std::memcpy(c.data(), b.data(), b.size());
  }
  template <class T>
  void vector(const std::string& name, std::vector<T>& v) const {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto b = need(name, sizeof(T), -1);
    v.resize(b.size() / sizeof(T));
    if (!b.empty()) std::memcpy(v.data(), b.data(), b.size());
  }
  // Copies a section of exactly `count` elements of `elem_size` bytes into `data`.
  void copy_raw(const std::string& name, void* data, std::size_t elem_size, std::size_t count) const {
    const auto b = need(name, elem_size, static_cast<long long>(count));
    if (!b.empty()) std::memcpy(data, b.data(), b.size());
  }
  const std::filesystem::path& file() const { return file_; }
  std::size_t bytes() const { return data_.size(); }  // the file's size
  // Throws CheckpointError "<file>: <problem>. Fix: <fix>".
  [[noreturn]] void fail(const std::string& problem, const std::string& fix) const;
  // Fails with "it is inconsistent (<what>)" unless `ok`. A checkpoint is raw arrays of the same build, sealed
  // by a checksum; one corrupted and sealed again must still not index past an array, so the readers check
  // every value they use as an index or a count. `fix`: one of the kFix remedies below.
  void require(bool ok, const std::string& what, const std::string& fix) const {
    if (!ok) fail("it is inconsistent (" + what + ")", fix);
  }
  // Fails unless the value the checkpoint was written with equals the scene's now.
  template <class T>
  void require_equal(const char* what, T stored, T now, const std::string& fix) const {
    if (stored != now)
      fail(std::string("it was written with ") + what + " = " + std::to_string(stored) + ", the scene now gives " +
               std::to_string(now),
           fix);
  }

 private:
  struct Section {
    std::size_t elem = 0, count = 0, offset = 0;
  };
  // The section's bytes; checks its element size and, when count >= 0, its element count.
  std::span<const char> need(const std::string& name, std::size_t elem, long long count) const;

  std::filesystem::path file_;
  std::string data_;
  std::map<std::string, Section> sections_;
};

// The remedies a checkpoint reader's refusals name, by what else can restart the run.
inline constexpr const char* kFixResume = "resume from an earlier checkpoint";
inline constexpr const char* kFixResumeOrStateFile =
    "resume from an earlier checkpoint, or from final_state.csv with a file fill";
inline constexpr const char* kFixResumeOrRerun = "resume from an earlier checkpoint, or run the scene again";

}  // namespace gf

namespace gf {

// A system with state of its own beyond the world's tables and resources (an output's next due
// time, a frame index). It writes that state into each checkpoint and takes it back on resume.
class Checkpointable {
 public:
  virtual ~Checkpointable() = default;
  virtual void save(CheckpointWriter& out) const = 0;
  virtual void restore(const CheckpointReader& in) = 0;
};

}  // namespace gf
