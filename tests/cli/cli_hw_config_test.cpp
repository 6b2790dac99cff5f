// `intgrid hw-config`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "cli_fixture.hpp"
#include "data_dir.hpp"

namespace {

using namespace intgrid::cli_test;

// `intgrid hw-config`: a configuration folder of the sectoral ISM's RTL. That its bytes are
// golden's is the hw test sectoral_ism_config_* (the committed cone16 and cone12); here the
// folder's files, the ROM paths its parameter files give, and the errors.
TEST_F(Cli, HwConfigWritesTheRomsAndTheParametersNamingThem) {
  const fs::path out = dir_ / "config" / "my_sensor";
  const CliRun r = run("hw-config --name my_sensor --out " + out.string() +
                       " --fov 60 --rings 24 --bins 12 --sectors 2 --cell 0.1");
  ASSERT_EQ(r.status, 0) << r.output;
  std::vector<std::string> names;
  for (const fs::directory_entry& e : fs::directory_iterator(out))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  const std::vector<std::string> want = {"sectoral_ism_my_sensor.svh",
                                         "sectoral_ism_my_sensor.vc",
                                         "sectoral_ism_my_sensor.ys",
                                         "sectoral_ism_my_sensor_log_add.mem",
                                         "sectoral_ism_my_sensor_log_norm.mem",
                                         "sectoral_ism_my_sensor_log_weight.mem",
                                         "sectoral_ism_my_sensor_quad_coef.mem",
                                         "sectoral_ism_my_sensor_threshold_bucket.mem",
                                         "sectoral_ism_my_sensor_thresholds.mem"};
  EXPECT_EQ(names, want);
  std::ifstream vc(out / "sectoral_ism_my_sensor.vc");
  const std::string text((std::istreambuf_iterator<char>(vc)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("-GBINS=12\n"), std::string::npos) << text;
  EXPECT_NE(text.find("-GSECTORS=2\n"), std::string::npos) << text;
  EXPECT_NE(text.find("-GLOG_ADD_FILE=\\\"config/my_sensor/sectoral_ism_my_sensor_log_add.mem\\\""),
            std::string::npos)
      << text;
  EXPECT_EQ(text.find(dir_.string()), std::string::npos) << "no absolute path: " << text;

  const CliRun moved =
      run("hw-config --name my_sensor --rom-dir roms --out " + (dir_ / "moved").string());
  ASSERT_EQ(moved.status, 0) << moved.output;
  std::ifstream ys(dir_ / "moved" / "sectoral_ism_my_sensor.ys");
  const std::string script((std::istreambuf_iterator<char>(ys)), std::istreambuf_iterator<char>());
  EXPECT_NE(script.find("chparam -set LOG_ADD_FILE \"roms/sectoral_ism_my_sensor_log_add.mem\""),
            std::string::npos)
      << script;
}

TEST_F(Cli, HwConfigRefusesWhatTheKernelCannotHoldNamingTheOption) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--bins 15 --sectors 4", "--bins: 15 is no multiple of --sectors 4"},
      {"--sectors 17", "--sectors"},
      {"--rings 300", "--rings"},  // reach (300 + window) << 8 passes the 16-bit reading port
      {"--sigma 50 --cell 0.01", "--sigma"},
      // the quadratic term's limit: led by --cell, and the --k-d that the user set is named too
      {"--k-d 10", "--k-d move it too"},
      {"--bits 1", "--bits"},
      {"--eps 0.5", "--eps"},
      {"--fov 0", "--fov"},
      {"--rom-dir /abs/roms", "--rom-dir"},
  };
  const fs::path out = dir_ / "bad";
  for (const auto& [options, keyword] : cases) {
    SCOPED_TRACE(options);
    const CliRun r = run("hw-config --name bad --out " + out.string() + " " + options);
    expect_error(r, keyword);
    EXPECT_EQ(r.status, 2);
    EXPECT_FALSE(fs::exists(out));
  }
  for (const char* name : {"Cone", "1st", "my-sensor", "a/b"}) {
    SCOPED_TRACE(name);
    const CliRun r = run(std::string("hw-config --name ") + name + " --out " + out.string());
    expect_error(r, "--name");
    EXPECT_EQ(r.status, 2);
  }
}

}  // namespace
