#include "cli/commands.hpp"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

namespace intgrid::cli {

void print_json(const nlohmann::json& j) {
  std::printf("%s\n", j.dump(2).c_str());
}

CLI::Option* add_arithmetic_option(CLI::App& cmd, core::Arithmetic& arithmetic,
                                   const std::string& help) {
  return add_choice_option(
      cmd, "--arith", arithmetic,
      {{"int", core::Arithmetic::integer}, {"float", core::Arithmetic::floating}}, help);
}

void check_reading_option(double z) {
  if (!(z >= 0.0) || !std::isfinite(z))
    bad_option("--z", "must be a finite distance >= 0 (m), got " + option_number(z));
}

nlohmann::json stats_json(const core::InsertionStats& s) {
  return {{"scans", s.scans},
          {"readings", s.readings},
          {"inserted", s.inserted},
          {"skipped",
           {{"zero", s.zero},
            {"not_finite", s.not_finite},
            {"negative", s.negative},
            {"at_or_over_max_range", s.at_or_over_max}}},
          {"cells_updated", s.cells_updated}};
}

nlohmann::json agreement_json(const core::MapAgreement& a) {
  return {{"ours_occupied", a.ours_occupied},
          {"reference_occupied", a.reference_occupied},
          {"ours_near_reference", a.ours_near_reference},
          {"reference_near_ours", a.reference_near_ours}};
}

// Options shared by `map` and `demo`: the sensor model and the integer set.
void add_model_options(CLI::App& cmd, MapJobOptions& o) {
  cmd.add_option("--sigma", o.model.sigma0, "sensor standard deviation at distance 0 (m)")
      ->check(positive())
      ->capture_default_str();
  cmd.add_option("--k-d", o.model.k_d, "relative growth of sigma per metre")
      ->check(non_negative())
      ->capture_default_str();
  cmd.add_option("--bits", o.bits, "S_eps index width")
      ->transform(whole_range(2, 16))
      ->capture_default_str();
  cmd.add_option("--levels", o.levels, "eps such that the ISM's Pmax is this many index steps")
      ->transform(whole_at_least(1))
      ->capture_default_str();
  cmd.add_option("--eps", o.eps, "eps of S_eps (overrides --levels)")
      ->check(real_range(0.0, 0.5, true, true));
  add_choice_option(cmd, "--veto-bound", o.veto,
                    {{"claim", core::VetoBound::strongest_claim}, {"none", core::VetoBound::none}},
                    "bound each reading's empty indices by its strongest occupied index")
      ->default_str("claim");
}

}  // namespace intgrid::cli
