#include "solver/io/toml_reader.hpp"

#include <cmath>
#include <sstream>

namespace pdmpm::io {

TomlReader::TomlReader(const toml::table& table, std::string file, std::string path)
    : table_(table), file_(std::move(file)), path_(std::move(path)) {}

void TomlReader::fail(const std::string& key, const std::string& message) const {
  throw InputError(file_, key.empty() ? path_ : path(key), message);
}

const toml::node& TomlReader::node(const std::string& key) const {
  seen_.insert(key);
  const toml::node* n = table_.get(key);
  if (!n) fail(key, "missing (required)");
  return *n;
}

std::string TomlReader::type_name(const toml::node& n) const {
  switch (n.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::array: return "an array";
    case toml::node_type::table: return "a table";
    default: return "a date/time";
  }
}

namespace {
std::optional<double> as_number(const toml::node& n) {
  if (auto v = n.value_exact<double>()) return *v;
  if (auto v = n.value_exact<std::int64_t>()) return static_cast<double>(*v);
  return std::nullopt;
}
}  // namespace

double TomlReader::number(const std::string& key) const {
  const toml::node& n = node(key);
  auto v = as_number(n);
  if (!v) fail(key, "must be a number, got " + type_name(n));
  if (!std::isfinite(*v)) fail(key, "must be finite");
  return *v;
}

std::optional<double> TomlReader::optional_number(const std::string& key) const {
  seen_.insert(key);
  if (!has(key)) return std::nullopt;
  return number(key);
}

std::int64_t TomlReader::integer(const std::string& key) const {
  const toml::node& n = node(key);
  if (auto v = n.value_exact<std::int64_t>()) return *v;
  fail(key, "must be an integer, got " + type_name(n));
}

std::optional<std::int64_t> TomlReader::optional_integer(const std::string& key) const {
  seen_.insert(key);
  if (!has(key)) return std::nullopt;
  return integer(key);
}

bool TomlReader::boolean(const std::string& key, bool fallback) const {
  seen_.insert(key);
  if (!has(key)) return fallback;
  const toml::node& n = node(key);
  if (auto v = n.value_exact<bool>()) return *v;
  fail(key, "must be true or false, got " + type_name(n));
}

std::string TomlReader::string(const std::string& key) const {
  const toml::node& n = node(key);
  if (auto v = n.value_exact<std::string>()) return *v;
  fail(key, "must be a string, got " + type_name(n));
}

std::optional<std::string> TomlReader::optional_string(const std::string& key) const {
  seen_.insert(key);
  if (!has(key)) return std::nullopt;
  return string(key);
}

std::vector<double> TomlReader::numbers(const std::string& key, std::size_t n) const {
  const toml::node& nd = node(key);
  const toml::array* arr = nd.as_array();
  if (!arr) fail(key, "must be an array of numbers, got " + type_name(nd));
  if (n > 0 && arr->size() != n) fail(key, "must have exactly " + std::to_string(n) + " numbers, got " + std::to_string(arr->size()));
  if (arr->empty()) fail(key, "must not be empty");
  std::vector<double> out;
  for (std::size_t k = 0; k < arr->size(); ++k) {
    auto v = as_number(*arr->get(k));
    if (!v || !std::isfinite(*v)) fail(key, "element " + std::to_string(k) + " must be a finite number");
    out.push_back(*v);
  }
  return out;
}

std::optional<std::vector<double>> TomlReader::optional_numbers(const std::string& key, std::size_t n) const {
  seen_.insert(key);
  if (!has(key)) return std::nullopt;
  return numbers(key, n);
}

std::optional<std::vector<std::string>> TomlReader::optional_expressions(const std::string& key, std::size_t n) const {
  seen_.insert(key);
  if (!has(key)) return std::nullopt;
  const toml::node& nd = node(key);
  auto item = [&](const toml::node& x, const std::string& where) -> std::string {
    if (auto v = as_number(x)) {
      std::ostringstream s;
      s.precision(17);
      s << *v;
      return s.str();
    }
    if (auto v = x.value_exact<std::string>()) return *v;
    fail(key, where + "must be a number or an expression string, got " + type_name(x));
  };
  std::vector<std::string> out;
  if (const toml::array* arr = nd.as_array()) {
    if (arr->size() != n) fail(key, "must have exactly " + std::to_string(n) + " components (use \"free\" to leave one unconstrained), got " + std::to_string(arr->size()));
    for (std::size_t k = 0; k < arr->size(); ++k) out.push_back(item(*arr->get(k), "component " + std::to_string(k) + " "));
  } else {
    out.push_back(item(nd, ""));
  }
  return out;
}

std::vector<std::string> TomlReader::strings(const std::string& key) const {
  const toml::node& nd = node(key);
  const toml::array* arr = nd.as_array();
  if (!arr) fail(key, "must be an array of strings, got " + type_name(nd));
  std::vector<std::string> out;
  for (std::size_t k = 0; k < arr->size(); ++k) {
    auto v = arr->get(k)->value_exact<std::string>();
    if (!v) fail(key, "element " + std::to_string(k) + " must be a string");
    out.push_back(*v);
  }
  return out;
}

std::vector<std::string> TomlReader::keys() const {
  std::vector<std::string> out;
  for (const auto& [k, v] : table_) out.emplace_back(k.str());
  return out;
}

std::vector<TomlReader> TomlReader::table_or_tables(const std::string& key) const {
  const toml::node& n = node(key);
  if (n.is_table()) return {table(key)};
  if (!n.is_array()) fail(key, "must be a table or an array of tables, got " + type_name(n));
  auto out = tables(key);
  if (out.empty()) fail(key, "must not be empty");
  return out;
}

std::optional<TomlReader> TomlReader::optional_table(const std::string& key) const {
  seen_.insert(key);
  if (!has(key)) return std::nullopt;
  return table(key);
}

TomlReader TomlReader::table(const std::string& key) const {
  const toml::node& n = node(key);
  const toml::table* t = n.as_table();
  if (!t) fail(key, "must be a table, got " + type_name(n));
  return TomlReader(*t, file_, path(key));
}

std::vector<TomlReader> TomlReader::tables(const std::string& key) const {
  seen_.insert(key);
  std::vector<TomlReader> out;
  if (!has(key)) return out;
  const toml::node& n = node(key);
  const toml::array* arr = n.as_array();
  if (!arr) fail(key, "must be an array of tables ([[" + key + "]]), got " + type_name(n));
  for (std::size_t k = 0; k < arr->size(); ++k) {
    const toml::table* t = arr->get(k)->as_table();
    const std::string p = path(key) + "[" + std::to_string(k) + "]";
    if (!t) throw InputError(file_, p, "must be a table");
    out.emplace_back(*t, file_, p);
  }
  return out;
}

void TomlReader::finish() const {
  for (const auto& [k, v] : table_) {
    const std::string key(k.str());
    if (!seen_.count(key)) fail(key, "unknown key (check the spelling; see the scene reference in README.md)");
  }
}

double TomlReader::positive(const std::string& key, double v) const {
  if (!(v > 0.0)) {
    std::ostringstream s;
    s << "must be > 0, got " << v;
    fail(key, s.str());
  }
  return v;
}

double TomlReader::in_range(const std::string& key, double v, double lo, double hi, bool lo_open, bool hi_open) const {
  const bool ok = (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  if (!ok) {
    std::ostringstream s;
    s << "must be in " << (lo_open ? "(" : "[") << lo << ", " << hi << (hi_open ? ")" : "]") << ", got " << v;
    fail(key, s.str());
  }
  return v;
}

}  // namespace pdmpm::io
