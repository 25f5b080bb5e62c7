// Phase sequences against seed-003 (ULN2003 tables, IN1 = bit 0 = A+) and
// seed-000 section 2 (the same cycle as A+, B+, A-, B- rows).
#include <gtest/gtest.h>

#include <vector>

#include "core/motor/phase_sequencer.h"

namespace {

std::vector<uint8_t> walk(am::StepMode mode, bool forward, int steps) {
  am::PhaseSequencer seq(mode);
  std::vector<uint8_t> out;
  for (int i = 0; i < steps; ++i) out.push_back(seq.step(forward));
  return out;
}

}  // namespace

TEST(PhaseSequencer, HalfStepForwardMatchesUln2003Table) {
  // seed-003: 0x01, 0x03, 0x02, 0x06, 0x04, 0x0C, 0x08, 0x09 from A+; the
  // sequencer starts on A+ so its first step shows the second entry.
  const std::vector<uint8_t> expected = {0x03, 0x02, 0x06, 0x04, 0x0C, 0x08, 0x09, 0x01, 0x03};
  EXPECT_EQ(walk(am::StepMode::half, true, 9), expected);
}

TEST(PhaseSequencer, HalfStepReverseWalksTheTableBackwards) {
  const std::vector<uint8_t> expected = {0x09, 0x08, 0x0C, 0x04, 0x06, 0x02, 0x03, 0x01};
  EXPECT_EQ(walk(am::StepMode::half, false, 8), expected);
}

TEST(PhaseSequencer, WaveDriveEnergisesOneCoilAtATime) {
  // seed-003 wave: 0x01, 0x02, 0x04, 0x08; AFMotor SINGLE moves to the next
  // even state, so from A+ the first step is B+.
  const std::vector<uint8_t> expected = {0x02, 0x04, 0x08, 0x01, 0x02};
  EXPECT_EQ(walk(am::StepMode::wave, true, 5), expected);
  const std::vector<uint8_t> back = {0x08, 0x04, 0x02, 0x01};
  EXPECT_EQ(walk(am::StepMode::wave, false, 4), back);
}

TEST(PhaseSequencer, TwoPhaseFullStepUsesAdjacentPairs) {
  // seed-003 two-phase: 0x03, 0x06, 0x0C, 0x09.
  const std::vector<uint8_t> expected = {0x03, 0x06, 0x0C, 0x09, 0x03};
  EXPECT_EQ(walk(am::StepMode::two_phase, true, 5), expected);
  const std::vector<uint8_t> back = {0x09, 0x0C, 0x06, 0x03};
  EXPECT_EQ(walk(am::StepMode::two_phase, false, 4), back);
}

TEST(PhaseSequencer, ReleaseTurnsCoilsOffAndKeepsThePhase) {
  am::PhaseSequencer seq(am::StepMode::two_phase);
  EXPECT_EQ(seq.pattern(), am::coil::off);  // power-up: nothing energised
  seq.step(true);
  seq.step(true);  // on B+A- (0x06)
  seq.release();
  EXPECT_EQ(seq.pattern(), am::coil::off);
  EXPECT_EQ(seq.hold(), 0x06);  // same state comes back
  EXPECT_EQ(seq.step(true), 0x0C);
}

TEST(PhaseSequencer, HoldFromPowerUpPrecedesTheFirstAfmotorStep) {
  am::PhaseSequencer seq(am::StepMode::two_phase);
  EXPECT_EQ(seq.hold(), 0x09);      // B-A+
  EXPECT_EQ(seq.step(true), 0x03);  // A+B+, AFMotor's first DOUBLE step
}

TEST(PhaseSequencer, SwitchingModeContinuesFromTheNearestState) {
  am::PhaseSequencer seq(am::StepMode::half);
  seq.step(true);  // A+B+ (odd state)
  seq.set_mode(am::StepMode::wave);
  EXPECT_EQ(seq.step(true), 0x02);  // half a step on to B+, not a jump
  seq.set_mode(am::StepMode::two_phase);
  EXPECT_EQ(seq.step(false), 0x03);  // back to A+B+
}
