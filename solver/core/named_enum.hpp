#pragma once
// One idiom for every enum a scene key or an output names: beside the enum, its
// namespace declares `names(E)` returning a table of (value, name) pairs (found by
// argument-dependent lookup). name(), find_enum(), enum_names() and parse_enum()
// below then work for it, and a new value is one table row.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>

#include "solver/core/error.hpp"

namespace pdmpm {

template <class E>
struct EnumName {
  E value;
  std::string_view name;
};

template <class E>
concept NamedEnum = std::is_enum_v<E> && requires(E e) { names(e); };

template <NamedEnum E>
std::string_view name(E e) {
  for (const auto& n : names(e))
    if (n.value == e) return n.name;
  return "?";
}

template <NamedEnum E>
std::optional<E> find_enum(std::string_view text) {
  for (const auto& n : names(E{}))
    if (n.name == text) return n.value;
  return std::nullopt;
}

// Every value, in table order (for loops over all influence functions, settings, …).
template <NamedEnum E>
constexpr auto enum_values() {
  constexpr auto table = names(E{});
  std::array<E, table.size()> out{};
  for (std::size_t i = 0; i < table.size(); ++i) out[i] = table[i].value;
  return out;
}

// "a, b, c" for error messages.
template <NamedEnum E>
std::string enum_names() {
  std::string out;
  for (const auto& n : names(E{})) out += (out.empty() ? "" : ", ") + std::string(n.name);
  return out;
}

// The value named `text`, or an InputError naming the file, the key and the allowed names.
template <NamedEnum E>
E parse_enum(std::string_view text, const std::string& file, const std::string& key) {
  if (auto e = find_enum<E>(text)) return *e;
  throw InputError(file, key, "must be one of " + enum_names<E>() + "; got \"" + std::string(text) + "\"");
}

}  // namespace pdmpm
