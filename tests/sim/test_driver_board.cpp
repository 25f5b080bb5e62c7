// The m32-driver image (seed-002 §1, §7): an ATmega32 that follows STEP (INT0,
// PD2), DIR (PD0) and ENABLE (PD1) and drives coils a, c, b, d on PB0..PB3
// two-phase-on, with a threshold current chopper on ADC0 (pair a/c) and ADC1
// (pair b/d). Expected values come from the seed's tables and the ATmega32
// datasheet, never from a run of the image:
//   states (PORTB low nibble) AB 0x05, BC 0x06, CD 0x0A, DA 0x09;
//   ADC: 8-bit left-adjusted reading = Vin x 256 / 5 V (AVCC), limit 100
//   counts = 1.953 V; one conversion 13 ADC clocks x 64 = 832 cycles.
#include <sim_avr.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "sim_fixture.h"

namespace {

constexpr uint8_t AB = 0x05, BC = 0x06, CD = 0x0A, DA = 0x09;
constexpr uint8_t kPairAC = 0x03, kPairBD = 0x0C;  // a|c = PB0|PB1, b|d = PB2|PB3
// ATmega32 data-space addresses (I/O address + 0x20) and vector numbers.
constexpr uint16_t kPORTB = 0x38, kDDRB = 0x37, kPORTD = 0x32, kDDRD = 0x31, kUCSRB = 0x2A;
constexpr int kInt0Vector = 1, kAdcVector = 16;
constexpr uint64_t kConversion = 13 * 64;  // cycles, datasheet: 13 ADC clocks at F_CPU/64
// Budget the firmware documents for one ADC interrupt's restart overhead
// (response, prologue, mux switch before ADSC); docs/driver-board.md.
constexpr uint64_t kRestartBudget = 40;
constexpr uint64_t kPairPeriodBound = 2 * (kConversion + kRestartBudget);

struct Change {
  uint64_t cycle;
  uint8_t coils;
};

class DriverBoard {
 public:
  DriverBoard() : m_(simtest::image("m32-driver")) {
    // Boot: until the firmware enables interrupts (init done).
    EXPECT_EQ(m_.run([this] { return observe() || m_.avr()->sreg[S_I]; }, 100000), sim::RunEnd::done);
  }

  sim::Machine& m() { return m_; }
  uint8_t coils() { return m_.avr()->data[kPORTB] & 0x0F; }
  const std::vector<Change>& changes() const { return changes_; }
  const sim::AxisTrace& axis() const { return *m_.axis('M'); }
  uint64_t now() const { return m_.cycles(); }

  void run_for(uint64_t cycles) {
    const uint64_t end = now() + cycles;
    m_.run([this, end] { return observe() || now() >= end; }, cycles + 16);
  }
  // Runs until the coil nibble satisfies `pred`; returns the cycles it took,
  // or UINT64_MAX when `budget` ran out first.
  template <typename Pred>
  uint64_t run_until(Pred pred, uint64_t budget) {
    const uint64_t start = now();
    const sim::RunEnd end = m_.run([&] { return observe() || pred(coils()); }, budget);
    return end == sim::RunEnd::done ? now() - start : UINT64_MAX;
  }

  void dir(bool cw) { m_.set_input('D', 0, cw); }
  void enable(bool on) {
    m_.set_input('D', 1, on);
    run_for(200);  // the main loop polls ENABLE
  }
  // One STEP pulse: high for `high` cycles, then low for `low`.
  void pulse(uint64_t high = 200, uint64_t low = 200) {
    m_.set_input('D', 2, true);
    run_for(high);
    m_.set_input('D', 2, false);
    run_for(low);
  }

 private:
  // Logs every change of the coil nibble; never stops the run by itself.
  bool observe() {
    const uint8_t c = coils();
    if (changes_.empty() || changes_.back().coils != c) changes_.push_back({now(), c});
    return false;
  }

