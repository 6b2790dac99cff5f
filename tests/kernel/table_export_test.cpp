// The text of the sectoral ISM kernel's table files (intgrid/kernel/table_export.hpp) read back:
// every .mem file holds exactly golden's table, one word a line of the width it states and the
// RTL's parameters name; the three parameter files agree and name the .mem files.
#include "intgrid/kernel/table_export.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "intgrid/kernel/hardware_configs.hpp"

using namespace intgrid::kernel;

namespace {

const std::filesystem::path kMemDir = "/tables";

struct MemFile {
  std::size_t stated_words = 0;
  int stated_bits = 0;
  std::vector<std::string> lines;  // the hex words, as written
};

// "// what: N words of B bits" then one word a line.
MemFile parse_mem(const std::string& text) {
  MemFile m;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  const std::size_t colon = line.rfind(": ");
  EXPECT_EQ(line.rfind("// ", 0), 0u) << line;
  EXPECT_NE(colon, std::string::npos) << line;
  std::istringstream header(line.substr(colon + 2));
  std::string words, of, bits;
  header >> m.stated_words >> words >> of >> m.stated_bits >> bits;
  EXPECT_EQ(words + " " + of + " " + bits, "words of bits") << line;
  while (std::getline(in, line)) m.lines.push_back(line);
  return m;
}

// The words of a .mem file: each exactly ceil(B / 4) hex digits and below 2^B.
std::vector<std::uint64_t> words_of(const MemFile& m, const std::string& what) {
  std::vector<std::uint64_t> out;
  const std::size_t digits = std::size_t(m.stated_bits + 3) / 4;
  for (const std::string& w : m.lines) {
    EXPECT_EQ(w.size(), digits) << what << ": '" << w << "'";
    EXPECT_EQ(w.find_first_not_of("0123456789abcdef"), std::string::npos) << what << ": " << w;
    const std::uint64_t v = std::stoull(w, nullptr, 16);
    EXPECT_LT(v, std::uint64_t{1} << m.stated_bits) << what << ": " << w;
    out.push_back(v);
  }
  return out;
}

std::int64_t sign_extend(std::uint64_t v, int bits) {
  const std::uint64_t m = std::uint64_t{1} << (bits - 1);
  return static_cast<std::int64_t>(v ^ m) - static_cast<std::int64_t>(m);
}

std::map<std::string, std::string> by_name(const std::vector<GeneratedFile>& files) {
  std::map<std::string, std::string> out;
  for (const GeneratedFile& f : files) EXPECT_TRUE(out.emplace(f.name, f.text).second) << f.name;
  return out;
}

class TableExport : public ::testing::TestWithParam<const char*> {};

TEST_P(TableExport, EveryMemFileHoldsGoldensTableInTheStatedWidth) {
  const IsmHwConfig& cfg = ism_hw_config(GetParam());
  const IsmKernelTables k = make_ism_hw_kernel(cfg);
  const IsmHwDerived d = derive_ism_hw(k, cfg.bits);
  const std::vector<int> buckets = threshold_buckets(k, d);
  const std::map<std::string, std::string> files = by_name(ism_table_files(cfg, kMemDir));
  const std::string base = std::string("sectoral_ism_") + cfg.name + "_";
  const auto mem = [&](const char* rom, std::size_t size, int bits) {
    const auto it = files.find(base + rom + ".mem");
    EXPECT_NE(it, files.end()) << rom;
    if (it == files.end()) return std::vector<std::uint64_t>{};
    const MemFile m = parse_mem(it->second);
    EXPECT_EQ(m.stated_words, size) << rom;
    EXPECT_EQ(m.lines.size(), size) << rom;
    EXPECT_EQ(m.stated_bits, bits) << rom;
    return words_of(m, rom);
  };

  const std::vector<std::uint64_t> coef = mem("quad_coef", k.quad_coef.size(), d.coef_bits);
  ASSERT_EQ(coef.size(), k.quad_coef.size());
  for (std::size_t i = 0; i < coef.size(); ++i) EXPECT_EQ(coef[i], k.quad_coef[i]) << i;

  const std::vector<std::uint64_t> norm = mem("log_norm", k.log_norm.size(), d.norm_bits);
  ASSERT_EQ(norm.size(), k.log_norm.size());
  for (std::size_t i = 0; i < norm.size(); ++i)
    EXPECT_EQ(sign_extend(norm[i], d.norm_bits), k.log_norm[i]) << i;

  // Class-major, a zero flag above the weight.
  const std::vector<std::uint64_t> weight =
      mem("log_weight", k.log_weight.size(), d.weight_bits + 1);
  ASSERT_EQ(weight.size(), k.log_weight.size());
  const std::size_t C = std::size_t(k.classes), V = std::size_t(k.conditions);
  for (std::size_t c = 0; c < C; ++c)
    for (std::size_t v = 0; v < V; ++v) {
      const std::uint64_t w = weight[c * V + v];
      const std::int32_t want = k.log_weight[v * C + c];
      const bool zero = (w >> d.weight_bits) != 0;
      EXPECT_EQ(zero, want == IsmKernelTables::kLogZero) << c << ", " << v;
      if (!zero) {
        const std::uint64_t value = w & ((std::uint64_t{1} << d.weight_bits) - 1);
        EXPECT_EQ(sign_extend(value, d.weight_bits), want) << c << ", " << v;
      }
    }

  const std::vector<std::uint64_t> phi = mem("log_add", k.log_add.size(), d.phi_bits);
  ASSERT_EQ(phi.size(), k.log_add.size());
  for (std::size_t i = 0; i < phi.size(); ++i) EXPECT_EQ(phi[i] + 1, k.log_add[i]) << i;

  const std::vector<std::uint64_t> thr = mem("thresholds", k.thresholds.size(), d.thr_bits);
  ASSERT_EQ(thr.size(), k.thresholds.size());
  for (std::size_t i = 0; i < thr.size(); ++i)
    EXPECT_EQ(thr[i], std::uint64_t(k.thresholds[i])) << i;

  ASSERT_EQ(buckets.size(), std::size_t(d.bucket_count));
  const std::vector<std::uint64_t> bucket = mem("threshold_bucket", buckets.size(), d.bucket_bits);
  ASSERT_EQ(bucket.size(), buckets.size());
  for (std::size_t i = 0; i < bucket.size(); ++i)
    EXPECT_EQ(bucket[i], std::uint64_t(buckets[i])) << i;
}

// "text", built by appending (GCC 12 warns falsely on "\"" + std::string).
std::string quoted(const std::string& text) {
  std::string out(1, '"');
  out += text;
  out += '"';
  return out;
}

// NAME -> value of "-GNAME=value" lines, "  .NAME(value), \" lines and "chparam -set NAME value
// sectoral_ism" lines.
std::map<std::string, std::string> vc_params(const std::string& text) {
  std::map<std::string, std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("-G", 0) != 0) continue;
    const std::size_t eq = line.find('=');
    std::string value = line.substr(eq + 1);
    if (value.rfind("\\\"", 0) == 0) value = quoted(value.substr(2, value.size() - 4));
    out[line.substr(2, eq - 2)] = value;
  }
  return out;
}
std::map<std::string, std::string> svh_params(const std::string& text) {
  std::map<std::string, std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("  .", 0) != 0) continue;
    const std::size_t open = line.find('('), close = line.rfind(')');
    out[line.substr(3, open - 3)] = line.substr(open + 1, close - open - 1);
  }
  return out;
}
std::map<std::string, std::string> ys_params(const std::string& text) {
  std::map<std::string, std::string> out;
  std::istringstream in(text);
  const std::string prefix = "chparam -set ", suffix = " sectoral_ism";
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(prefix, 0) != 0) continue;
    EXPECT_EQ(line.substr(line.size() - suffix.size()), suffix) << line;
    const std::string rest =
        line.substr(prefix.size(), line.size() - prefix.size() - suffix.size());
    const std::size_t space = rest.find(' ');
    out[rest.substr(0, space)] = rest.substr(space + 1);
  }
  return out;
}

