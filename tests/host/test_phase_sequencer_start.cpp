// PhaseSequencer started on a chosen state (the seed-002 driver board powers up
// on AB). Expected patterns come from seed-002 section 7's step table
// 1 = AB, 2 = BC, 3 = CD, 4 = DA (right = clockwise = forward), written in the
// sequencer's coil bits A+ = a = 0x1, B+ = b = 0x2, A- = c = 0x4, B- = d = 0x8.
#include <gtest/gtest.h>

#include <vector>

#include "core/motor/phase_sequencer.h"

namespace {

constexpr uint8_t AB = 0x1 | 0x2, BC = 0x2 | 0x4, CD = 0x4 | 0x8, DA = 0x8 | 0x1;

std::vector<uint8_t> walk(am::PhaseSequencer& seq, bool forward, int steps) {
  std::vector<uint8_t> out;
  for (int i = 0; i < steps; ++i) out.push_back(seq.step(forward));
  return out;
}

TEST(PhaseSequencerStart, StartsOffAndHoldsTheStartState) {
  am::PhaseSequencer seq(am::StepMode::two_phase, 1);
  EXPECT_EQ(seq.pattern(), 0);  // coils off until energised
  EXPECT_EQ(seq.index(), 1);
  EXPECT_EQ(seq.hold(), AB);
  EXPECT_EQ(seq.index(), 1);
}

TEST(PhaseSequencerStart, ClockwiseFromAbIsBcCdDaAb) {
  am::PhaseSequencer seq(am::StepMode::two_phase, 1);
  seq.hold();
  const std::vector<uint8_t> expected = {BC, CD, DA, AB, BC};
  EXPECT_EQ(walk(seq, true, 5), expected);
}

TEST(PhaseSequencerStart, CounterClockwiseFromAbIsDaCdBcAb) {
  am::PhaseSequencer seq(am::StepMode::two_phase, 1);
  seq.hold();
  const std::vector<uint8_t> expected = {DA, CD, BC, AB, DA};
  EXPECT_EQ(walk(seq, false, 5), expected);
}

TEST(PhaseSequencerStart, ReleaseKeepsThePhase) {
  am::PhaseSequencer seq(am::StepMode::two_phase, 1);
  seq.hold();
  seq.step(true);  // BC
  seq.step(true);  // CD
  seq.release();
  EXPECT_EQ(seq.pattern(), 0);
  EXPECT_EQ(seq.hold(), CD);
  EXPECT_EQ(seq.step(true), DA);
}

TEST(PhaseSequencerStart, StartIndexIsTakenModuloEight) {
  am::PhaseSequencer seq(am::StepMode::two_phase, 9);
  EXPECT_EQ(seq.index(), 1);
  EXPECT_EQ(seq.hold(), AB);
}

TEST(PhaseSequencerStart, DefaultStartIsUnchanged) {
  // The one-argument constructor still starts on A+ (index 0), so the
  // two-phase hold backs up to B-A+ as before.
  am::PhaseSequencer seq(am::StepMode::two_phase);
  EXPECT_EQ(seq.index(), 0);
  EXPECT_EQ(seq.hold(), DA);
}

}  // namespace
