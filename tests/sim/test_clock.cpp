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
//   - What it costs: the vector's cycles and CPU share, how long it can
//     hold the step vector off (its entry: response, JMP, SEI and the one
//     instruction after SEI), how much later that makes a software step
//     edge, its flash and RAM. Printed, and bounded.
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

namespace {

struct ImageCase {
  const char* image;
  uint16_t prescaler;  // Timer0's, as the board claims it (firmware/boards/*.h)
  const char* move;    // a move of the image's fastest axis at its top rate
  char axis;
  uint32_t steps;
  int junk;  // NOP lines: their error answers keep the UART busy for the whole move
};

const ImageCase kImages[] = {
    {"uno", 8, "MOVE Z150000 F160000 A300000", 'Z', 150000, 600},  // 1.5 s, 0.4 s of it at 160 kHz
    {"m32-direct", 64, "MOVE X24000 F40000 A800000", 'X', 24000, 280},  // 0.6 s; the m32 printer and mill images have no MOVE
    {"m16", 64, "MOVE Z12000 F20000 A800000", 'Z', 12000, 280},    // 0.6 s
    {"m16-8mhz", 64, "MOVE Z6000 F10000 A800000", 'Z', 6000, 90},  // 0.6 s at 38400 baud
};

// Vector numbers (the datasheets' interrupt vector tables).
struct Vectors {
  int step;   // TIMER1_COMPA
  int clock;  // TIMER0_OVF
};
Vectors vectors_of(const std::string& mcu) {
  if (mcu == "atmega328p") return {11, 16};
  if (mcu == "atmega32") return {7, 11};
  if (mcu == "atmega16") return {6, 9};
  ADD_FAILURE() << "no vector table for " << mcu;
  return {0, 0};
}

// Cycles of the jump in vector `v`'s table entry (4 bytes each on these
// parts): JMP 3, or RJMP 2 where the linker's relaxation reached the
// handler from the table (the ATmega16's 16 KB).
int vector_jump_cycles(sim::Machine& m, int v) {
  const uint8_t* f = m.avr()->flash + 4 * v;
  const uint16_t word = uint16_t(f[0] | f[1] << 8);
  if ((word & 0xF000) == 0xC000) return 2;
  EXPECT_EQ(word & 0xFE0E, 0x940C) << "vector " << v << " is neither JMP nor RJMP";
  return 3;
}

// A symbol's value and size from the image's symbol table.

// Watches the clock's and the step engine's vectors through simavr's
// interrupt IRQs: when TOV0 was set (the wrap), when each vector was entered
// and left, clock_high after every overflow vector, and for every step
// interrupt how long it waited and whether it nested in the overflow vector.
class Probe {
 public:
  struct StepIrq {
    uint64_t pending = 0;  // the compare match (OCF1A set)
    uint64_t entry = 0;    // its response began (simavr adds the 4 cycles before it says so)
    bool nested = false;   // it interrupted the overflow vector
    bool held = false;     // its match came while the overflow vector was being entered or ran (held())
    uint64_t wait() const { return entry - pending; }
  };

  Probe(sim::Machine& m, const std::string& elf) : m_(m), v_(vectors_of(m.board().mcu)) {
    high_addr_ = sim::read_data_symbol(elf, "clock_high");
    avr_irq_t* clock = avr_get_interrupt_irq(m.avr(), uint8_t(v_.clock));
    avr_irq_t* step = avr_get_interrupt_irq(m.avr(), uint8_t(v_.step));
    avr_irq_register_notify(clock + AVR_INT_IRQ_PENDING, &Probe::on_clock_pending, this);
    avr_irq_register_notify(clock + AVR_INT_IRQ_RUNNING, &Probe::on_clock_running, this);
    avr_irq_register_notify(step + AVR_INT_IRQ_PENDING, &Probe::on_step_pending, this);
    avr_irq_register_notify(step + AVR_INT_IRQ_RUNNING, &Probe::on_step_running, this);
  }

  uint32_t high() const {
    const uint8_t* d = m_.avr()->data + high_addr_;
    return uint32_t(d[0]) | uint32_t(d[1]) << 8 | uint32_t(d[2]) << 16;
  }

  std::vector<uint64_t> wraps;         // TOV0 set
  std::vector<uint64_t> clock_entries;  // overflow vector entered (response began)
  std::vector<uint64_t> clock_exits;    // and the end of its RETI
  std::vector<uint32_t> high_after;    // clock_high at each of its RETIs
  std::vector<StepIrq> steps;
  uint64_t clock_exclusive = 0;  // cycles in the overflow vector, nested handlers excluded, RETI included

