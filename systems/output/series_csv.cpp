#include "systems/output/series_csv.hpp"

#include <cerrno>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <fstream>
#include <system_error>

#include <unistd.h>

#include "engine/atomic_file.hpp"

namespace gf {

void SeriesCsv::check_columns() const {
  if (columns_.empty())
    throw std::invalid_argument("time series '" + file_.string() + "' needs at least one column");
  for (const std::string& c : columns_)
    if (c.empty() || c.find_first_of(",\"\r\n") != std::string::npos)
      throw std::invalid_argument("time series '" + file_.string() + "': column name '" + c +
                                  "' must be non-empty and contain no comma, quote or line break");
}

std::string SeriesCsv::header() const {
  std::string h;
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    if (i) h += ',';
    h += columns_[i];
  }
  return h + '\n';
}

SeriesCsv::SeriesCsv(std::filesystem::path file, std::vector<std::string> columns)
    : file_(std::move(file)), columns_(std::move(columns)) {
  check_columns();
  out_.reset(std::fopen(file_.c_str(), "w"));
  if (!out_)
    throw WriteError("cannot open time series '" + file_.string() +
                     "' for writing: " + std::system_category().message(errno));
  put(header());
}

SeriesCsv SeriesCsv::resume(std::filesystem::path file, std::vector<std::string> columns, std::size_t keep_rows) {
  return SeriesCsv(Resume{}, std::move(file), std::move(columns), keep_rows, INFINITY);
}

SeriesCsv SeriesCsv::resume_through(std::filesystem::path file, std::vector<std::string> columns, double last_time) {
  return SeriesCsv(Resume{}, std::move(file), std::move(columns), SIZE_MAX, last_time);
}

SeriesCsv::SeriesCsv(Resume, std::filesystem::path file, std::vector<std::string> columns, std::size_t keep_rows,
                     double last_time)
    : file_(std::move(file)), columns_(std::move(columns)) {
  check_columns();
  std::string kept = header();
  if (std::ifstream in{file_}) {
    std::string line;
    std::getline(in, line);
    if (line + '\n' != kept)
      throw std::runtime_error("cannot resume time series '" + file_.string() + "': its header is '" + line +
                               "', this run writes '" + kept.substr(0, kept.size() - 1) +
                               "'. Fix: resume into the folder of the run that wrote the checkpoint (--out), or "
                               "into a new folder");
    // A row cut short by a kill (no line end) is dropped too: the resumed run writes it again.
    for (std::size_t r = 0; r < keep_rows && std::getline(in, line) && !in.eof(); ++r) {
      // The time column parsed as written (shortest round trip): a later row, or one that does
      // not parse, ends what is kept.
      double t = NAN;
      if (last_time < INFINITY) std::from_chars(line.data(), line.data() + line.size(), t);
      if (last_time < INFINITY && !(t <= last_time)) break;
      kept += line;
      kept += '\n';
    }
  }
  write_file_atomic(file_, kept);
  out_.reset(std::fopen(file_.c_str(), "a"));
  if (!out_)
    throw WriteError("cannot open time series '" + file_.string() +
                     "' for appending: " + std::system_category().message(errno));
  complete_bytes_ = kept.size();
}

void SeriesCsv::append(std::span<const double> values) {
  if (!out_) throw WriteError("time series '" + file_.string() + "' was closed by an earlier write failure");
  if (values.size() != columns_.size())
    throw std::invalid_argument("time series '" + file_.string() + "': got " +
                                std::to_string(values.size()) + " values for " +
                                std::to_string(columns_.size()) + " columns");
  line_.clear();
  char buf[32];  // the longest shortest-round-trip double is 24 characters
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i) line_ += ',';
    // Plain to_chars is the shortest text that parses back to the same double: exact, and
    // shorter than %.17g. NaN and infinities come out as nan/inf, which strtod and numpy read.
    const auto res = std::to_chars(buf, buf + sizeof buf, values[i]);
    line_.append(buf, res.ptr);
  }
  line_ += '\n';
  put(line_);
}

void SeriesCsv::put(const std::string& line) {
  // Flush per line: stdio would otherwise hold up to a buffer's worth of rows that a killed
  // run loses. Rows are one per sampling interval, so the syscall is noise.
  errno = 0;
  if (std::fwrite(line.data(), 1, line.size(), out_.get()) != line.size() ||
      std::fflush(out_.get()) != 0) {
    const int err = errno;
    // A full disk may have taken part of the row: cut the file back to its last whole row, so what
    // was written stays a valid CSV. The stream is closed: nothing more goes to this file.
    const int fd = ::fileno(out_.get());
    const bool cut = ::ftruncate(fd, static_cast<off_t>(complete_bytes_)) == 0;
    out_.reset();
    throw WriteError("cannot write time series '" + file_.string() +
                     "': " + (err ? std::system_category().message(err) : "write failed") +
                     (cut ? " (the file keeps its complete rows)" : ""));
  }
  complete_bytes_ += line.size();
}

}  // namespace gf
