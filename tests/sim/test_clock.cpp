// The time base (firmware/engine/clock.h) on the real images: Timer0 counts
// the low byte, its overflow vector the rest.
//   - The overflows come exactly 256 x prescaler cycles apart (uno: 8, the
//     ATmega16/32 images: 64, the boards' claims), and the vector counts
//     each of them once, however busy the step engine and the UART are.
//   - clock::now(), the image's own code, called on the simulated chip from
//     the main loop hundreds to thousands of times, many timed to read TCNT0 just
//     as it wraps, while the step engine runs at the board's top rate with
//     the UART receiving and answering: it never goes backwards, and every
//     value it returns is the simulator's cycle counter over the prescaler,
//     plus one constant, at some cycle during the call.
//   - The Uno's Timer0 still drives stepper 2's PWM, now at F_CPU / 8 / 256,
//     and its overflow is that PWM's period.
//   - What it costs: test_clock_cost.cpp; the probe: clock_probe.h.
#include <avr_ioport.h>
#include <sim_avr.h>
#include <sim_interrupts.h>
#include <sim_irq.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "board_info.h"
#include "main_context.h"
#include "schedule.h"
#include "sim_fixture.h"
#include "clock_probe.h"

namespace {

using clocktest::ImageCase;
using clocktest::kImages;
using clocktest::Probe;
using clocktest::vector_jump_cycles;
using clocktest::vectors_of;
using clocktest::Vectors;

// (main_context.h): the ticks it returned and the cycles it spanned.
struct NowCall {
  uint32_t ticks;
  uint64_t start, end;
};

NowCall call_now(sim::Machine& m, uint32_t now_byte_address, bool interrupts_off = false) {
  const simtest::MainCall c = simtest::call_in_main(m, now_byte_address, interrupts_off);
  return NowCall{c.result, c.start, c.end};
}

uint32_t now_address(const std::string& elf) {
  const sim::ElfSymbol s = sim::find_symbol(elf, "_ZN5clock3nowEv");
  EXPECT_TRUE(s.found) << elf << " carries no clock::now()";
  return s.value;
}

uint64_t next_random(uint64_t& state) {
  state = state * 6364136223846793005ull + 1442695040888963407ull;
  return state >> 33;
}

// The overflows after the first that the vector served are exactly one
// period apart, and the vector counted each one once.
void expect_regular_overflows(const Probe& p, uint64_t period, const char* image) {
  ASSERT_GE(p.clock_entries.size(), 10u) << image;
  // Wraps from the first one the vector served (earlier ones come before
  // clock::init() enables the interrupt, and on the Uno before the timer's
  // last set-up).
  size_t first = 0;
  while (first + 1 < p.wraps.size() && p.wraps[first + 1] <= p.clock_entries.front()) ++first;
  ASSERT_LT(first + 1, p.wraps.size());
  size_t irregular = 0;
  for (size_t i = first + 1; i < p.wraps.size(); ++i) irregular += p.wraps[i] - p.wraps[i - 1] != period;
  EXPECT_EQ(irregular, 0u) << image << ": overflows not " << period << " cycles apart";
  // Every wrap served once, before the next wrap.
  size_t e = 0;
  size_t unserved = 0;
  for (size_t i = first; i + 1 < p.wraps.size(); ++i) {
    while (e < p.clock_entries.size() && p.clock_entries[e] < p.wraps[i]) ++e;
    const bool served = e < p.clock_entries.size() && p.clock_entries[e] < p.wraps[i + 1];
    unserved += !served;
  }
  EXPECT_EQ(unserved, 0u) << image << ": overflows the vector did not count";
  // The software part counts up by one each time.
  size_t jumps = 0;
  for (size_t i = 1; i < p.high_after.size(); ++i) jumps += p.high_after[i] != p.high_after[i - 1] + 1;
  EXPECT_EQ(jumps, 0u) << image << ": clock_high did not count one per overflow";
  EXPECT_EQ(p.high_after.size(), p.clock_entries.size());
}

void check_clock_under_load(const ImageCase& c) {
  SCOPED_TRACE(c.image);
  const std::string elf = simtest::image(c.image);
  sim::Machine m(elf);
  Probe probe(m, elf);
  const uint32_t now_at = now_address(elf);
  const uint64_t P = c.prescaler;
  const uint64_t period = 256 * P;
  m.serial().add_line(c.move);
  for (int i = 0; i < c.junk; ++i) m.serial().add_line("NOP");
  m.serial().add_line("POS");

  // Calls at pseudo-random points, and calls timed so that TCNT0 is read
  // within a few cycles of the wrap, on both sides (now() reads it about 16
  // to 20 cycles after it starts, more when an interrupt comes between):
  // the offsets before the predicted wrap sweep 0..63 cycles.
  std::vector<NowCall> calls;
  uint64_t state = 7;
  size_t k = 0;
  const uint64_t budget = uint64_t(m.f_cpu()) * 20;
  const uint64_t give_up = m.cycles() + budget;
  ASSERT_TRUE(m.run([&] { return m.serial().banner_seen(); }, budget) == sim::RunEnd::done);
  while (!m.serial().finished() && m.cycles() < give_up) {
    uint64_t target;
    if (k % 3 == 2 || probe.wraps.empty()) {
      target = m.cycles() + 50 + next_random(state) % period;
    } else {
      uint64_t wrap = probe.wraps.back() + period;
      while (wrap < m.cycles() + 70) wrap += period;
      target = wrap - (k % 64);
    }
    ++k;
    if (!simtest::run_to_main(m, target, budget)) break;
    if (m.serial().finished()) break;
    calls.push_back(call_now(m, now_at));
  }
  ASSERT_TRUE(m.serial().finished()) << "the script did not finish";
  EXPECT_EQ(m.axis(c.axis)->step_cycles.size(), c.steps) << "the move is not exact";
  // The UART was busy until the last step.
  ASSERT_GT(m.serial().responses().size(), size_t(c.junk));
  EXPECT_GT(m.serial().responses()[size_t(c.junk)].answer_cycle, m.axis(c.axis)->step_cycles.back());
  // Then, the engine idle, calls with interrupts off (as from a cli section,
  // where the vector cannot run: a wrap during the call leaves TOV0 set),
  // timed across the wrap the same way.
  const size_t under_load = calls.size();
  for (int j = 0; j < 192; ++j) {
    uint64_t wrap = probe.wraps.back() + period;
    while (wrap < m.cycles() + 70) wrap += period;
    ASSERT_TRUE(simtest::run_to_main(m, wrap - uint64_t(j % 64), budget));
    calls.push_back(call_now(m, now_at, true));
  }

  // The overflows and their vector.
  expect_regular_overflows(probe, period, c.image);

  // now(): never backwards; one constant offset D fits every call: the
  // value is (cycle - T0) / P + D at some cycle of the call, T0 the cycle
  // the wraps say the count was 0 at (wrap k: T0 + 256 P k).
  ASSERT_GE(under_load, 300u);
  const uint64_t t0 = probe.wraps.back() % period;
  auto hw = [&](uint64_t cycle) { return int64_t((cycle - t0) / P); };
  int64_t lo = INT64_MIN, hi = INT64_MAX;
  size_t backwards = 0, straddling = 0, straddling_off = 0;
  for (size_t i = 0; i < calls.size(); ++i) {
    const NowCall& n = calls[i];
    if (i > 0) backwards += n.ticks < calls[i - 1].ticks;
    // D = ticks - hw(read cycle): between ticks - hw(end) and ticks - hw(start).
    lo = std::max(lo, int64_t(n.ticks) - hw(n.end));
    hi = std::min(hi, int64_t(n.ticks) - hw(n.start));
    const auto w = std::upper_bound(probe.wraps.begin(), probe.wraps.end(), n.start);
    const bool across = w != probe.wraps.end() && *w <= n.end;
    (i < under_load ? straddling : straddling_off) += across;
  }
  EXPECT_EQ(backwards, 0u);
  EXPECT_LE(lo, hi) << "no single offset fits every value: the clock does not tick at F_CPU / " << P;
  // The wrap-timed calls: many of them saw the counter wrap during the call.
  EXPECT_GE(straddling, under_load / 8);
  EXPECT_GE(straddling_off, 40u);
  std::printf("%s: %zu calls of clock::now() under load (%zu across a wrap), %zu with interrupts off (%zu across a "
              "wrap), %zu overflows: all consistent with one tick per %llu cycles\n",
              c.image, under_load, straddling, calls.size() - under_load, straddling_off,
              probe.clock_entries.size(), (unsigned long long)P);
}

}  // namespace

