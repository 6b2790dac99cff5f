// Errors of the sectoral ISM kernel's configuration (`ism --fov ... --arith int`, `hw-config`)
// named by options: a golden check's message names a field first ("rings (R) must be ...") and
// becomes that option's error; the kernel's own limits ("ISM kernel: ...", "sectoral ISM
// hardware: ...") name none, and each is named by the option that moves it most directly, of
// those the command has.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "cli/options.hpp"

namespace intgrid::cli {

[[noreturn]] inline void rethrow_naming_kernel_options(const std::invalid_argument& e,
                                                       const FieldFlags& flags) {
  if (const auto* option_error = dynamic_cast<const OptionError*>(&e)) throw *option_error;
  std::string message = e.what();
  for (const std::string_view prefix : {"ISM kernel: ", "sectoral ISM hardware: "})
    if (message.starts_with(prefix)) message.erase(0, prefix.size());
  try {
    rethrow_naming_flags(std::invalid_argument(message), flags);
  } catch (const OptionError&) {
    throw;
  } catch (const std::invalid_argument&) {
    // no field leads: one of the kernel's limits below
  }
  // The message's words, the option that moves the limit most directly, and the others that
  // move it too (named after the message, so that a user who set one of them finds it).
  struct Limit {
    std::string_view needle, flag;
    std::vector<std::string_view> also;
  };
  static const Limit kLimits[] = {
      {"sigma", "--sigma", {}},
      {"reading fraction", "--reading-frac", {}},
      {"log fraction", "--log-frac", {}},
      {"quadratic coefficient fraction", "--quad-coef-frac", {}},
      {"reading", "--rings", {}},  // reach, (R + window) << reading_frac, must fit the port
      // bits a cell^2 at the least sigma times the window, which the spread of sigma widens
      {"quadratic term", "--cell", {"--sigma", "--k-d"}},
      {"log", "--rings", {}},  // the ring prior (R - 1) * A grows the log words
      {"multiplier", "--sectors", {}},
      {"conditions", "--sectors", {}}};
  const auto has = [&](std::string_view flag) {
    for (const FieldFlag& f : flags)
      if (f.flag == flag) return true;
    return false;
  };
  for (const Limit& limit : kLimits) {
    if (!has(limit.flag) || message.find(limit.needle) == std::string::npos) continue;
    std::string also;
    for (const std::string_view flag : limit.also)
      if (has(flag)) also += std::string(also.empty() ? "" : ", ") + std::string(flag);
    bad_option(std::string(limit.flag), "the kernel cannot hold this configuration: " + message +
                                            (also.empty() ? "" : " (" + also + " move it too)"));
  }
  throw std::invalid_argument(message);
}

}  // namespace intgrid::cli
