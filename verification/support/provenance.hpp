#pragma once
// Where a result came from: git sha and dirty flag, date, compiler and flags,
// CPU and thread count.
#include <nlohmann/json.hpp>

namespace pdmpm::test {
nlohmann::json provenance();
}