TEST(Clock, UnoTicksEveryEightCyclesUnderFullRateStepping) { check_clock_under_load(kImages[0]); }
TEST(Clock, M32TicksEverySixtyFourCyclesUnderFullRateStepping) { check_clock_under_load(kImages[1]); }
TEST(Clock, M16TicksEverySixtyFourCyclesUnderFullRateStepping) { check_clock_under_load(kImages[2]); }
TEST(Clock, M16At8MHzTicksEverySixtyFourCyclesUnderFullRateStepping) { check_clock_under_load(kImages[3]); }

TEST(Clock, StartsAtBootAndCountsWhileIdle) {
  // Without any command: the vector runs from the banner on, and now()
  // agrees with the cycle counter over a quiet stretch (no handler but the
  // clock's), to the tick.
  for (const ImageCase& c : kImages) {
    SCOPED_TRACE(c.image);
    const std::string elf = simtest::image(c.image);
    sim::Machine m(elf);
    Probe probe(m, elf);
    ASSERT_EQ(m.run([&] { return m.serial().banner_seen(); }, uint64_t(m.f_cpu())), sim::RunEnd::done);
    const uint64_t P = c.prescaler;
    ASSERT_TRUE(simtest::run_to_main(m, m.cycles() + 1000, 100000));
    const NowCall a = call_now(m, now_address(elf));
    ASSERT_TRUE(simtest::run_to_main(m, m.cycles() + m.f_cpu() / 10, m.f_cpu()));
    const NowCall b = call_now(m, now_address(elf));
    // 0.1 s later by the cycle counter: ticks = cycles / P, within the
    // calls' own length.
    const double expected = double(b.start - a.start) / P;
    EXPECT_NEAR(double(b.ticks - a.ticks), expected, double(std::max(a.end - a.start, b.end - b.start)) / P + 1);
    EXPECT_EQ(probe.high_after.size(), probe.clock_entries.size());
    expect_regular_overflows(probe, 256 * P, c.image);
  }
}

