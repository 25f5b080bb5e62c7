// A main loop that falls behind must never cost a step. The Uno's Z runs at
// 160 kHz, where the assembly fast path takes each next segment of a
// deceleration by itself; stalls of the main loop (it runs nothing but
// clock::now() for a while, interrupts all on: main_context.h) at many
// points of the move, of many lengths, let the queue run low or dry at
// every kind of moment: a segment that arrives just after the fast path
// looked for it is then taken by the C handler, late. Whatever happens to
// the timing, the pins must make every step and POS must say so.
#include <cstdio>

#include "board_info.h"
#include "main_context.h"
#include "sim_fixture.h"

TEST(StarvedEngine, AStalledMainLoopCostsNoStepAt160kHz) {
  const std::string elf = simtest::image("uno");
  const sim::ElfSymbol now = sim::find_symbol(elf, "_ZN5clock3nowEv");
  ASSERT_TRUE(now.found);
  sim::Machine m(elf);
  m.serial().add_line("MOVE Z100000 F160000 A300000");
  m.serial().add_line("POS");
  const auto& st = m.axis('Z')->step_cycles;
  const uint64_t budget = uint64_t(m.f_cpu()) * 20;
  int stalls = 0;
  // Stall points through the whole move (accelerating, cruising, slowing
  // down), each a different length: 0.2 .. 30 ms.
  for (uint32_t at = 1500, k = 0; at < 99000; at += 1300 + 97 * (k % 7), ++k) {
    ASSERT_EQ(m.run([&] { return st.size() >= at; }, budget), sim::RunEnd::done) << "stuck before step " << at;
    ASSERT_TRUE(simtest::run_to_main(m, m.cycles(), budget));
    const uint64_t until = m.cycles() + uint64_t(m.f_cpu() / 1e6 * (200 + (k * 3733) % 29800));
    while (m.cycles() < until) simtest::call_in_main(m, now.value);
    ++stalls;
  }
  ASSERT_EQ(m.run_script(budget), sim::RunEnd::done);
  std::printf("%d stalls, %d starvations\n", stalls, m.starvations());
  EXPECT_GT(m.starvations(), 0) << "no stall ran the queue dry: the test tests nothing";
  EXPECT_EQ(st.size(), 100000u);
  EXPECT_EQ(m.axis('Z')->steps(), 100000.0);
  const std::vector<std::string> msgs = m.serial().messages();
  ASSERT_FALSE(msgs.empty());
  EXPECT_NE(msgs.back().find("Z:100000"), std::string::npos) << msgs.back();
}
