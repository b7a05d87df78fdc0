#include "verification/support/output_files.hpp"

#include <fstream>
#include <iterator>
#include <sstream>

namespace pdmpm::test {

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<std::map<std::string, double>> history_rows(const std::filesystem::path& csv) {
  std::ifstream in(csv);
  std::string header, line;
  std::getline(in, header);
  std::vector<std::string> names;
  std::stringstream h(header);
  for (std::string name; std::getline(h, name, ',');) names.push_back(name);
  std::vector<std::map<std::string, double>> rows;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::stringstream v(line);
    auto& row = rows.emplace_back();
    std::string value;
    for (std::size_t k = 0; k < names.size() && std::getline(v, value, ','); ++k) row[names[k]] = std::stod(value);
  }
  return rows;
}

std::map<std::string, double> last_history_row(const std::filesystem::path& csv) {
  auto rows = history_rows(csv);
  return rows.empty() ? std::map<std::string, double>{} : rows.back();
}

}  // namespace pdmpm::test