TEST_P(TableExport, ParameterFilesAgreeAndNameTheMemFiles) {
  const IsmHwConfig& cfg = ism_hw_config(GetParam());
  const IsmKernelTables k = make_ism_hw_kernel(cfg);
  const IsmHwDerived d = derive_ism_hw(k, cfg.bits);
  const std::map<std::string, std::string> files = by_name(ism_table_files(cfg, kMemDir));
  const std::string base = std::string("sectoral_ism_") + cfg.name;
  ASSERT_EQ(files.size(), 10u);
  for (const char* ext : {".vc", ".svh", ".ys", "_config.hpp"})
    ASSERT_EQ(files.count(base + ext), 1u) << ext;

  const std::map<std::string, std::string> vc = vc_params(files.at(base + ".vc"));
  EXPECT_EQ(vc, svh_params(files.at(base + ".svh")));
  EXPECT_EQ(vc, ys_params(files.at(base + ".ys")));
  EXPECT_EQ(vc.size(), 19u + std::size(kIsmRomNames));
  // A few parameters the RTL sizes its words and ROMs by.
  EXPECT_EQ(vc.at("RINGS"), std::to_string(k.grid.rings));
  EXPECT_EQ(vc.at("IDX_W"), std::to_string(cfg.bits));
  EXPECT_EQ(vc.at("COEF_W"), std::to_string(d.coef_bits));
  EXPECT_EQ(vc.at("PHI_N"), std::to_string(k.log_add.size()));
  EXPECT_EQ(vc.at("BUCKET_N"), std::to_string(d.bucket_count));
  for (const char* rom : kIsmRomNames) {
    std::string key = rom;
    for (char& ch : key) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    const std::string name = base + "_" + rom + ".mem";
    EXPECT_EQ(files.count(name), 1u) << name;
    EXPECT_EQ(vc.at(key + "_FILE"), quoted((kMemDir / name).string())) << key;
  }
}

