// The lathe image cuts threads on the simulated spindle: each pass's
// leadscrew steps against the test's own floor(lambda s) (sim/lathe_check.h,
// 128-bit integers), at every spindle count from the lock to the end.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "../../core/lathe/pitch_tables.h"
#include "lathe_rig.h"

namespace {

using simtest::field;
using simtest::LatheRig;

struct Encoder {
  uint16_t lines;
  bool quadrature;
  double rpm;
  const char* command;
};
const Encoder kSeedDisc = {40, false, 300, "ENCODER C40 E1"};
const Encoder kQuadrature = {600, true, 600, "ENCODER C600 E4"};
// For the coarse pitches: 4 TPI at 600 rpm asks 16000 steps/s, too close to
// the carriage's 20000 to catch up within a few turns.
const Encoder kQuadratureSlow = {600, true, 300, "ENCODER C600 E4"};

struct Thread {
  std::string words;  // G33's pitch words
  int64_t pitch_num, pitch_den;  // um
};

// Runs one pass "G33 Z-<far> <words>" with the spindle starting from rest
// (0.2 s) up to the encoder's rpm in 0.3 s, `turns` turns at that speed,
// then down to rest; returns the check of every count.
sim::PassResult cut(const Encoder& e, const Thread& t, double turns, bool left = false, double jitter_us = 0) {
  sim::SpindleParams p;
  p.lines = e.lines;
  p.quadrature = e.quadrature;
  p.jitter_us = jitter_us;
  const double spin_s = turns / (e.rpm / 60);
  p.profile = {{0.2, 0}, {0.5, e.rpm}, {0.5 + spin_s, e.rpm}, {0.8 + spin_s, 0}};
  LatheRig rig(p);
  EXPECT_EQ(rig.send(e.command), "ok");
  EXPECT_EQ(rig.send(std::string("G33 Z") + (left ? "900 " : "-900 ") + t.words), "ok") << t.words;
  const uint64_t armed = rig.armed_after();
  rig.run_for(1.0 + spin_s);
  const std::string st = rig.status();
  sim::ThreadSpec spec{t.pitch_num, t.pitch_den};
  spec.right_hand = !left;
  spec.counts_per_turn = e.lines * (e.quadrature ? 4 : 1);
  const sim::PassResult r = sim::check_pass(*rig.spindle, rig.z(), *rig.step, spec, 0, armed, rig.m->cycles());
  // Steps on the pins = position reported, and the pass is still locked.
  EXPECT_EQ(field(st, "z"), std::to_string(rig.z().position)) << st;
  EXPECT_EQ(field(st, "state"), "locked") << st;
  EXPECT_EQ(field(st, "err"), "0") << st;
  EXPECT_EQ(field(st, "lost"), "0") << st;
  EXPECT_EQ(rig.z().decode_errors, 0u);
  return r;
}

void expect_exact(const sim::PassResult& r, const std::string& what, double min_counts) {
  ASSERT_TRUE(r.index_found) << what;
  EXPECT_TRUE(r.locked) << what;
  EXPECT_EQ(r.mismatches, 0u) << what;
  EXPECT_GE(double(r.counts), min_counts) << what;
  EXPECT_EQ(r.position, r.expected) << what << ": after " << r.s_end << " counts";
  EXPECT_NE(r.position, 0) << what;
}

TEST(LatheThread, OneMillimetreAnd13TpiOverManyTurnsEndOnTheGearedStepCount) {
  const Thread mm1 = {"K1", 1000, 1}, tpi13 = {"P13", 25400, 13};
  for (const Encoder& e : {kSeedDisc, kQuadrature}) {
    for (const Thread& t : {mm1, tpi13}) {
      const sim::PassResult r = cut(e, t, 20);
      const std::string what = std::string(e.command) + " G33 " + t.words;
      expect_exact(r, what, 20.0 * e.lines * (e.quadrature ? 4 : 1));
      std::printf("%s: %zu counts, %lld steps (= floor(lambda s)), locked after %zu counts\n", what.c_str(), r.counts,
                  (long long)r.position, r.locked_after);
    }
  }
}

TEST(LatheThread, PitchesFromTheTablesBothHands) {
  // Every fourth ISO coarse and UNC entry, a turning feed: K in mm, P in TPI.
  std::vector<Thread> threads;
  for (size_t i = 0; i < sizeof am::kIsoCoarse / sizeof am::kIsoCoarse[0]; i += 5) {
    const uint32_t um = am::kIsoCoarse[i].pitch_um;
    char words[24];
    std::snprintf(words, sizeof words, "K%u.%03u", um / 1000, um % 1000);
    threads.push_back({words, um, 1});
  }
  for (size_t i = 0; i < sizeof am::kUnc / sizeof am::kUnc[0]; i += 6) {
    const uint32_t x2 = am::kUnc[i].tpi_x2;
    char words[24];
    std::snprintf(words, sizeof words, "P%u%s", x2 / 2, x2 % 2 ? ".5" : "");
    threads.push_back({words, 50800, x2});
  }
  threads.push_back({"K0.08", 80, 1});
  bool left = false;
  for (const Thread& t : threads) {
    const sim::PassResult r = cut(kQuadratureSlow, t, 4, left);
    expect_exact(r, std::string("G33 ") + t.words + (left ? " left" : " right"), 4.0 * 2400);
    left = !left;
  }
}

// Edges up to +-10 us off their times (a quadrature edge every 42 us at 600
// rpm): the counts, not their timing, make the thread.
TEST(LatheThread, JitteredEdgesCutTheSameThread) {
  const Thread mm15 = {"K1.5", 1500, 1};
  for (const Encoder& e : {kSeedDisc, kQuadrature}) {
    const sim::PassResult r = cut(e, mm15, 6, false, 10);
    expect_exact(r, std::string(e.command) + " G33 K1.5, jitter 10 us", 6.0 * e.lines * (e.quadrature ? 4 : 1));
  }
}

}  // namespace