 private:
  static void on_clock_pending(avr_irq_t*, uint32_t value, void* p) {
    auto* self = static_cast<Probe*>(p);
    const uint64_t now = self->m_.cycles();
    // simavr raises the pending IRQ again on a flag already set; one wrap
    // per cycle.
    if (value && (self->wraps.empty() || self->wraps.back() != now)) self->wraps.push_back(now);
  }
  static void on_clock_running(avr_irq_t*, uint32_t value, void* p) {
    auto* self = static_cast<Probe*>(p);
    avr_t* avr = self->m_.avr();
    const uint64_t now = self->m_.cycles();
    if (value) {
      const uint64_t response = uint64_t(2 + avr->address_size);
      self->clock_entries.push_back(now - response);
      self->clock_in_ = now - response;
      self->nested_ = 0;
    } else {
      self->high_after.push_back(self->high());
      // RETI's own 4 cycles are still to come.
      self->clock_exits.push_back(now + 4);
      self->clock_exclusive += now + 4 - self->clock_in_ - self->nested_;
    }
  }
  static void on_step_pending(avr_irq_t*, uint32_t value, void* p) {
    auto* self = static_cast<Probe*>(p);
    if (value) self->step_pending_ = self->m_.cycles();
  }
  static void on_step_running(avr_irq_t*, uint32_t value, void* p) {
    auto* self = static_cast<Probe*>(p);
    avr_t* avr = self->m_.avr();
    const uint64_t now = self->m_.cycles();
    const avr_int_table_p table = &avr->interrupts;
    if (value) {
      StepIrq s;
      s.pending = self->step_pending_;
      s.entry = now - uint64_t(2 + avr->address_size);
      // The vector it interrupted is still on top of simavr's stack of
      // running vectors (the step vector is pushed after this callback).
      s.nested = table->running_ptr > 0 && table->running[table->running_ptr - 1]->vector == self->v_.clock;
      self->steps.push_back(s);
      self->step_in_ = s.entry;
    } else if (table->running_ptr > 0 && table->running[table->running_ptr - 1]->vector == self->v_.clock) {
      // Leaving a step vector that nested in the overflow vector (simavr has
      // popped it already: the overflow vector is on top again).
      self->nested_ += now + 4 - self->step_in_;
    }
  }

 public:
  // Marks the step interrupts whose match came after an overflow vector's
  // response had begun (a match on that very cycle wins: the step vector
  // comes first in the table) and before its RETI had ended: the ones the
  // overflow vector could hold off.
  void classify() {
    for (StepIrq& s : steps) {
      const auto e = std::lower_bound(clock_entries.begin(), clock_entries.end(), s.pending);
      if (e == clock_entries.begin()) continue;
      const size_t k = size_t(e - clock_entries.begin()) - 1;
      s.held = k < clock_exits.size() && s.pending < clock_exits[k];
    }
  }

