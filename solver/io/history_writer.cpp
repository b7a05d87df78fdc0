#include "solver/io/history_writer.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <set>
#include <utility>

#include "solver/core/error.hpp"

namespace pdmpm::io {
namespace {

std::string system_error_text(int error) { return error ? std::strerror(error) : "unknown error"; }

std::string header_line(const std::vector<std::string>& columns) {
  std::string header;
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (i) header += ',';
    header += columns[i];
  }
  return header + '\n';
}

}  // namespace

HistoryWriter::HistoryWriter(std::filesystem::path path, std::vector<std::string> columns)
    : path_(std::move(path)), columns_(std::move(columns)) {
  if (columns_.empty()) throw RunError(fmt::format("history '{}': no columns", path_.string()));
  std::set<std::string> seen;
  for (const std::string& name : columns_) {
    if (name.empty() || name.find_first_of(",\"\r\n") != std::string::npos)
      throw RunError(
          fmt::format("history '{}': column name '{}' must be non-empty without commas, quotes or line breaks",
                      path_.string(), name));
    if (!seen.insert(name).second)
      throw RunError(fmt::format("history '{}': column '{}' given twice", path_.string(), name));
  }
  errno = 0;
  file_ = std::fopen(path_.c_str(), "w");
  if (!file_) throw RunError(fmt::format("history: cannot create '{}': {}", path_.string(), system_error_text(errno)));
  const std::string header = header_line(columns_);
  if (std::fwrite(header.data(), 1, header.size(), file_) != header.size() || std::fflush(file_) != 0) {
    const int error = errno;
    std::fclose(file_);
    file_ = nullptr;
    throw RunError(fmt::format("history: cannot write '{}': {}", path_.string(), system_error_text(error)));
  }
}

HistoryWriter HistoryWriter::resume(const std::filesystem::path& source, std::filesystem::path path,
                                    std::vector<std::string> columns, std::size_t rows) {
  std::ifstream in(source, std::ios::binary);
  if (!in) throw RunError(fmt::format("history: cannot open '{}'", source.string()));
  std::string text, line;
  std::getline(in, line);
  if (line + '\n' != header_line(columns))
    throw RunError(fmt::format("history '{}': its columns are not this run's", source.string()));
  text = line + '\n';
  for (std::size_t r = 0; r < rows; ++r) {
    if (!std::getline(in, line) || in.eof())  // a row without its line break was cut short
      throw RunError(
          fmt::format("history '{}': has fewer than the {} rows the checkpoint wrote", source.string(), rows));
    text += line + '\n';
  }
  HistoryWriter w;
  w.path_ = std::move(path);
  w.columns_ = std::move(columns);
  errno = 0;
  w.file_ = std::fopen(w.path_.c_str(), "w");
  if (!w.file_ || std::fwrite(text.data(), 1, text.size(), w.file_) != text.size() || std::fflush(w.file_) != 0)
    throw RunError(fmt::format("history: cannot write '{}': {}", w.path_.string(), system_error_text(errno)));
  w.rows_ = rows;
  return w;
}

HistoryWriter::~HistoryWriter() {
  if (file_) std::fclose(file_);
}

HistoryWriter::HistoryWriter(HistoryWriter&& other) noexcept
    : path_(std::move(other.path_)),
      columns_(std::move(other.columns_)),
      file_(std::exchange(other.file_, nullptr)),
      rows_(other.rows_) {}

HistoryWriter& HistoryWriter::operator=(HistoryWriter&& other) noexcept {
  if (this != &other) {
    if (file_) std::fclose(file_);
    path_ = std::move(other.path_);
    columns_ = std::move(other.columns_);
    file_ = std::exchange(other.file_, nullptr);
    rows_ = other.rows_;
  }
  return *this;
}

void HistoryWriter::write_row(const std::vector<double>& values) {
  if (!file_) throw RunError(fmt::format("history '{}': write_row after close", path_.string()));
  if (values.size() != columns_.size())
    throw RunError(
        fmt::format("history '{}': row has {} values for {} columns", path_.string(), values.size(), columns_.size()));
  fmt::memory_buffer line;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i) line.push_back(',');
    fmt::format_to(std::back_inserter(line), "{:.17g}", values[i]);
  }
  line.push_back('\n');
  errno = 0;
  if (std::fwrite(line.data(), 1, line.size(), file_) != line.size() || std::fflush(file_) != 0)
    throw RunError(fmt::format("history: cannot write '{}': {}", path_.string(), system_error_text(errno)));
  ++rows_;
}

void HistoryWriter::close() {
  if (!file_) return;
  errno = 0;
  const int status = std::fclose(std::exchange(file_, nullptr));
  if (status != 0)
    throw RunError(fmt::format("history: cannot close '{}': {}", path_.string(), system_error_text(errno)));
}

}  // namespace pdmpm::io