TEST(Clock, UnoTimer0StillDrivesStepper2sPwmAtItsNewRate) {
  // Stepper 2 (axis Y) holds microstep 2 of 16: A 250, B 50 (docs/modes.md).
  // Its enables OC0A (D6) and OC0B (D5) run at 16 MHz / 8 / 256 = 7812.5 Hz,
  // high for OCR + 1 ticks of 8 cycles; every period starts (BOTTOM, the pin
  // set) on the cycle TOV0 is set: the PWM's period is the clock's overflow.
  // Stepper 1 on Timer2 keeps 62.5 kHz.
  const std::string elf = simtest::image("uno");
  sim::Machine m(elf);
  Probe probe(m, elf);
  for (const char* l : {"MODE X16", "MOVE X2", "MODE Y16", "MOVE Y2", "WAIT"}) m.serial().add_line(l);
  ASSERT_EQ(m.run_script(uint64_t(m.f_cpu()) * 5), sim::RunEnd::done);
  const uint8_t* data = m.avr()->data;
  EXPECT_EQ(data[0x44], 0xA3);         // TCCR0A: COM0A 10, COM0B 10, WGM01:0 11
  EXPECT_EQ(data[0x45] & 0x0F, 0x02);  // TCCR0B: WGM02 0, CS0 010: clk / 8
  EXPECT_EQ(data[0x6E] & 0x01, 0x01);  // TIMSK0: TOIE0
  EXPECT_EQ(data[0xB1] & 0x0F, 0x01);  // TCCR2B: clk / 1
  struct PinCase {
    char port;
    uint8_t bit;
    uint64_t period;
    int duty;
  };
  const PinCase pins[] = {{'D', 6, 2048, 250}, {'D', 5, 2048, 50}, {'B', 3, 256, 250}, {'D', 3, 256, 50}};
  std::vector<const std::vector<sim::PinEdge>*> logs;
  for (const PinCase& p : pins) logs.push_back(&m.watch_pin(p.port, p.bit));
  const size_t wraps_before = probe.wraps.size();
  const uint64_t until = m.cycles() + 2048 * 60;
  m.run([&] { return m.cycles() >= until; }, 2048 * 80);
  for (size_t k = 0; k < logs.size(); ++k) {
    SCOPED_TRACE(testing::Message() << "pin P" << pins[k].port << int(pins[k].bit));
    const simtest::PwmTrace t = simtest::pwm_trace(*logs[k]);
    const std::vector<uint64_t>& rises = t.rises;
    const uint64_t high_total = t.high_total;
    const size_t highs = t.highs;
    ASSERT_GE(rises.size(), 50u);
    const double mean = double(rises.back() - rises.front()) / double(rises.size() - 1);
    EXPECT_DOUBLE_EQ(mean, double(pins[k].period));
    ASSERT_GT(highs, 0u);
    const double ticks = double(pins[k].period) / 256;
    EXPECT_NEAR(double(high_total) / double(highs), (pins[k].duty + 1) * ticks, ticks);
    if (pins[k].period == 2048) {
      // Each rise on a wrap.
      size_t off = 0;
      for (uint64_t r : rises)
        off += std::find(probe.wraps.begin() + long(wraps_before), probe.wraps.end(), r) == probe.wraps.end();
      EXPECT_EQ(off, 0u) << "PWM periods that do not start on an overflow";
    }
  }
}

