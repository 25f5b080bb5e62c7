// What the time base (firmware/engine/clock.h) costs on the real images:
// the vector's cycles and CPU share, how long it can hold the step vector
// off (its entry: response, JMP, SEI and the one instruction after SEI), how
// much later that makes a software step edge, its flash and RAM. Printed,
// and bounded. The clock itself: test_clock.cpp; the probe: clock_probe.h.
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

}  // namespace

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

