// Firmware retraction on the real m32-grbl image (G10/G11, M207/M208,
// core/text/gcode_retraction.h): the extruder's and Z's steps on the pins
// through a retract, a move while retracted, a recovery, then a retract
// with a hop and a recovery with an extra; the retraction's cruise rate on
// every interval of its move; M114's program position against the pins'.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "sim_fixture.h"

namespace {

constexpr double kHz = 16e6;

TEST(Retraction, RetractMoveRecoverAndHopOnThePins) {
  const std::vector<std::string> lines = {"M207 F1200", "M208 F600", "G1 E5 F600", "G10",        "G1 E6",
                                          "G11",        "M207 S2 Z0.4", "M208 S0.5", "G10", "G11",
                                          "G10",        "G10",        "M400",      "M114"};
  auto m = simtest::run("m32-grbl", lines, 20);
  for (const sim::Response& r : m->serial().responses()) EXPECT_EQ(r.answer, "ok") << r.line;
  // E at 1000 steps/mm: +5000, G10 -3000, to E6 while retracted +1000, G11
  // +3000, G10 -2000, G11 +2500, G10 -2000 (the second G10 moves nothing).
  const std::vector<uint64_t>& e = m->axis('E')->step_cycles;
  EXPECT_EQ(long(m->axis('E')->steps()), 5000 - 3000 + 1000 + 3000 - 2000 + 2500 - 2000);
  EXPECT_EQ(e.size(), size_t(5000 + 3000 + 1000 + 3000 + 2000 + 2500 + 2000));
  // Z: up 0.4 and down at the first hop, up again at the last G10.
  EXPECT_EQ(long(m->axis('Z')->steps()), 400);
  EXPECT_EQ(m->axis('Z')->step_cycles.size(), size_t(1200));
  // The first G10's 3000 steps (after the first move's 5000) at M207's
  // 1200 mm/min, 20000 steps/s: no interval shorter, the cruise at it.
  ASSERT_GE(e.size(), size_t(8000));
  std::vector<uint64_t> d;
  for (size_t i = 5001; i < 8000; ++i) d.push_back(e[i] - e[i - 1]);
  const uint64_t shortest = *std::min_element(d.begin(), d.end());
  std::sort(d.begin(), d.end());
  const uint64_t median = d[d.size() / 2];
  const double cruise = kHz / 20000;
  std::printf("G10 at M207 F1200: %zu intervals, shortest %llu, median %llu cycles (%.0f at 20 mm/s)\n", d.size(),
              (unsigned long long)shortest, (unsigned long long)median, cruise);
  EXPECT_GE(double(shortest), cruise * 0.99);
  EXPECT_NEAR(double(median), cruise, cruise * 0.01);
  // The program's E is 6 and Z 0 (the retraction is in the offsets); the
  // motors' counts are where the pins are.
  const std::vector<std::string> msgs = m->serial().messages();
  ASSERT_FALSE(msgs.empty());
  const std::string& pos = msgs.back();
  std::printf("M114: %s\n", pos.c_str());
  EXPECT_NE(pos.find("Z:0.0000"), std::string::npos) << pos;
  EXPECT_NE(pos.find("E:6.0000"), std::string::npos) << pos;
  EXPECT_NE(pos.find("Count X:0 Y:0 Z:400 E:4500"), std::string::npos) << pos;
}

}  // namespace