TEST_P(TableExport, ConfigHeaderHoldsEveryTableAtItsSize) {
  const IsmHwConfig& cfg = ism_hw_config(GetParam());
  const IsmKernelTables k = make_ism_hw_kernel(cfg);
  const IsmHwDerived d = derive_ism_hw(k, cfg.bits);
  const std::map<std::string, std::string> files = by_name(ism_table_files(cfg, kMemDir));
  const std::string& h = files.at(std::string("sectoral_ism_") + cfg.name + "_config.hpp");
  const auto array = [](const char* type, std::size_t n, const char* name) {
    return "static constexpr std::array<" + std::string(type) + ", " + std::to_string(n) + "> " +
           name + "{";
  };
  EXPECT_NE(h.find(array("std::uint32_t", k.quad_coef.size(), "quad_coef")), std::string::npos);
  EXPECT_NE(h.find(array("std::int32_t", k.log_norm.size(), "log_norm")), std::string::npos);
  EXPECT_NE(h.find(array("std::int32_t", k.log_weight.size(), "log_weight")), std::string::npos);
  EXPECT_NE(h.find(array("std::uint16_t", k.log_add.size(), "log_add")), std::string::npos);
  EXPECT_NE(h.find(array("std::int32_t", k.thresholds.size(), "thresholds")), std::string::npos);
  EXPECT_NE(h.find(array("std::uint16_t", std::size_t(d.bucket_count), "threshold_bucket")),
            std::string::npos);
  EXPECT_NE(h.find("  static constexpr int index_bits = " + std::to_string(cfg.bits) + ";\n"),
            std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Configs, TableExport, ::testing::Values("cone16", "cone12"),
                         [](const ::testing::TestParamInfo<const char*>& param) {
                           return std::string(param.param);
                         });

}  // namespace
