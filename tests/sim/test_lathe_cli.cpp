// avrmotion-sim's spindle options, as a user runs them: a 5 mm pass on a
// quadrature encoder ends on its length (round(5 x 800 / 3.175) = 1260
// steps, towards the chuck), a one-channel disc too; bad spindle options and
// spindle options on a board without a spindle are usage errors (2).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "sim_fixture.h"

namespace {

using simtest::slurp;
using simtest::temp_path;

int run(const std::string& board, const std::string& input, const std::string& options, std::string& report) {
  const std::string json = temp_path("lathe-cli.json");
  const std::string cmd = std::string("'") + AVRMOTION_SIM_EXE + "' --board " + board + " --input '" + input +
                          "' --report '" + json + "' --max-seconds 20 " + options + " 2>/dev/null";
  const int rc = std::system(cmd.c_str());
  report = slurp(json);
  std::remove(json.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

TEST(LatheCli, SpindleOptionsDriveThePass) {
  const std::string job = temp_path("lathe-cli.txt");
  std::string report;
  { std::ofstream(job) << "ENCODER C600 E4\nG33 Z-5 K1\n"; }
  ASSERT_EQ(run("m16-lathe", job,
                "--spindle-lines 600 --spindle-quadrature --spindle-rpm 0@0 --spindle-rpm 300@0.5 "
                "--spindle-jitter 5",
                report),
            0);
  EXPECT_NE(report.find("\"Z\": {\"steps\": -1260,"), std::string::npos) << report;
  EXPECT_NE(report.find("\"errors\": []"), std::string::npos) << report;
  { std::ofstream(job) << "ENCODER C40 E1\nG33 Z-5 P13\n"; }
  ASSERT_EQ(run("m16-lathe", job, "--spindle-rpm 200@0", report), 0);
  EXPECT_NE(report.find("\"Z\": {\"steps\": -1260,"), std::string::npos) << report;
  // At rest (no --spindle-rpm) the pass waits for an index that never comes.
  EXPECT_EQ(run("m16-lathe", job, "--max-seconds 1", report), 3);
  EXPECT_EQ(run("m16-lathe", job, "--spindle-lines 0", report), 2);
  EXPECT_EQ(run("m16-lathe", job, "--spindle-rpm 300", report), 2);
  EXPECT_EQ(run("m16-lathe", job, "--spindle-rpm 300@1 --spindle-rpm 100@0.5", report), 2);
  EXPECT_EQ(run("m16", job, "--spindle-rpm 300@0", report), 2);
  std::remove(job.c_str());
}

}  // namespace
