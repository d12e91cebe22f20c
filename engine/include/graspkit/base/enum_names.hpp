#pragma once
// The one way an enum's values get their names, for every enum a user writes in a file, a flag or
// a script (materials, warning kinds, search spaces, energies' modes, wrench spaces, ...). Beside
// each such enum, its header declares its table:
//
//   std::span<const EnumName<Material>> enumNames(std::type_identity<Material>);
//
// one row per name: a value's first row is its name, any later rows are names also accepted for
// it (GraspIt!'s, older spellings). nameOf, valueNamed and parseNamed read that table, and the CLI,
// Lua, Python and the C ABI call them, so every front end prints and accepts the same names.

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>

#include "graspkit/base/error.hpp"

namespace graspkit {

template <typename E>
struct EnumName {
  E value;
  const char* name;  // a string literal: NUL-terminated, lives for the program
};

// The name of `value`; "unknown" for a value its table lacks (a cast from a bad integer). The
// view is of a string literal, so its data() is NUL-terminated (for C APIs).
template <typename E>
std::string_view nameOf(E value) {
  for (const EnumName<E>& row : enumNames(std::type_identity<E>{}))
    if (row.value == value) return row.name;
  return "unknown";
}

// The value named `name` (exactly, aliases included), or nullopt.
template <typename E>
std::optional<E> valueNamed(std::string_view name) {
  for (const EnumName<E>& row : enumNames(std::type_identity<E>{}))
    if (name == row.name) return row.value;
  return std::nullopt;
}

// The names of E's values (aliases left out) as "a, b or c".
template <typename E>
std::string namesOf() {
  const auto rows = enumNames(std::type_identity<E>{});
  auto primary = [&](std::size_t i) {
    for (std::size_t j = 0; j < i; ++j)
      if (rows[j].value == rows[i].value) return false;
    return true;
  };
  std::size_t count = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) count += primary(i);
  std::string list;
  std::size_t written = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (!primary(i)) continue;
    if (written > 0) list.append(written + 1 == count ? " or " : ", ");
    list.append(rows[i].name);
    ++written;
  }
  return list;
}

// The value named `text`; throws graspkit::Error "unknown <what> '<text>'; expected a, b or c".
template <typename E>
E parseNamed(std::string_view text, std::string_view what) {
  if (const std::optional<E> value = valueNamed<E>(text)) return *value;
  std::string message("unknown ");
  message.append(what).append(" '").append(text).append("'; expected ").append(namesOf<E>());
  throw Error(message);
}

}  // namespace graspkit
