// The harness's own measurements: the cycle budget, interrupt accounting and
// the stack high-water mark (step timestamps are covered by test_step_timing).
#include <sim_avr.h>

#include "sim_fixture.h"

TEST(Harness, AHungRunEndsAtItsCycleBudget) {
  // The driver-board image never prints a banner, so the serial script can
  // never finish: the run must stop at the budget, not hang.
  sim::Machine m(simtest::image("m32-driver"));
  m.serial().add_line("POS");
  EXPECT_EQ(m.run_script(1000000), sim::RunEnd::budget_spent);
  EXPECT_GE(m.cycles(), 1000000u);
  EXPECT_LT(m.cycles(), 1000000u + 8);  // stops within one instruction
}

TEST(Harness, EveryStepIsOneStepInterrupt) {
  // Uno axis Z: each step is one compare-match vector (no interval here is
  // longer than the 16-bit timer), so the vector's count is the step count.
  auto m = simtest::run("uno", {"MOVE Z1000 F50000 A400000"});
  ASSERT_EQ(m->axis('Z')->step_cycles.size(), 1000u);
  const sim::IsrStats& step = m->isr_stats().at(11);  // TIMER1_COMPA on the ATmega328P
  EXPECT_EQ(step.count, 1000u);
  // Cycles inside it are counted, bounded and below the elapsed time.
  EXPECT_GT(step.max_cycles, 20u);
  EXPECT_LT(step.total_cycles, m->cycles());
}

TEST(Harness, StackHighWaterIsFoundByPainting) {
  auto m = simtest::run("uno", {"MOVE X50", "POS"});
  const unsigned used = m->stack_bytes();
  // main's frame, a call or two and the general step handler's 17 saved
  // registers: more than 20 bytes, and far from the 2 KB of RAM.
  EXPECT_GT(used, 20u);
  EXPECT_LT(used, 512u);
  // A byte disturbed deeper down is found: the scan, not a fixed answer.
  avr_t* avr = m->avr();
  const unsigned deeper = used + 100;
  avr->data[avr->ramend + 1 - deeper] = 0;
  EXPECT_EQ(m->stack_bytes(), deeper);
}
