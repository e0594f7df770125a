// The run's time series: one CSV row per sample, flushed as it is written, so a run that is
// killed keeps every row it produced and the file can be plotted while the run goes on.
#pragma once

#include <cstdio>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace gf {

class SeriesCsv {
 public:
  // Creates (truncating) `file` and writes the header line. Column names may not contain a
  // comma, quote or line break, since they would need CSV quoting that plotting tools
  // handle unevenly: std::invalid_argument. WriteError naming the file if it
  // cannot be opened or written.
  SeriesCsv(std::filesystem::path file, std::vector<std::string> columns);

  // Continues the series of a resumed run: keeps the first `keep_rows` rows of an existing `file`
  // (those written up to the checkpoint), drops later ones (written after it by the run that was
  // stopped, a final sample included), and appends from there. The file is rewritten atomically
  // before appending. A file with fewer complete rows, or none, is continued from what it has
  // (the rows cannot be made up); one whose header names other columns is a std::runtime_error.
  static SeriesCsv resume(std::filesystem::path file, std::vector<std::string> columns, std::size_t keep_rows);

  // The same, keeping the rows whose first column (the time) is at most `last_time`: for a series
  // whose row count the checkpoint does not record. A missing file is started with its header.
  static SeriesCsv resume_through(std::filesystem::path file, std::vector<std::string> columns, double last_time);

  // Writes one row in the columns' order, in the shortest form that reads back as the same
  // double, then flushes. std::invalid_argument if values.size() != columns().size(). A failed
  // write (full disk) throws WriteError after cutting the file back to its last complete row.
  void append(std::span<const double> values);

  const std::vector<std::string>& columns() const { return columns_; }
  const std::filesystem::path& path() const { return file_; }

 private:
  struct Resume {};
  SeriesCsv(Resume, std::filesystem::path file, std::vector<std::string> columns, std::size_t keep_rows,
            double last_time);
  void check_columns() const;
  std::string header() const;
  struct Closer {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  void put(const std::string& line);

  std::filesystem::path file_;
  std::vector<std::string> columns_;
  std::unique_ptr<std::FILE, Closer> out_;
  std::string line_;  // reused, so a sample allocates nothing once warm
  std::size_t complete_bytes_ = 0;  // file size up to the end of the last complete row
};

}  // namespace gf