 private:
  sim::Machine& m_;
  Vectors v_;
  uint16_t high_addr_ = 0;
  uint64_t step_pending_ = 0, clock_in_ = 0, step_in_ = 0, nested_ = 0;
};

// A call of the image's clock::now() from the main loop's context
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

namespace {

struct CostCase {
  const char* image;
  uint16_t prescaler;
  const char* move;  // a quiet move of a software-pulsed axis at its top rate
  char axis;
  uint32_t steps, rate, accel;
};

// Software step edges only: a timer-pulsed edge (Uno Z) is made by the
// compare match and cannot be late (tests/sim/test_step_timing.cpp). Each
// rate is near the axis's top and its interval is chosen so that the
// overflow lands on every phase of it, 8 or 16 cycles apart (the phase moves
// by the overflow period modulo the interval, 384 of 400 or 1000 cycles, 48
// of 1000 on the Uno), and so some step interrupts meet the vector whatever
// the start-up time: with an interval of 800 the phases are 32 cycles apart,
// wider than the vector, and a build can miss it altogether.
const CostCase kCosts[] = {
    {"uno", 8, "MOVE X6000 F16000 A300000", 'X', 6000, 16000, 300000},
    {"m32-direct", 64, "MOVE X40000 F40000 A800000", 'X', 40000, 40000, 800000},
    {"m16", 64, "MOVE Z16000 F16000 A800000", 'Z', 16000, 16000, 800000},
    {"m16-8mhz", 64, "MOVE Z8000 F8000 A800000", 'Z', 8000, 8000, 800000},
};

}  // namespace

TEST(Clock, CostsTheStepPathOnlyTheOverflowVectorsEntry) {
  for (const CostCase& c : kCosts) {
    SCOPED_TRACE(c.image);
    const std::string elf = simtest::image(c.image);
    const double period = 256.0 * c.prescaler;
    double per_overflow = 0;
    {
      // Idle: the vector alone, nothing nests in it.
      sim::Machine m(elf);
      Probe probe(m, elf);
      ASSERT_EQ(m.run([&] { return m.serial().banner_seen(); }, uint64_t(m.f_cpu())), sim::RunEnd::done);
      const size_t idle_from = probe.clock_entries.size();
      const uint64_t idle_cycles0 = probe.clock_exclusive;
      ASSERT_TRUE(simtest::run_to_main(m, m.cycles() + uint64_t(m.f_cpu()) / 20, m.f_cpu()));
      const size_t idle_n = probe.clock_entries.size() - idle_from;
      ASSERT_GT(idle_n, 10u);
      per_overflow = double(probe.clock_exclusive - idle_cycles0) / double(idle_n);
      // 29 cycles with a JMP in the table, response and RETI included; 6
      // more on every 256th.
      const double cycles = 26.0 + vector_jump_cycles(m, vectors_of(m.board().mcu).clock);
      EXPECT_GE(per_overflow, cycles);
      EXPECT_LE(per_overflow, cycles + 6.0 * 2 / double(idle_n) + 0.01);
    }

    // A quiet move at the top software rate: which step interrupts the
    // vector held off, by how much, and what that did to their edges.
    sim::Machine m(elf);
    Probe probe(m, elf);
    m.serial().add_line(c.move);
    const size_t first_step = 0;
    ASSERT_EQ(m.run_script(uint64_t(m.f_cpu()) * 10), sim::RunEnd::done);
    const std::vector<uint64_t>& edges = m.axis(c.axis)->step_cycles;
    ASSERT_EQ(edges.size(), c.steps);
    probe.classify();
    uint64_t held_wait = 0, other_wait = 0;
    size_t held = 0;
    for (size_t i = first_step; i < probe.steps.size(); ++i) {
      const Probe::StepIrq& s = probe.steps[i];
      if (s.held) {
        ++held;
        held_wait = std::max(held_wait, s.wait());
      } else {
        other_wait = std::max(other_wait, s.wait());
      }
    }
    // Every software edge against the schedule; its interrupt: the last
    // step interrupt entered before it.
    const std::vector<uint32_t> plan =
        sim::planned_schedule(c.steps, sim::Ramp{m.f_cpu(), c.rate, c.accel});
    ASSERT_EQ(plan.size(), c.steps);
    int64_t held_late = INT64_MIN, other_late = INT64_MIN, other_early = INT64_MAX;
    uint64_t due = edges[0];
    size_t s = first_step;
    for (size_t i = 1; i < edges.size(); ++i) {
      due += plan[i];
      while (s + 1 < probe.steps.size() && probe.steps[s + 1].entry < edges[i]) ++s;
      const int64_t late = int64_t(edges[i]) - int64_t(due);
      if (probe.steps[s].held) held_late = std::max(held_late, late);
      else {
        other_late = std::max(other_late, late);
        other_early = std::min(other_early, late);
      }
    }
    const double share = per_overflow / period;
    std::printf(
        "%s: overflow vector %.1f cycles every %.0f (%.2f %% of the CPU); %s at %u Hz: %zu of %zu step interrupts "
        "met it, waited up to %llu cycles (others up to %llu); their edges %lld cycles after the schedule at worst, "
        "the others' %lld..%lld: %lld cycles later at worst\n",
        c.image, per_overflow, period, 100 * share, c.move, c.rate, held, probe.steps.size() - first_step,
        (unsigned long long)held_wait, (unsigned long long)other_wait, (long long)(held ? held_late : 0),
        (long long)other_early, (long long)other_late, (long long)(held ? held_late - other_late : 0));
    // The vector can be in the way only with its entry: 4 cycles of response,
    // JMP 3, SEI 1 and the PUSH after it (2), the match at least one cycle
    // after its response began; after that the step vector nests in it.
    ASSERT_GT(held, 0u) << "no step interrupt met the overflow vector: nothing measured";
    EXPECT_LE(held_wait, 9u) << "the overflow vector holds the step vector off for more than its entry";
    EXPECT_LE(held_late - other_late, 9);
  }
}

TEST(Clock, FlashAndRamPerImage) {
  // The vector, now() (in the vector's section, so every image has it),
  // init() and the three bytes above TCNT0. The driver board has none.
  for (const ImageCase& c : kImages) {
    const std::string elf = simtest::image(c.image);
    const Vectors v = vectors_of(sim::read_board_descriptor(elf).mcu);
    const sim::ElfSymbol vec = sim::find_symbol(elf, "__vector_" + std::to_string(v.clock));
    const sim::ElfSymbol now = sim::find_symbol(elf, "_ZN5clock3nowEv");
    const sim::ElfSymbol init = sim::find_symbol(elf, "_ZN5clock4initEv");
    const sim::ElfSymbol high = sim::find_symbol(elf, "clock_high");
    ASSERT_TRUE(vec.found && now.found && high.found) << c.image;
    // init() may be inlined into main().
    std::printf("%s: clock flash %u B (vector %u, now() %u, init() %s), RAM %u B\n", c.image,
                vec.size + now.size + init.size, vec.size, now.size,
                init.found ? std::to_string(init.size).c_str() : "inlined", high.size);
    EXPECT_EQ(high.size, 3u);
    EXPECT_LE(vec.size + now.size + init.size, 160u);
  }
  const std::string driver = simtest::image("m32-driver");
  EXPECT_FALSE(sim::find_symbol(driver, "clock_high").found);
  EXPECT_FALSE(sim::find_symbol(driver, "_ZN5clock3nowEv").found);
}

