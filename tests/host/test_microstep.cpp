// Microstep tables and sequencing against the sine and seed-000's AFMotor facts.
#include <gtest/gtest.h>

#include <cmath>

#include "core/motor/microstep.h"
#include "core/motor/phase_sequencer.h"

namespace {

template <uint8_t M>
void expect_curve_matches_sine() {
  constexpr am::MicrostepCurve<M> curve{};
  for (int k = 0; k <= M; ++k) {
    const double exact = 255.0 * std::sin(k * M_PI / (2.0 * M));
    EXPECT_LE(std::fabs(curve.duty[k] - exact), 0.5 + 1e-6) << "M=" << int(M) << " k=" << k;
  }
  EXPECT_EQ(curve.duty[0], 0);
  EXPECT_EQ(curve.duty[M], 255);
}

TEST(Microstep, CurveIsRoundedSineForEveryPowerOfTwo) {
  expect_curve_matches_sine<2>();
  expect_curve_matches_sine<4>();
  expect_curve_matches_sine<8>();
  expect_curve_matches_sine<16>();
  expect_curve_matches_sine<32>();
  expect_curve_matches_sine<64>();
}

TEST(Microstep, SixteenMicrostepsAgreeWithAfmotorWithinOne) {
  // seed-000 section 2: the AFMotor 17-entry curve.
  const int afmotor[17] = {0, 25, 50, 74, 98, 120, 141, 162, 180,
                           197, 212, 225, 236, 244, 250, 253, 255};
  constexpr am::MicrostepCurve<16> curve{};
  int differing = 0;
  for (int k = 0; k <= 16; ++k) {
    EXPECT_LE(std::abs(curve.duty[k] - afmotor[k]), 1) << "k=" << k;
    if (curve.duty[k] != afmotor[k]) ++differing;
  }
  // The two documented differences: k = 6 and k = 15 (AFMotor truncated).
  EXPECT_EQ(curve.duty[6], 142);
  EXPECT_EQ(curve.duty[15], 254);
  EXPECT_EQ(differing, 2);
}

TEST(Microstep, QuadrantMappingFollowsAfmotor) {
  constexpr am::MicrostepCurve<16> curve{};
  using MS = am::Microstepper<16>;
  const uint8_t coils[4] = {am::coil::a_pos | am::coil::b_pos, am::coil::b_pos | am::coil::a_neg,
                            am::coil::a_neg | am::coil::b_neg, am::coil::b_neg | am::coil::a_pos};
  for (int i = 0; i < 64; ++i) {
    const int q = i / 16, cs = i % 16;
    const am::MicrostepOutput out = MS::output_at(uint16_t(i));
    EXPECT_EQ(out.coils, coils[q]) << i;
    if (q == 0 || q == 2) {
      EXPECT_EQ(out.pwm_a, curve.duty[16 - cs]) << i;
      EXPECT_EQ(out.pwm_b, curve.duty[cs]) << i;
    } else {
      EXPECT_EQ(out.pwm_a, curve.duty[cs]) << i;
      EXPECT_EQ(out.pwm_b, curve.duty[16 - cs]) << i;
    }
  }
}

// Signed winding currents implied by coils + duty must trace a circle:
// A = cos(theta), B = sin(theta) with theta = i * pi / (2M).
template <uint8_t M>
void expect_currents_trace_cosine_sine() {
  using MS = am::Microstepper<M>;
  for (int i = 0; i < 4 * M; ++i) {
    const am::MicrostepOutput out = MS::output_at(uint16_t(i));
    const int sign_a = (out.coils & am::coil::a_pos) ? 1 : -1;
    const int sign_b = (out.coils & am::coil::b_pos) ? 1 : -1;
    const double theta = i * M_PI / (2.0 * M);
    EXPECT_NEAR(sign_a * out.pwm_a, 255.0 * std::cos(theta), 0.5 + 1e-6) << "M=" << int(M) << " i=" << i;
    EXPECT_NEAR(sign_b * out.pwm_b, 255.0 * std::sin(theta), 0.5 + 1e-6) << "M=" << int(M) << " i=" << i;
  }
}

TEST(Microstep, WindingCurrentsFollowTheElectricalAngle) {
  expect_currents_trace_cosine_sine<2>();
  expect_currents_trace_cosine_sine<16>();
  expect_currents_trace_cosine_sine<64>();
}

TEST(Microstep, FullCurrentIndicesAreTheHalfStepStates) {
  using MS = am::Microstepper<8>;
  for (uint8_t j = 0; j < 8; ++j) {
    const am::MicrostepOutput out = MS::output_at(uint16_t(j * 4));
    // The windings carrying current are exactly the half-step state's coils.
    uint8_t lit = 0;
    if (out.pwm_a) lit |= out.coils & (am::coil::a_pos | am::coil::a_neg);
    if (out.pwm_b) lit |= out.coils & (am::coil::b_pos | am::coil::b_neg);
    EXPECT_EQ(lit, am::half_step_pattern(j)) << int(j);
  }
}

TEST(Microstep, ForwardReverseReleaseHold) {
  am::Microstepper<16> m;
  EXPECT_FALSE(m.energised());
  EXPECT_EQ(m.output().coils, 0);
  // First forward microstep from power-up: index 1, as AFMotor's onestep().
  am::MicrostepOutput out = m.step(true);
  EXPECT_EQ(m.index(), 1);
  EXPECT_EQ(out.pwm_a, 254);  // curve[15]: 255 sin(15 pi / 32) = 253.77
  EXPECT_EQ(out.pwm_b, 25);
  EXPECT_EQ(out.coils, am::coil::a_pos | am::coil::b_pos);
  // Backward wraps through the cycle.
  m.step(false);
  out = m.step(false);
  EXPECT_EQ(m.index(), 63);
  EXPECT_EQ(out.coils, am::coil::b_neg | am::coil::a_pos);
  // A whole cycle forward returns to the same output.
  for (int i = 0; i < 64; ++i) m.step(true);
  EXPECT_EQ(m.index(), 63);
  // Release keeps the index; hold re-energises it.
  out = m.release();
  EXPECT_EQ(out.coils, 0);
  EXPECT_EQ(out.pwm_a, 0);
  EXPECT_EQ(out.pwm_b, 0);
  EXPECT_EQ(m.index(), 63);
  out = m.hold();
  EXPECT_EQ(out.coils, am::coil::b_neg | am::coil::a_pos);
  EXPECT_EQ(out.pwm_b, am::MicrostepCurve<16>{}.duty[1]);
}

}  // namespace
