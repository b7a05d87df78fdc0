#include "solver/dist/launch.hpp"

#include <cstdlib>
#include <string>

namespace pdmpm::dist {
namespace {

// A positive integer variable, or `fallback` when unset or not a number.
int integer_variable(const char* name, int fallback) {
  const char* text = std::getenv(name);
  if (!text) return fallback;
  try {
    return std::stoi(text);
  } catch (const std::exception&) {
    return fallback;
  }
}

}  // namespace

Launch launch_from_environment() {
  Launch l;
  for (const auto& [size, rank] :
       {std::pair{"OMPI_COMM_WORLD_SIZE", "OMPI_COMM_WORLD_RANK"}, std::pair{"PMI_SIZE", "PMI_RANK"}}) {
    const int n = integer_variable(size, 0);
    if (n > 0) {
      l.processes = n;
      l.rank = integer_variable(rank, 0);
      return l;
    }
  }
  return l;
}

}  // namespace pdmpm::dist
