// ExcitationCursor / ExcitationTable (core/motor/microstep.h): the shield's modes on
// one rotor angle. Expectations come from seed-000 sections 1-2 (coil order,
// half-step cycle, AFMotor curve) and from std::sin, not from the code.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/motor/microstep.h"

namespace {

using am::ExcitationCursor;
namespace ex = am::excitation;

// Angles visited by n steps from the cursor's current state.
std::vector<int> walk(ExcitationCursor& c, int n, bool forward) {
  std::vector<int> out;
  for (int i = 0; i < n; ++i) out.push_back(c.step(forward));
  return out;
}

// Coil bits in the phase-sequencer order, so table bits read as patterns.
const am::ExcitationTable table(0x1, 0x2, 0x4, 0x8);

}  // namespace

TEST(ExcitationCursor, ModeNumbers) {
  for (int m = 0; m < 256; ++m) {
    const bool expected = m == 0 || m == 1 || m == 2 || m == 16 || m == 32 || m == 64;
    EXPECT_EQ(ex::valid(uint8_t(m)), expected) << m;
  }
  ExcitationCursor c;
  EXPECT_EQ(c.mode(), ex::two_phase);
  EXPECT_FALSE(c.set_mode(8));
  EXPECT_EQ(c.mode(), ex::two_phase);
}

TEST(ExcitationCursor, PowerUpTwoPhaseHoldsBMinusAPlusThenAPlusBPlus) {
  ExcitationCursor c;
  EXPECT_EQ(c.snap_down(), 224);  // state 7, B-A+
  EXPECT_EQ(walk(c, 5, true), (std::vector<int>{32, 96, 160, 224, 32}));
  EXPECT_EQ(walk(c, 3, false), (std::vector<int>{224, 160, 96}));
}

TEST(ExcitationCursor, GridsOfEveryMode) {
  // Full steps are 64 units, half steps 32, N microsteps 64 / N.
  const struct { uint8_t mode; int start; int step; } cases[] = {
      {ex::wave, 0, 64}, {ex::two_phase, 32, 64}, {ex::half, 0, 32},
      {ex::micro16, 0, 4}, {ex::micro32, 0, 2}, {ex::micro64, 0, 1}};
  for (const auto& k : cases) {
    ExcitationCursor c;
    ASSERT_TRUE(c.set_mode(k.mode));
    c.snap_down();
    if (k.mode == ex::two_phase) c.step(true);
    EXPECT_EQ(c.angle(), k.start);
    EXPECT_TRUE(c.on_grid());
    for (int i = 1; i <= 300; ++i) {
      EXPECT_EQ(c.step(true), (k.start + i * k.step) & 255) << int(k.mode);
    }
    for (int i = 299; i >= 0; --i) {
      EXPECT_EQ(c.step(false), (k.start + i * k.step) & 255) << int(k.mode);
    }
  }
}

TEST(ExcitationCursor, ModeChangeOffTheGridTakesAPartialStep) {
  ExcitationCursor c;
  c.set_mode(ex::micro64);
  c.snap_down();
  walk(c, 5, true);  // angle 5: 5/64 of a full step past A+
  c.set_mode(ex::micro16);
  EXPECT_FALSE(c.on_grid());
  EXPECT_EQ(c.angle(), 5);   // the mode change itself does not move
  EXPECT_EQ(c.step(true), 8);
  EXPECT_EQ(c.step(false), 4);

  c.set_mode(ex::micro64);
  walk(c, 3, true);  // 7
  c.set_mode(ex::two_phase);
  EXPECT_EQ(c.step(false), 224);  // the two-phase state behind: B-A+
  c.set_mode(ex::micro64);
  walk(c, 40, true);  // 224 + 40 = 264 -> 8
  c.set_mode(ex::two_phase);
  EXPECT_EQ(c.step(true), 32);  // the state ahead: A+B+
  c.set_mode(ex::wave);
  EXPECT_EQ(c.step(true), 64);  // from A+B+ one half step on to B+
  c.set_mode(ex::half);
  EXPECT_EQ(c.step(false), 32);
}

