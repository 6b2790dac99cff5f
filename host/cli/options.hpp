// The conventions every subcommand's options follow (docs/cli.md, "Errors"):
// - a bad value is an error that names the flag, and exits 2 like any other bad input: CLI11's
//   own parse errors, an OptionError found after parsing, a golden check's std::invalid_argument
//   translated by the command's field->flag table (rethrow_naming_flags);
// - the help shows short descriptions of what a value may be (`> 0`, `[0, 1]`, `2..16`,
//   `int|float`), never a validator's internals: the validators below, not CLI11's Range,
//   PositiveNumber or CheckedTransformer;
// - every number option refuses text that is no number, NaN and infinity.
#pragma once

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <utility>
#include <vector>

namespace intgrid::cli {

// A bad value of a command-line option found after parsing (two options that do not fit
// together, a value a golden check refuses): main prints "intgrid: error: " + what() and a hint
// to the subcommand's help, and exits 2. what() names the option by its flag.
class OptionError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Throws OptionError("FLAG: MESSAGE").
[[noreturn]] inline void bad_option(const std::string& flag, const std::string& message) {
  throw OptionError(flag + ": " + message);
}

// A number as the messages print it: the shortest text that reads back the same.
inline std::string option_number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char digits[32];
  const auto [end, error] = std::to_chars(digits, digits + sizeof digits, v);
  return error == std::errc() ? std::string(digits, end) : std::to_string(v);
}

// ---- Field names of the golden model -> flags.

// A field of a golden-model structure (as its checks name it) and the flag that sets it.
struct FieldFlag {
  std::string_view field;
  std::string_view flag;
};
using FieldFlags = std::vector<FieldFlag>;

namespace detail {

inline bool is_word_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
}

// Whether `field` occurs in `text` at `at` as a whole word.
inline bool word_at(std::string_view text, std::size_t at, std::string_view field) {
  if (text.substr(at, field.size()) != field) return false;
  const std::size_t end = at + field.size();
  return (at == 0 || !is_word_char(text[at - 1])) &&
         (end == text.size() || !is_word_char(text[end]));
}

}  // namespace detail

// Rethrows a golden check's message as an OptionError naming flags instead of fields: the
// message's leading field ("pose_res must be ...", "obstacles.count: must be ...") becomes
// "--pose-cell: must be ...", and every other field of the table it mentions becomes its flag. A
// message that starts with no field of the table is no bad option: it is rethrown as it is (an
// internal error, exit 1).
[[noreturn]] inline void rethrow_naming_flags(const std::invalid_argument& e,
                                              const FieldFlags& table) {
  if (const auto* option_error = dynamic_cast<const OptionError*>(&e)) throw *option_error;
  const std::string_view what = e.what();
  const FieldFlag* lead = nullptr;
  for (const FieldFlag& f : table)
    if (detail::word_at(what, 0, f.field) && (!lead || f.field.size() > lead->field.size()))
      lead = &f;
  if (!lead) throw e;
  std::string_view rest = what.substr(lead->field.size());
  while (!rest.empty() && (rest.front() == ':' || rest.front() == ' ')) rest.remove_prefix(1);
  std::string message;
  for (std::size_t i = 0; i < rest.size();) {
    const FieldFlag* hit = nullptr;
    for (const FieldFlag& f : table)
      if (detail::word_at(rest, i, f.field) && (!hit || f.field.size() > hit->field.size()))
        hit = &f;
    if (hit) {
      message += hit->flag;
      i += hit->field.size();
    } else {
      message += rest[i++];
    }
  }
  bad_option(std::string(lead->flag), message);
}

// Runs f; a std::invalid_argument it throws is rethrown by rethrow_naming_flags(table).
template <class F>
decltype(auto) naming_flags(const FieldFlags& table, F&& f) {
  try {
    return std::forward<F>(f)();
  } catch (const std::invalid_argument& e) {
    rethrow_naming_flags(e, table);
  }
}

// ---- Validators with short descriptions.

namespace detail {

// The whole of text as a double (NaN and infinity included), or nothing.
inline std::optional<double> parse_real(const std::string& text) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front()))) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) return std::nullopt;
  return v;
}

// The whole of text as a decimal whole number, or nothing.
template <class T>
std::optional<T> parse_whole(const std::string& text) {
  T v{};
  const char* first = text.data();
  if (!text.empty() && text.front() == '+') ++first;
  const auto [end, error] = std::from_chars(first, text.data() + text.size(), v);
  if (text.empty() || first == text.data() + text.size() || error != std::errc() ||
      end != text.data() + text.size())
    return std::nullopt;
  return v;
}

}  // namespace detail

