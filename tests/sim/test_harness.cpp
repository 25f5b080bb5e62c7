// The harness's own measurements: the cycle budget, interrupt accounting and
// the stack high-water mark (step timestamps are covered by test_step_timing).
#include <sim_avr.h>

#include <string>

#include "sim_fixture.h"

namespace {

avr_cycle_count_t never_mind(avr_t*, avr_cycle_count_t, void*) { return 0; }

// A cycle timer that registers more far-off timers than simavr has slots, as
// the level pollers piling up on a PWM pin did (issue 7, docs/simulator.md).
avr_cycle_count_t fill_the_timer_pool(avr_t* avr, avr_cycle_count_t, void*) {
  static char params[MAX_CYCLE_TIMERS + 1];
  for (char& p : params) avr_cycle_timer_register(avr, 1000000000, never_mind, &p);
  return 0;
}

}  // namespace

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
  auto m = simtest::run("uno", {"MOVE Z1000 F50000 A300000"});
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

TEST(Harness, ARunInWhichSimavrDropsAnEventFails) {
  // simavr reports a lost event only with an error-level log line ("CYCLE:
  // avr_cycle_timer_register: pool is full (64)!", "... ran out of timers")
  // and runs on without it. Here its cycle-timer pool overflows 100000 cycles
  // into the run: the run must stop right there and fail with the message.
  sim::Machine m(simtest::image("uno"));
  avr_cycle_timer_register(m.avr(), 100000, fill_the_timer_pool, nullptr);
  std::string what;
  testing::internal::CaptureStderr();
  try {
    m.run([] { return false; }, 1000000);
  } catch (const sim::SimulatorFault& e) {
    what = e.what();
  }
  const std::string printed = testing::internal::GetCapturedStderr();
  EXPECT_NE(what.find("pool is full (64)"), std::string::npos) << "no SimulatorFault, or another one: " << what;
  EXPECT_NE(printed.find("pool is full (64)"), std::string::npos) << printed;  // still printed, as simavr would
  EXPECT_GE(m.simavr_errors(), 1u);
  EXPECT_EQ(m.first_simavr_error().find("CYCLE: avr_cycle_timer_register: pool is full"), 0u)
      << m.first_simavr_error();
  EXPECT_GE(m.cycles(), 100000u);
  EXPECT_LT(m.cycles(), 100000u + 8);  // within one instruction
  // The machine stays failed: a later run cannot hide the loss.
  EXPECT_THROW(m.run([] { return false; }, 1000), sim::SimulatorFault);
}