  sim::Machine m_;
  std::vector<Change> changes_;
};

std::vector<uint8_t> states_after_pulses(DriverBoard& b, int n) {
  std::vector<uint8_t> out;
  for (int i = 0; i < n; ++i) {
    b.pulse();
    out.push_back(b.coils());
  }
  return out;
}

TEST(driver_board, DescriptorNamesTheCoilsInSequencerOrder) {
  DriverBoard b;
  const am::BoardDescriptor& d = b.m().board();
  EXPECT_STREQ(d.mcu, "atmega32");
  EXPECT_EQ(d.f_cpu, 16000000u);
  ASSERT_EQ(d.axis_count, 1);
  EXPECT_EQ(d.axes[0].kind, am::AxisKind::unipolar4);
  // IN1..IN4 = A+, B+, A-, B- = a, b, c, d = PB0, PB2, PB1, PB3.
  const uint8_t expected[4] = {am::pin_code('B', 0), am::pin_code('B', 2), am::pin_code('B', 1),
                               am::pin_code('B', 3)};
  for (int k = 0; k < 4; ++k) EXPECT_EQ(d.axes[0].pins[k], expected[k]) << "IN" << k + 1;
}

TEST(driver_board, PowerUpLeavesCoilsOffAndInputsFloating) {
  DriverBoard b;
  b.run_for(20000);  // a dozen ADC conversions
  for (const Change& c : b.changes()) EXPECT_EQ(c.coils, 0) << "at cycle " << c.cycle;
  const uint8_t* d = b.m().avr()->data;
  EXPECT_EQ(d[kDDRB] & 0x0F, 0x0F);  // coil pins drive
  EXPECT_EQ(d[kDDRD] & 0x07, 0);     // STEP, DIR, ENABLE are inputs
  EXPECT_EQ(d[kPORTD] & 0x07, 0);    // without pull-ups
  EXPECT_EQ(d[kUCSRB] & 0x18, 0);    // RXEN, TXEN off: PD0/PD1 are GPIO
  // Steps without ENABLE move nothing.
  b.dir(true);
  for (int i = 0; i < 4; ++i) b.pulse();
  EXPECT_EQ(b.coils(), 0);
  EXPECT_TRUE(b.axis().step_cycles.empty());
}

TEST(driver_board, EnableEnergisesAbWithinAFewMainLoopTurns) {
  DriverBoard b;
  b.m().set_input('D', 1, true);
  const uint64_t took = b.run_until([](uint8_t c) { return c == AB; }, 2000);
  EXPECT_LE(took, 200u);  // main-loop poll plus at most one ADC interrupt
}

TEST(driver_board, ClockwiseSequenceFromAb) {
  DriverBoard b;
  b.dir(true);
  b.enable(true);
  EXPECT_EQ(b.coils(), AB);
  const std::vector<uint8_t> expected = {BC, CD, DA, AB, BC, CD, DA, AB};
  EXPECT_EQ(states_after_pulses(b, 8), expected);
  EXPECT_DOUBLE_EQ(b.axis().steps(), 8.0);  // decoded from the descriptor's pins
  EXPECT_EQ(b.axis().step_cycles.size(), 8u);
  EXPECT_EQ(b.axis().decode_errors, 0u);
}

TEST(driver_board, CounterClockwiseSequenceFromAb) {
  DriverBoard b;
  b.dir(false);
  b.enable(true);
  const std::vector<uint8_t> expected = {DA, CD, BC, AB, DA, CD};
  EXPECT_EQ(states_after_pulses(b, 6), expected);
  EXPECT_DOUBLE_EQ(b.axis().steps(), -6.0);
  EXPECT_EQ(b.axis().decode_errors, 0u);
}

TEST(driver_board, DirectionIsReadAtEveryStep) {
  DriverBoard b;
  b.enable(true);
  b.dir(true);
  b.pulse();  // BC
  b.pulse();  // CD
  b.dir(false);
  b.pulse();  // BC
  EXPECT_EQ(b.coils(), BC);
  EXPECT_DOUBLE_EQ(b.axis().steps(), 1.0);
}

TEST(driver_board, DisableKeepsThePhaseAndIgnoresSteps) {
  DriverBoard b;
  b.dir(true);
  b.enable(true);
  b.pulse();
  b.pulse();
  ASSERT_EQ(b.coils(), CD);
  b.enable(false);
  EXPECT_EQ(b.coils(), 0);
  for (int i = 0; i < 5; ++i) b.pulse();
  EXPECT_EQ(b.coils(), 0);
  b.enable(true);
  EXPECT_EQ(b.coils(), CD);  // same phase as before
  b.pulse();
  EXPECT_EQ(b.coils(), DA);
  EXPECT_DOUBLE_EQ(b.axis().steps(), 3.0);
}

TEST(driver_board, CoilWritesLeaveTheHighNibbleAlone) {
  DriverBoard b;
  b.m().avr()->data[kPORTB] |= 0xA0;  // pull-ups someone set on PB5/PB7
  b.dir(true);
  b.enable(true);
  for (int i = 0; i < 5; ++i) b.pulse();
  b.m().set_adc_millivolts(0, 3000);
  b.run_for(4000);
  b.enable(false);
  EXPECT_EQ(b.m().avr()->data[kPORTB] & 0xF0, 0xA0);
}

TEST(driver_board, ChopperCutsExactlyTheOverLimitPair) {
  DriverBoard b;
  b.dir(true);
  b.enable(true);
  b.pulse();  // BC: b (PB2) and c (PB1), one coil of each pair
  ASSERT_EQ(b.coils(), BC);

  b.m().set_adc_millivolts(0, 2500);  // 128 counts > 100: a/c pair cut
  uint64_t t = b.run_until([](uint8_t c) { return c == (BC & ~kPairAC); }, 10000);
  EXPECT_LE(t, kPairPeriodBound);
  b.run_for(3 * kPairPeriodBound);
  EXPECT_EQ(b.coils(), BC & ~kPairAC);  // stays cut while over the limit

  b.m().set_adc_millivolts(0, 1000);  // 51 counts: restored at the next AC sample
  t = b.run_until([](uint8_t c) { return c == BC; }, 10000);
  EXPECT_LE(t, kPairPeriodBound);

  b.m().set_adc_millivolts(1, 2500);  // now the b/d pair
  t = b.run_until([](uint8_t c) { return c == (BC & ~kPairBD); }, 10000);
  EXPECT_LE(t, kPairPeriodBound);
  b.m().set_adc_millivolts(0, 2500);  // both pairs over: all off
  EXPECT_NE(b.run_until([](uint8_t c) { return c == 0; }, 10000), UINT64_MAX);
  b.m().set_adc_millivolts(0, 0);
  b.m().set_adc_millivolts(1, 0);
  EXPECT_LE(b.run_until([](uint8_t c) { return c == BC; }, 10000), kPairPeriodBound);
}

TEST(driver_board, ChopperThresholdIsOneHundredCountsUnsigned) {
  DriverBoard b;
  b.enable(true);  // AB: a and b on
  // 1.95 V = 99.8 counts: not above the limit, whatever the rounding.
  b.m().set_adc_millivolts(0, 1950);
  b.run_for(4 * kPairPeriodBound);
  EXPECT_EQ(b.coils(), AB);
  for (const Change& c : b.changes()) {
    if (c.coils != 0) {
      EXPECT_EQ(c.coils, AB) << "at cycle " << c.cycle;
    }
  }
  // 2.0 V = 102 counts: cut.
  b.m().set_adc_millivolts(0, 2000);
  EXPECT_LE(b.run_until([](uint8_t c) { return c == (AB & ~kPairAC); }, 10000), kPairPeriodBound);
  // 4.5 V = 230 counts: as a signed byte this would be negative (the seed's
  // int8_t bug) and the pair would stay on.
  b.m().set_adc_millivolts(0, 0);
  b.run_until([](uint8_t c) { return c == AB; }, 10000);
  b.m().set_adc_millivolts(0, 4500);
  EXPECT_LE(b.run_until([](uint8_t c) { return c == (AB & ~kPairAC); }, 10000), kPairPeriodBound);
}

TEST(driver_board, SamplesEachPairOncePerTwoConversions) {
  DriverBoard b;
  b.run_for(10000);  // past the first, longer conversion
  const uint64_t n0 = b.m().isr_stats().at(kAdcVector).count;
  const uint64_t window = 1000000;
  b.run_for(window);
  const uint64_t n = b.m().isr_stats().at(kAdcVector).count - n0;
  // Each conversion is 832 cycles plus the restart overhead; AC and BD alternate.
  EXPECT_GE(n, window / (kConversion + kRestartBudget));
  EXPECT_LE(n, window / kConversion);
}

TEST(driver_board, FollowsStepsEvery400Cycles) {
  DriverBoard b;
  b.dir(true);
  b.enable(true);
  const int n = 400;
  for (int i = 0; i < n; ++i) b.pulse(200, 200);  // 40 kHz at 16 MHz
  EXPECT_DOUBLE_EQ(b.axis().steps(), double(n));
  EXPECT_EQ(b.axis().decode_errors, 0u);
  EXPECT_EQ(b.coils(), AB);  // 400 steps = 100 full cycles of four states
}

TEST(driver_board, StepLatencyStaysWithinTheDocumentedBound) {
  DriverBoard b;
  b.dir(true);
  b.enable(true);
  // The worst case is an edge just after the ADC interrupt was taken: sweep
  // the edge from 0 to 80 cycles after the ADC vector's first instruction.
  constexpr uint32_t kAdcVectorAddress = kAdcVector * 4;  // JMP table, bytes
  uint64_t worst = 0, idle = UINT64_MAX;
  for (uint64_t k = 0; k <= 80; ++k) {
    b.m().run([&] { return b.m().avr()->pc == kAdcVectorAddress; }, 4000);
    b.run_for(k);
    const uint8_t before = b.coils();
    b.m().set_input('D', 2, true);
    const uint64_t t = b.run_until([before](uint8_t c) { return c != before; }, 2000);
    ASSERT_NE(t, UINT64_MAX) << "edge " << k << " cycles after ADC entry not followed";
    worst = std::max(worst, t);
    idle = std::min(idle, t);
    b.run_for(100);
    b.m().set_input('D', 2, false);
  }
  const sim::IsrStats& step = b.m().isr_stats().at(kInt0Vector);
  const sim::IsrStats& adc = b.m().isr_stats().at(kAdcVector);
  // Bound: a whole ADC interrupt (response + JMP 7, body, RETI 4), one
  // main-loop instruction (<= 2), INT0 response + JMP 7, then the INT0 body up
  // to its OUT (shorter than the whole body).
  const uint64_t bound = 7 + adc.max_cycles + 4 + 2 + 7 + step.max_cycles;
  EXPECT_LE(worst, bound);
  EXPECT_LE(worst, 130u);    // docs/driver-board.md: worst-case step latency
  EXPECT_LE(idle, 60u);      // docs/driver-board.md: latency with the CPU idle
  EXPECT_LE(step.max_cycles, 70u);
  EXPECT_LE(adc.max_cycles, 60u);
  RecordProperty("worst_step_latency_cycles", int(worst));
  RecordProperty("idle_step_latency_cycles", int(idle));
}

TEST(driver_board, FollowsEveryStepAtTheGuaranteedRate) {
  // docs/driver-board.md: any edge is served within one ADC interrupt plus
  // the INT0 entry, so edges 150 cycles apart (106 kHz) never share a flag.
  DriverBoard b;
  b.dir(false);
  b.enable(true);
  b.run_for(3000);  // past the first conversion
  const uint64_t conversions0 = b.m().isr_stats().at(kAdcVector).count, t0 = b.now();
  const int n = 1000;
  for (int i = 0; i < n; ++i) b.pulse(75, 75);
  EXPECT_DOUBLE_EQ(b.axis().steps(), -double(n));
  EXPECT_EQ(b.axis().decode_errors, 0u);
  EXPECT_EQ(b.coils(), AB);  // 1000 = 250 cycles of four states
  // The chopper keeps sampling: a restart waits at most for one INT0
  // interrupt (< 80 cycles with entry and RETI) on top of its own overhead.
  const uint64_t conversions = b.m().isr_stats().at(kAdcVector).count - conversions0;
  EXPECT_GE(conversions, (b.now() - t0) / (kConversion + kRestartBudget + 80));
}

TEST(driver_board, StepsFasterThanTheIsrAreDroppedNeverReversed) {
  // docs/driver-board.md: beyond the limit the INT0 flag holds one edge, the
  // rest are lost; the rotor falls behind but never moves the wrong way.
  DriverBoard b;
  b.dir(true);
  b.enable(true);
  // Pulses every 40 cycles: shorter than the INT0 interrupt itself, so one
  // INTF0 flag cannot hold them all.
  const int n = 200;
  for (int i = 0; i < n; ++i) b.pulse(20, 20);
  b.run_for(1000);
  const sim::AxisTrace& a = b.axis();
  EXPECT_LT(a.steps(), double(n));
  EXPECT_GT(a.steps(), 0.0);
  for (int8_t d : a.step_deltas) EXPECT_EQ(d, 2);  // every decoded move is one step forward
  EXPECT_EQ(a.decode_errors, 0u);
}

}  // namespace
