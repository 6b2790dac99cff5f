#include "intgrid/kernel/table_export.hpp"

#include <cctype>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace intgrid::kernel {
namespace {

// One hex word per line, `bits` wide (two's complement for negative values).
std::string mem_file(const std::vector<std::int64_t>& words, int bits, const std::string& what) {
  std::ostringstream s;
  const int digits = (bits + 3) / 4;
  const std::uint64_t mask = bits >= 64 ? ~0ull : ((std::uint64_t{1} << bits) - 1);
  s << "// " << what << ": " << words.size() << " words of " << bits << " bits\n";
  for (const std::int64_t w : words) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%0*llx\n", digits,
                  static_cast<unsigned long long>(static_cast<std::uint64_t>(w) & mask));
    s << buf;
  }
  return s.str();
}

template <class T>
std::string cpp_array(const char* type, const char* name, const std::vector<T>& v) {
  std::ostringstream s;
  s << "  static constexpr std::array<" << type << ", " << v.size() << "> " << name << "{";
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i % 12 == 0) s << "\n     ";
    s << ' ' << static_cast<long long>(v[i]) << (i + 1 < v.size() ? "," : "");
  }
  s << "};\n";
  return s.str();
}

std::string upper_case(std::string s) {
  for (char& ch : s) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  return s;
}

// cone16 -> SectoralIsmCone16, a_b -> SectoralIsmAB.
std::string struct_name(const std::string& name) {
  std::string out = "SectoralIsm";
  bool up = true;
  for (const char ch : name) {
    if (ch == '_') {
      up = true;
      continue;
    }
    out += up ? static_cast<char>(std::toupper(static_cast<unsigned char>(ch))) : ch;
    up = false;
  }
  return out;
}

}  // namespace

