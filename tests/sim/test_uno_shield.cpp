// The Uno + Motor Shield v1 image: exact 74HC595 bytes (seed-000 section 1 and
// 2: stepper 1 two-phase 0x06, 0x0A, 0x18, 0x14; stepper 2 0x21, 0x81, 0xC0,
// 0x60) and positions decoded from them.
#include <algorithm>
#include <vector>

#include "sim_fixture.h"

namespace {

std::vector<uint8_t> latched(const sim::Machine& m) {
  std::vector<uint8_t> out;
  for (const sim::LatchEvent& e : m.latch()->history()) out.push_back(e.value);
  return out;
}

}  // namespace

TEST(UnoShield, Stepper1TwoPhaseForwardBytes) {
  auto m = simtest::run("uno", {"MOVE X5"});
  // Power-on clears the register, the move first holds B-A+ (0x14), then each
  // step shows the next pair, exactly AFMotor's FORWARD DOUBLE sequence.
  const std::vector<uint8_t> expected = {0x00, 0x14, 0x06, 0x0A, 0x18, 0x14, 0x06};
  EXPECT_EQ(latched(*m), expected);
  EXPECT_DOUBLE_EQ(m->axis('X')->steps(), 5.0);
}

TEST(UnoShield, Stepper1TwoPhaseReverseBytes) {
  auto m = simtest::run("uno", {"MOVE X-4"});
  const std::vector<uint8_t> expected = {0x00, 0x14, 0x18, 0x0A, 0x06, 0x14};
  EXPECT_EQ(latched(*m), expected);
  EXPECT_DOUBLE_EQ(m->axis('X')->steps(), -4.0);
}

TEST(UnoShield, Stepper2TwoPhaseBytesLeaveStepper1Alone) {
  auto m = simtest::run("uno", {"MOVE Y4"});
  const std::vector<uint8_t> expected = {0x00, 0x60, 0x21, 0x81, 0xC0, 0x60};
  EXPECT_EQ(latched(*m), expected);
  EXPECT_DOUBLE_EQ(m->axis('Y')->steps(), 4.0);
  EXPECT_TRUE(m->axis('X')->step_cycles.empty());
}

TEST(UnoShield, BothSteppersShareTheLatchWithoutDisturbingEachOther) {
  auto m = simtest::run("uno", {"MOVE X3", "MOVE Y-2", "POS"});
  const std::vector<uint8_t> bytes = latched(*m);
  ASSERT_FALSE(bytes.empty());
  // After X's three steps (B-A+ -> A+B+ -> B+A- -> A-B-: 0x18) Y holds 0x60,
  // then steps back twice: 0xC0 then 0x81, with X's bits untouched.
  EXPECT_EQ(bytes.back(), 0x18 | 0x81);
  EXPECT_DOUBLE_EQ(m->axis('X')->steps(), 3.0);
  EXPECT_DOUBLE_EQ(m->axis('Y')->steps(), -2.0);
  const auto& got = m->serial().received();
  EXPECT_NE(std::find(got.begin(), got.end(), "pos X:3 Y:-2 Z:0"), got.end());
}

TEST(UnoShield, ReleaseTurnsEveryCoilOff) {
  auto m = simtest::run("uno", {"MOVE X3", "MOVE Y3", "RELEASE"});
  EXPECT_EQ(m->latch()->outputs(), 0);
  EXPECT_EQ(m->serial().lines_ok(), 3u);
}

TEST(UnoShield, PositionStaysExactAcrossModeChanges) {
  // One two-phase step (B-A+ held, then A+B+: 1 full step), three 1/16
  // microsteps (1.1875), then back to two-phase from that off-grid angle:
  // the first step only reaches the next two-phase state, B+A-, two full
  // steps from where the rotor was first held.
  auto m = simtest::run("uno", {"MOVE X1", "MODE X16", "MOVE X3", "POS", "MODE X1", "MOVE X1", "POS"});
  const auto& got = m->serial().received();
  EXPECT_NE(std::find(got.begin(), got.end(), "pos X:1.1875 Y:0 Z:0"), got.end());
  EXPECT_NE(std::find(got.begin(), got.end(), "pos X:2 Y:0 Z:0"), got.end());
  EXPECT_DOUBLE_EQ(m->axis('X')->steps(), 2.0);  // the coil decoder agrees
  EXPECT_EQ(m->latch()->outputs() & 0x1E, 0x0A);  // B+A-
}
