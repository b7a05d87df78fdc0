#pragma once
// Key-by-key reading of a TOML table with validation. Every read marks the key
// as known; finish() rejects keys nobody asked for. Errors are InputErrors that
// name the file, the full key path and the allowed values.
#include <toml++/toml.h>

#include <optional>
#include <set>
#include <string>
#include <vector>

#include "solver/core/error.hpp"
#include "solver/core/named_enum.hpp"

namespace pdmpm::io {

class TomlReader {
 public:
  TomlReader(const toml::table& table, std::string file, std::string path);

  bool has(const std::string& key) const { return table_.contains(key); }
  std::string path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }

  // Typed reads. `required` reads throw when the key is missing.
  double number(const std::string& key) const;
  std::optional<double> optional_number(const std::string& key) const;
  std::int64_t integer(const std::string& key) const;
  std::optional<std::int64_t> optional_integer(const std::string& key) const;
  bool boolean(const std::string& key, bool fallback) const;
  std::string string(const std::string& key) const;
  std::optional<std::string> optional_string(const std::string& key) const;
  // A string naming a value of a NamedEnum; any other string fails listing the allowed names.
  template <NamedEnum E>
  std::optional<E> optional_enum(const std::string& key) const {
    const auto text = optional_string(key);
    if (!text) return std::nullopt;
    if (auto e = find_enum<E>(*text)) return e;
    fail(key, "must be one of " + enum_names<E>() + "; got \"" + *text + "\"");
  }
  // A list of exactly `n` numbers (n = 0: any length ≥ 1).
  std::vector<double> numbers(const std::string& key, std::size_t n) const;
  std::optional<std::vector<double>> optional_numbers(const std::string& key, std::size_t n) const;
  // A number or an expression string, or a list of them (one per component).
  std::optional<std::vector<std::string>> optional_expressions(const std::string& key, std::size_t n) const;

  // A list of strings.
  std::vector<std::string> strings(const std::string& key) const;
  // Keys of this table, in file order.
  std::vector<std::string> keys() const;
  // A table, or an array of tables: each returned with its path.
  std::vector<TomlReader> table_or_tables(const std::string& key) const;

  std::optional<TomlReader> optional_table(const std::string& key) const;
  TomlReader table(const std::string& key) const;
  // Array of tables ([[key]]), each with its indexed path "key[i]".
  std::vector<TomlReader> tables(const std::string& key) const;

  // Throws for the first key that no read asked for.
  void finish() const;

  [[noreturn]] void fail(const std::string& key, const std::string& message) const;
  // Range checks with a message naming the allowed interval.
  double positive(const std::string& key, double v) const;
  double in_range(const std::string& key, double v, double lo, double hi, bool lo_open, bool hi_open) const;

 private:
  const toml::node& node(const std::string& key) const;
  std::string type_name(const toml::node& n) const;

  const toml::table& table_;
  std::string file_, path_;
  mutable std::set<std::string> seen_;
};

}  // namespace pdmpm::io