// A finite number for which ok(v) holds; `what` says which ("> 0", "in [0, 1]"), and the help
// shows `description`.
template <class Predicate>
CLI::Validator real_number(std::string description, std::string what, Predicate ok) {
  return CLI::Validator(
      [what, ok](std::string& text) -> std::string {
        const std::optional<double> v = detail::parse_real(text);
        if (!v) return "must be a number " + what + ", got '" + text + "'";
        if (!std::isfinite(*v)) return "must be a finite number " + what + ", got " + text;
        if (!ok(*v)) return "must be " + what + ", got " + text;
        return {};
      },
      std::move(description));
}

// Any finite number.
inline CLI::Validator finite() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const std::optional<double> v = detail::parse_real(text);
        if (!v) return "must be a number, got '" + text + "'";
        if (!std::isfinite(*v)) return "must be a finite number, got " + text;
        return {};
      },
      "");
}

inline CLI::Validator positive() {
  return real_number("> 0", "> 0", [](double v) { return v > 0.0; });
}

inline CLI::Validator non_negative() {
  return real_number(">= 0", ">= 0", [](double v) { return v >= 0.0; });
}

// lo <= v <= hi, or with open ends lo < v, v < hi.
inline CLI::Validator real_range(double lo, double hi, bool open_lo = false, bool open_hi = false) {
  const std::string interval = std::string(open_lo ? "(" : "[") + option_number(lo) + ", " +
                               option_number(hi) + (open_hi ? ")" : "]");
  return real_number(interval, "in " + interval, [=](double v) {
    return (open_lo ? v > lo : v >= lo) && (open_hi ? v < hi : v <= hi);
  });
}

inline CLI::Validator probability() {
  return real_range(0.0, 1.0);
}

// A decimal whole number in lo..hi, rewritten in plain decimal for CLI11's conversion (which
// would read a leading 0 as octal).
inline CLI::Validator whole_range(long long lo, long long hi) {
  const std::string range = std::to_string(lo) + ".." + std::to_string(hi);
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        const std::optional<long long> v = detail::parse_whole<long long>(text);
        if (!v || *v < lo || *v > hi)
          return "must be a whole number in " + range + ", got '" + text + "'";
        text = std::to_string(*v);
        return {};
      },
      range);
}

// A decimal whole number >= lo.
inline CLI::Validator whole_at_least(long long lo) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        const std::optional<long long> v = detail::parse_whole<long long>(text);
        if (!v || *v < lo)
          return "must be a whole number >= " + std::to_string(lo) + ", got '" + text + "'";
        text = std::to_string(*v);
        return {};
      },
      ">= " + std::to_string(lo));
}

// A seed: a decimal whole number from 0 to 2^64 - 1.
inline CLI::Validator seed_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const std::optional<std::uint64_t> v = detail::parse_whole<std::uint64_t>(text);
        if (!v || (!text.empty() && text.front() == '-'))
          return "must be a whole number from 0 to 2^64 - 1, got '" + text + "'";
        text = std::to_string(*v);
        return {};
      },
      "0..2^64-1");
}

// One of `names`, whatever the case; the help shows the names as the option's type (a|b|c).
inline std::string choice_names(const std::vector<std::string>& names, const char* separator) {
  std::string joined;
  for (const std::string& n : names) joined += (joined.empty() ? "" : separator) + n;
  return joined;
}

inline CLI::Validator one_of(std::vector<std::string> names) {
  return CLI::Validator(
      [names](std::string& text) -> std::string {
        std::string lower = text;
        std::transform(lower.begin(), lower.end(), lower.begin(),
                       [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        if (std::find(names.begin(), names.end(), lower) == names.end())
          return "must be one of " + choice_names(names, ", ") + "; got '" + text + "'";
        text = lower;
        return {};
      },
      "");
}

// An option whose value is one of named values (an enum): `--arith int|float`.
template <class T>
CLI::Option* add_choice_option(CLI::App& cmd, const std::string& name, T& value,
                               std::vector<std::pair<std::string, T>> choices,
                               const std::string& help) {
  static_assert(std::is_enum_v<T>);
  std::vector<std::string> names;
  for (const auto& c : choices) names.push_back(c.first);
  CLI::Validator to_value(
      [choices](std::string& text) -> std::string {
        for (const auto& [n, v] : choices)
          if (n == text) {
            text = std::to_string(static_cast<long long>(v));
            return {};
          }
        return "unknown value '" + text + "'";
      },
      "");
  // one_of first (lower case, a message naming the choices), then the name's value.
  return cmd.add_option(name, value, help)
      ->transform(to_value)
      ->transform(one_of(names))
      ->type_name(choice_names(names, "|"));
}

}  // namespace intgrid::cli
