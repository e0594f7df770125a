#include "engine/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <stdexcept>
#include <string>
#include <system_error>

namespace gf {
namespace {

// std::system_category().message gives strerror's text without strerror's shared buffer,
// which matters once several output systems write from different threads.
[[noreturn]] void fail(const std::string& what, const std::filesystem::path& target, int err) {
  throw WriteError("cannot write '" + target.string() + "': " + what + ": " +
                           std::system_category().message(err));
}

// Owns a descriptor so every error path closes it.
class Fd {
 public:
  explicit Fd(int fd) : fd_(fd) {}
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }
  // Returns close()'s errno (0 on success): on NFS and some others a deferred write error
  // is reported only here, so it must not be ignored.
  int close() {
    const int fd = fd_;
    fd_ = -1;
    return ::close(fd) == 0 ? 0 : errno;
  }

 private:
  int fd_;
};

int write_all(int fd, std::string_view bytes) {
  const char* p = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t w = ::write(fd, p, left);
    if (w < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    p += w;
    left -= static_cast<std::size_t>(w);
  }
  return 0;
}

int fsync_retry(int fd) {
  while (::fsync(fd) != 0) {
    if (errno != EINTR) return errno;
  }
  return 0;
}

}  // namespace

void write_file_atomic(const std::filesystem::path& path, std::string_view bytes) {
  write_file_atomic(path, std::span<const std::string_view>(&bytes, 1));
}

void write_file_atomic(const std::filesystem::path& path, std::span<const std::string_view> pieces) {
  std::filesystem::path tmp = path;
  tmp += ".tmp";

  {
    // O_TRUNC: a stale .tmp from a killed earlier write is simply overwritten.
    Fd fd(::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666));
    if (fd.get() < 0) fail("cannot create temporary file '" + tmp.string() + "'", path, errno);

    int err = 0;
    for (std::size_t k = 0; k < pieces.size() && err == 0; ++k) err = write_all(fd.get(), pieces[k]);
    const char* step = "write to";
    if (err == 0) {
      // Without fsync the rename can reach the disk before the data, and a power cut would
      // leave an empty file under the final name: exactly the loss this function exists to stop.
      err = fsync_retry(fd.get());
      step = "fsync of";
    }
    if (err == 0) {
      err = fd.close();
      step = "close of";
    }
    if (err != 0) {
      ::unlink(tmp.c_str());
      fail(std::string(step) + " temporary file '" + tmp.string() + "' failed", path, err);
    }
  }

  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    fail("cannot rename '" + tmp.string() + "' over it", path, err);
  }

  // The rename lives in the folder's entries; fsync the folder so it is durable too. Some
  // filesystems cannot open or fsync a folder (EINVAL, EACCES on a write-only folder): the file
  // is already complete and in place there, so those are not errors.
  std::filesystem::path dir = path.parent_path();
  if (dir.empty()) dir = ".";
  Fd dfd(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (dfd.get() >= 0) {
    const int err = fsync_retry(dfd.get());
    if (err != 0 && err != EINVAL && err != EROFS)
      fail("fsync of folder '" + dir.string() + "' failed", path, err);
  }
}

void ensure_directory(const std::filesystem::path& dir) {
  if (dir.empty()) throw WriteError("cannot create output folder: the path is empty");
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec)
    throw WriteError("cannot create output folder '" + dir.string() + "': " + ec.message());
  if (!std::filesystem::is_directory(dir, ec))
    throw WriteError("output folder '" + dir.string() +
                             "' exists but is not a folder; remove it or choose another --out");
}

}  // namespace gf
