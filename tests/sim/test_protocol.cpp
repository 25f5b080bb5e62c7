// Bad input on the real image: clear errors, a machine that carries on, and
// nothing acknowledged lost (docs/protocol.md).
#include <algorithm>
#include <string>

#include "sim_fixture.h"

TEST(Protocol, MalformedAndOverlongLinesAreRefusedAndTheMachineCarriesOn) {
  const std::string overlong = "MOVE X1 " + std::string(80, 'F');
  auto m = simtest::run("m32", {"MOVE X1.5", "MOVE X99999999999", "MOVE X10 F0", "MOVE X10 A0",
                                overlong, "MOVE X20000000", "MOVE Q5", "MOVE X10", "POS"});
  const std::vector<std::string> expected = {"error: bad number",
                                             "error: number out of range",
                                             "error: speed must be above 0",
                                             "error: acceleration must be above 0",
                                             "error: line too long (max 80 characters)",
                                             "error: move too long (max 16777216 steps)",
                                             "error: word not allowed here"};
  EXPECT_EQ(m->serial().errors(), expected);
  EXPECT_EQ(m->serial().lines_ok(), 2u);  // the last MOVE and POS
  EXPECT_EQ(m->axis('X')->steps(), 10.0);
}

TEST(Protocol, AFloodLosesNoAcknowledgedLine) {
  // Twelve moves of 1, 2, 4 ... 2048 steps sent back to back, ignoring the
  // answers: the receive ring overflows while a move waits for the planner.
  // Each move's steps are one bit of the final position, so the position
  // says which moves ran: as many as were answered "ok", each one whole (a
  // line spliced across the gap would add a number that is no single bit).
  sim::Machine m(simtest::image("m32"));
  // An empty script: the host's closing WAIT goes out after the banner; its
  // answer must be in before the flood starts, or the two streams would mix.
  ASSERT_EQ(m.run_script(16000000), sim::RunEnd::done);
  const size_t before = m.serial().received().size();
  std::string flood;
  for (int i = 0; i < 12; ++i) flood += "MOVE X" + std::to_string(1 << i) + " F20000 A200000\n";
  m.serial().send_raw(flood);
  const auto& got = m.serial().received();
  const auto answers = [&] {
    return std::count_if(got.begin() + long(before), got.end(),
                         [](const std::string& l) { return l == "ok" || l.rfind("error", 0) == 0; });
  };
  // Lost bytes may take newlines with them, so fewer than twelve lines can
  // end: run until the answers stop and the motion has ended.
  long last = -1;
  for (int i = 0; i < 20 && answers() != last; ++i) {
    last = answers();
    m.run([] { return false; }, 16000000 / 2);
  }
  const auto oks = std::count(got.begin() + long(before), got.end(), std::string("ok"));
  const auto overruns =
      std::count(got.begin() + long(before), got.end(), std::string("error: serial overrun, line dropped"));
  EXPECT_EQ(oks + overruns, answers());  // every answer is one of the two
  EXPECT_LE(answers(), 12);
  EXPECT_GT(overruns, 0);  // the flood did overflow
  EXPECT_GT(oks, 0);
  const int position = int(m.axis('X')->steps());
  EXPECT_EQ(__builtin_popcount(unsigned(position)), oks) << "position " << position;
}