std::vector<GeneratedFile> ism_table_files(const IsmHwConfig& cfg,
                                           const std::filesystem::path& mem_dir) {
  const std::string name = cfg.name;
  const IsmKernelTables k = make_ism_hw_kernel(cfg);
  const IsmHwDerived d = derive_ism_hw(k, cfg.bits);
  const std::vector<int> buckets = threshold_buckets(k, d);
  const std::string base = "sectoral_ism_" + name;
  const int C = k.classes, V = k.conditions;
  std::vector<GeneratedFile> out;

  // ROM files, in kIsmRomNames order. log_weight is stored class-major ([c * V + v], the order
  // the sum pipeline reads it) with a zero flag above the value; log_add holds phi - 1 (every
  // phi >= 1).
  const auto add_mem = [&](const char* rom, std::string text) {
    out.push_back({base + "_" + rom + ".mem", std::move(text)});
  };
  {
    std::vector<std::int64_t> w(k.quad_coef.begin(), k.quad_coef.end());
    add_mem("quad_coef", mem_file(w, d.coef_bits, "quad_coef[(r-1)*C + c]"));
  }
  {
    std::vector<std::int64_t> w(k.log_norm.begin(), k.log_norm.end());
    add_mem("log_norm", mem_file(w, d.norm_bits, "log_norm[(r-1)*C + c]"));
  }
  {
    std::vector<std::int64_t> w;
    for (int c = 0; c < C; ++c)
      for (int v = 0; v < V; ++v) {
        const std::int32_t x = k.log_weight[std::size_t(v) * std::size_t(C) + std::size_t(c)];
        w.push_back(x == IsmKernelTables::kLogZero
                        ? (std::int64_t{1} << d.weight_bits)
                        : (x & ((std::int64_t{1} << d.weight_bits) - 1)));
      }
    add_mem("log_weight", mem_file(w, d.weight_bits + 1, "{zero, log_weight[v*C + c]} at c*V + v"));
  }
  {
    std::vector<std::int64_t> w;
    for (const std::uint16_t phi : k.log_add) w.push_back(std::int64_t{phi} - 1);
    add_mem("log_add", mem_file(w, d.phi_bits, "phi(d) - 1"));
  }
  {
    std::vector<std::int64_t> w(k.thresholds.begin(), k.thresholds.end());
    add_mem("thresholds", mem_file(w, d.thr_bits, "thresholds[n - 1]"));
  }
  {
    std::vector<std::int64_t> w(buckets.begin(), buckets.end());
    add_mem("threshold_bucket", mem_file(w, d.bucket_bits, "thresholds below b << bucket_shift"));
  }

  // The top's parameters, in one list for the three formats: the configuration and the widths
  // that depend on the tables' values. The top derives the rest (rtl/sectoral_ism_pkg.sv).
  const std::vector<std::pair<std::string, long long>> params = {
      {"READING_W", kIsmReadingBits},
      {"RINGS", k.grid.rings},
      {"BINS", k.grid.bins},
      {"SECTORS", k.grid.sectors},
      {"CLASSES", C},
      {"WINDOW", k.window_cells},
      {"IDX_W", d.index_bits},
      {"READING_FRAC", k.format.reading_frac_bits},
      {"LOG_FRAC", k.format.log_frac_bits},
      {"QUAD_SHIFT", d.quad_shift},
      {"LOG_W", d.log_bits},
      {"COEF_W", d.coef_bits},
      {"NORM_W", d.norm_bits},
      {"WEIGHT_W", d.weight_bits},
      {"PHI_N", static_cast<long long>(k.log_add.size())},
      {"PHI_W", d.phi_bits},
      {"THR_W", d.thr_bits},
      {"BUCKET_SHIFT", d.bucket_shift},
      {"BUCKET_N", d.bucket_count},
  };
  std::vector<std::pair<std::string, std::string>> files;
  for (const char* rom : kIsmRomNames)
    files.emplace_back(upper_case(rom) + "_FILE",
                       (mem_dir / (base + "_" + rom + ".mem")).lexically_normal().string());

  std::ostringstream vc, svh, ys;
  vc << "// Verilator parameters of sectoral_ism, configuration " << name << "\n";
  const std::string upper = upper_case(name);
  svh << "// Parameters of sectoral_ism, configuration " << name
      << ": sectoral_ism #(`SECTORAL_ISM_" << upper << "_PARAMS) u (...);\n"
      << "`define SECTORAL_ISM_" << upper << "_PARAMS \\\n";
  ys << "# Parameters of sectoral_ism, configuration " << name << "\n";
  for (const auto& [key, value] : params) {
    vc << "-G" << key << "=" << value << "\n";
    svh << "  ." << key << "(" << value << "), \\\n";
    ys << "chparam -set " << key << " " << value << " sectoral_ism\n";
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    const auto& [key, path] = files[i];
    vc << "-G" << key << "=\\\"" << path << "\\\"\n";
    svh << "  ." << key << "(\"" << path << "\")" << (i + 1 < files.size() ? ", \\\n" : "\n");
    ys << "chparam -set " << key << " \"" << path << "\" sectoral_ism\n";
  }
  out.push_back({base + ".vc", vc.str()});
  out.push_back({base + ".svh", svh.str()});
  out.push_back({base + ".ys", ys.str()});

  // The constexpr configuration of the C++ layers: golden's tables as they are (log_weight
  // in golden's [v * classes + c] order, log 0 as kLogZero, phi itself) and the derived
  // constants.
  std::ostringstream h;
  const std::string sname = struct_name(name);
  h << "// Generated by testbench/ism_kernel_export.cpp from golden's make_ism_kernel: the "
       "sectoral\n"
    << "// ISM hardware configuration " << name << ". Do not edit.\n"
    << "#pragma once\n\n#include <array>\n#include <cstdint>\n\nnamespace intgrid::hw {\n\n"
    << "struct " << sname << " {\n"
    << "  static constexpr const char* name = \"" << name << "\";\n"
    << "  static constexpr int rings = " << k.grid.rings << ";\n"
    << "  static constexpr int bins = " << k.grid.bins << ";\n"
    << "  static constexpr int sectors = " << k.grid.sectors << ";\n"
    << "  static constexpr int bins_per_sector = " << k.grid.bins_per_sector() << ";\n"
    << "  static constexpr int classes = " << C << ";\n"
    << "  static constexpr int conditions = " << V << ";\n"
    << "  static constexpr int window_cells = " << k.window_cells << ";\n"
    << "  static constexpr std::uint32_t reach = " << k.reach << ";\n"
    << "  static constexpr int max_index = " << k.max_index << ";\n"
    << "  static constexpr int index_bits = " << d.index_bits << ";\n"
    << "  static constexpr int reading_bits = " << kIsmReadingBits << ";\n"
    << "  static constexpr int reading_frac_bits = " << k.format.reading_frac_bits << ";\n"
    << "  static constexpr int log_frac_bits = " << k.format.log_frac_bits << ";\n"
    << "  static constexpr int quad_coef_frac_bits = " << k.format.quad_coef_frac_bits << ";\n"
    << "  static constexpr int quad_shift = " << d.quad_shift << ";\n"
    << "  static constexpr std::int32_t log_zero = " << IsmKernelTables::kLogZero << ";\n"
    << "  // RTL word widths (bits) and schedule constants\n"
    << "  static constexpr int log_bits = " << d.log_bits << ";\n"
    << "  static constexpr std::int32_t log_bound = " << d.log_bound << ";\n"
    << "  static constexpr int e_bits = " << d.e_bits << ";\n"
    << "  static constexpr int sq_bits = " << d.sq_bits << ";\n"
    << "  static constexpr int coef_bits = " << d.coef_bits << ";\n"
    << "  static constexpr int mul_b_bits = " << d.mul_b_bits << ";\n"
    << "  static constexpr int mul_digit_bits = " << d.mul_digit_bits << ";\n"
    << "  static constexpr int mul_digits = " << d.mul_digits << ";\n"
    << "  static constexpr int phi_bits = " << d.phi_bits << ";\n"
    << "  static constexpr int phi_addr_bits = " << d.phi_addr_bits << ";\n"
    << "  static constexpr int bucket_shift = " << d.bucket_shift << ";\n"
    << "  static constexpr int bucket_count = " << d.bucket_count << ";\n"
    << "  static constexpr int bucket_bits = " << d.bucket_bits << ";\n";
  h << cpp_array("std::uint32_t", "quad_coef", k.quad_coef);
  h << cpp_array("std::int32_t", "log_norm", k.log_norm);
  h << cpp_array("std::int32_t", "log_weight", k.log_weight);
  h << cpp_array("std::uint16_t", "log_add", k.log_add);
  h << cpp_array("std::int32_t", "thresholds", k.thresholds);
  h << cpp_array("std::uint16_t", "threshold_bucket", buckets);
  h << "};\n\n}  // namespace intgrid::hw\n";
  out.push_back({base + "_config.hpp", h.str()});
  return out;
}

}  // namespace intgrid::kernel
