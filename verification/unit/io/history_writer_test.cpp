// HistoryWriter: the CSV reads back as the same doubles, each row is on disk
// as soon as write_row returns, and malformed input is refused.
#include "solver/io/history_writer.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "solver/core/error.hpp"
#include "verification/support/scratch_dir.hpp"
#include "verification/support/same_bits.hpp"

namespace pdmpm::io {
namespace {

using test::same_bits;

namespace fs = std::filesystem;

std::vector<std::string> read_lines(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string cell; std::getline(ss, cell, ',');) out.push_back(cell);
  return out;
}

TEST(HistoryWriter, RoundTripsEveryDoubleExactly) {
  test::ScratchDir dir("history_roundtrip");
  const fs::path path = dir.path() / "history.csv";
  const std::vector<std::string> columns = {"time", "step", "kinetic_energy", "broken_bonds"};
  // Values that a short format would change: 0.1, 1/3, the extremes of the
  // double range, a signed zero, and values whose shortest form has 17 digits.
  const std::vector<std::vector<double>> rows = {
      {0.0, 0.0, 0.1, 0.0},
      {1.0 / 3.0, 1.0, -0.0, 12.0},
      {std::numeric_limits<double>::denorm_min(), 2.0, std::numeric_limits<double>::max(), 1e300},
      {std::numeric_limits<double>::min(), 3.0, 2.0 / 3.0 * 1e-9, 0.30000000000000004},
      {9007199254740993.0, 4.0, -123456.78901234567, std::nextafter(1.0, 2.0)},
  };
  {
    HistoryWriter writer(path, columns);
    for (const auto& row : rows) writer.write_row(row);
    EXPECT_EQ(writer.rows(), rows.size());
    writer.close();
  }
  const auto lines = read_lines(path);
  ASSERT_EQ(lines.size(), rows.size() + 1);
  EXPECT_EQ(lines[0], "time,step,kinetic_energy,broken_bonds");
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const auto cells = split(lines[r + 1]);
    ASSERT_EQ(cells.size(), columns.size()) << lines[r + 1];
    for (std::size_t c = 0; c < cells.size(); ++c)
      EXPECT_TRUE(same_bits(std::strtod(cells[c].c_str(), nullptr), rows[r][c])) << "row " << r << ": " << cells[c];
  }
  // %.17g style: 0.1 is written with all 17 significant digits.
  EXPECT_EQ(split(lines[1])[2], "0.10000000000000001");
}

TEST(HistoryWriter, NonFiniteValuesAreWrittenReadably) {
  test::ScratchDir dir("history_nonfinite");
  const fs::path path = dir.path() / "h.csv";
  HistoryWriter writer(path, {"a", "b", "c"});
  writer.write_row({std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(), std::nan("")});
  const auto lines = read_lines(path);
  ASSERT_EQ(lines.size(), 2u);
  const auto cells = split(lines[1]);
  EXPECT_EQ(std::strtod(cells[0].c_str(), nullptr), std::numeric_limits<double>::infinity());
  EXPECT_EQ(std::strtod(cells[1].c_str(), nullptr), -std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isnan(std::strtod(cells[2].c_str(), nullptr))) << cells[2];
}

// `tail -f` sees each row as soon as it is written: read the file through a
// separate stream while the writer is still open.
TEST(HistoryWriter, EachRowIsFlushed) {
  test::ScratchDir dir("history_flush");
  const fs::path path = dir.path() / "h.csv";
  HistoryWriter writer(path, {"t", "e"});
  EXPECT_EQ(read_lines(path), (std::vector<std::string>{"t,e"}));
  writer.write_row({1.5, 2.25});
  EXPECT_EQ(read_lines(path), (std::vector<std::string>{"t,e", "1.5,2.25"}));
  writer.write_row({3.0, -4.0});
  EXPECT_EQ(read_lines(path).size(), 3u);
}

TEST(HistoryWriter, RejectsBadColumnsRowsAndPaths) {
  test::ScratchDir dir("history_invalid");
  const fs::path path = dir.path() / "h.csv";
  EXPECT_THROW(HistoryWriter(path, {}), RunError);
  EXPECT_THROW(HistoryWriter(path, {"a", ""}), RunError);
  EXPECT_THROW(HistoryWriter(path, {"a,b"}), RunError);
  EXPECT_THROW(HistoryWriter(path, {"a", "a"}), RunError);
  try {
    HistoryWriter writer(dir.path() / "missing" / "h.csv", {"a"});
    ADD_FAILURE() << "created a file in a missing directory";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("No such file or directory"), std::string::npos) << e.what();
  }
  HistoryWriter writer(path, {"a", "b"});
  try {
    writer.write_row({1.0});
    ADD_FAILURE() << "accepted a short row";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("row has 1 values for 2 columns"), std::string::npos) << e.what();
  }
  writer.close();
  writer.close();
  EXPECT_THROW(writer.write_row({1.0, 2.0}), RunError);
  EXPECT_EQ(read_lines(path), (std::vector<std::string>{"a,b"}));
}

}  // namespace
}  // namespace pdmpm::io
