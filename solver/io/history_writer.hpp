#pragma once
// Time history as CSV: a header of column names, then one row per call with
// every value at full precision (%.17g, so it reads back as the same double).
// Each row is flushed, so a long run can be followed with `tail -f`.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace pdmpm::io {

class HistoryWriter {
 public:
  // Column names must be non-empty, unique, and free of commas, quotes and
  // line breaks (they are written unquoted).
  HistoryWriter(std::filesystem::path path, std::vector<std::string> columns);
  // Continues the history in `source` at `path`: its header must be these columns,
  // and its first `rows` rows are kept (a resumed run drops the rows written after
  // its checkpoint). RunError if the file is not such a history.
  static HistoryWriter resume(const std::filesystem::path& source, std::filesystem::path path,
                              std::vector<std::string> columns, std::size_t rows);
  ~HistoryWriter();
  HistoryWriter(HistoryWriter&& other) noexcept;
  HistoryWriter& operator=(HistoryWriter&& other) noexcept;
  HistoryWriter(const HistoryWriter&) = delete;
  HistoryWriter& operator=(const HistoryWriter&) = delete;

  void write_row(const std::vector<double>& values);
  // Closes the file and reports a failed write; idempotent.
  void close();

  const std::vector<std::string>& columns() const { return columns_; }
  std::size_t rows() const { return rows_; }

 private:
  HistoryWriter() = default;
  std::filesystem::path path_;
  std::vector<std::string> columns_;
  std::FILE* file_ = nullptr;
  std::size_t rows_ = 0;
};

}  // namespace pdmpm::io
