#pragma once
// Reading what a run wrote, for tests: a whole file as text, and history.csv by
// column name.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace pdmpm::test {

// The file's bytes ("" if it cannot be opened).
std::string read_text(const std::filesystem::path& file);
// Every row of a history.csv, by column name (every column is a number).
std::vector<std::map<std::string, double>> history_rows(const std::filesystem::path& csv);
// Its last row (empty if the file has no row).
std::map<std::string, double> last_history_row(const std::filesystem::path& csv);

}  // namespace pdmpm::test