TEST(ExcitationTable, MicroCurrentsFollowTheSine) {
  const double pi = std::acos(-1.0);
  for (int a = 0; a < 256; ++a) {
    // Winding currents of electrical angle a * (pi/2) / 64: A = cos, B = sin.
    const double theta = a * pi / 128;
    const double ia = 255 * std::cos(theta), ib = 255 * std::sin(theta);
    const am::ExcitationEntry& e = table.micro[a];
    EXPECT_NEAR(e.pwm_a, std::fabs(ia), 0.5 + 1e-9) << a;
    EXPECT_NEAR(e.pwm_b, std::fabs(ib), 0.5 + 1e-9) << a;
    // Polarity from the sign of each current; no bits for a zero duty.
    const uint8_t a_bits = e.pwm_a == 0 ? 0 : ia > 0 ? 0x1 : 0x4;
    const uint8_t b_bits = e.pwm_b == 0 ? 0 : ib > 0 ? 0x2 : 0x8;
    EXPECT_EQ(e.bits, a_bits | b_bits) << a;
  }
}

TEST(ExcitationTable, SixteenMicrostepsMatchAFMotorWithinOne) {
  // AFMotor's curve (seed-000 section 2), quadrant 0: A = curve[16 - cs],
  // B = curve[cs]; 16 microsteps are every fourth angle.
  const int afmotor[17] = {0, 25, 50, 74, 98, 120, 141, 162, 180, 197, 212, 225, 236, 244, 250, 253, 255};
  for (int cs = 0; cs < 16; ++cs) {
    EXPECT_NEAR(table.micro[4 * cs].pwm_a, afmotor[16 - cs], 1) << cs;
    EXPECT_NEAR(table.micro[4 * cs].pwm_b, afmotor[cs], 1) << cs;
  }
}

TEST(ExcitationTable, QuadrantStartsAreTheSingleCoilStates) {
  // A+, B+, A-, B- at full current in one winding, the other off.
  EXPECT_EQ(table.micro[0].bits, 0x1);
  EXPECT_EQ(table.micro[64].bits, 0x2);
  EXPECT_EQ(table.micro[128].bits, 0x4);
  EXPECT_EQ(table.micro[192].bits, 0x8);
  EXPECT_EQ(table.micro[0].pwm_a, 255);
  EXPECT_EQ(table.micro[64].pwm_b, 255);
  // Between them both coils of the quadrant carry current.
  EXPECT_EQ(table.micro[32].bits, 0x3);
  EXPECT_EQ(table.micro[96].bits, 0x6);
  EXPECT_EQ(table.micro[160].bits, 0xC);
  EXPECT_EQ(table.micro[224].bits, 0x9);
}

TEST(ExcitationTable, FullStatesAreTheHalfStepCycleAtFullCurrent) {
  // seed-000 section 2: 1000, 1100, 0100, 0110, 0010, 0011, 0001, 1001 (A+ B+ A- B-).
  const uint8_t expected[8] = {0x1, 0x3, 0x2, 0x6, 0x4, 0xC, 0x8, 0x9};
  for (int j = 0; j < 8; ++j) {
    EXPECT_EQ(table.full[j].bits, expected[j]) << j;
    EXPECT_EQ(table.full[j].pwm_a, 255);
    EXPECT_EQ(table.full[j].pwm_b, 255);
  }
}

TEST(ExcitationTable, ShieldWiringBytes) {
  // Stepper 1 latch bits A+ 0x04, B+ 0x02, A- 0x08, B- 0x10 (seed-000 section 1).
  constexpr am::ExcitationTable s1(0x04, 0x02, 0x08, 0x10);
  EXPECT_EQ(s1.full[1].bits, 0x06);
  EXPECT_EQ(s1.full[3].bits, 0x0A);
  EXPECT_EQ(s1.full[5].bits, 0x18);
  EXPECT_EQ(s1.full[7].bits, 0x14);
  EXPECT_EQ(s1.micro[200].bits, 0x14);
}
