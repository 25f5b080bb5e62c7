// Bad input on the real image: clear errors, a machine that carries on, and
// nothing acknowledged lost (docs/protocol.md).
#include <sim_avr.h>

#include <algorithm>
#include <cstring>
#include <string>

#include "board_info.h"
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

TEST(Protocol, ControlAndNonAsciiBytesRefuseTheWholeLine) {
  // No prefix of a line ever runs: a NUL (or any byte outside printable ASCII
  // and TAB) anywhere in a line makes all of it an error, on every board.
  const std::string bad_bytes[] = {std::string(1, '\0'), "\x01", "\x08", "\x1b", "\x7f", "\x80", "\xff"};
  for (const char* image : {"uno", "m32", "m16"}) {
    std::vector<std::string> lines;
    for (const std::string& b : bad_bytes) {
      for (const std::string& line : {"MODE X1" + b + "6", "MOVE Z1" + b + "00", "MOVE Z5" + b + " junk F0",
                                      b + "POS", "MOVE Z5" + b})
        lines.push_back(line);
    }
    lines.push_back("POS");
    auto m = simtest::run(image, lines);
    const std::vector<std::string> errors = m->serial().errors();
    ASSERT_EQ(errors.size(), lines.size() - 1) << image;
    for (const std::string& e : errors) EXPECT_EQ(e, "error: control or non-ASCII byte in line") << image;
    EXPECT_EQ(m->serial().lines_ok(), 1u) << image;
    for (const sim::AxisTrace& a : m->axes()) EXPECT_TRUE(a.step_cycles.empty()) << image << " " << a.name;
    const std::vector<std::string> msgs = m->serial().messages();
    ASSERT_EQ(msgs.size(), 1u);
    EXPECT_EQ(msgs[0].find(":-"), std::string::npos) << msgs[0];  // still all at zero
  }
}

TEST(Protocol, BlankLinesAreAnsweredOkAndDoNothing) {
  // docs/protocol.md: a line of spaces and tabs is answered "ok"; an empty
  // line (two line ends in a row, as in CRLF) is no line and gets no answer.
  auto m = simtest::run("m32", {" ", "\t", " \t  \t", "MOVE X3", "   ", "POS"});
  ASSERT_EQ(m->serial().responses().size(), 6u);
  for (const sim::Response& r : m->serial().responses()) EXPECT_EQ(r.answer, "ok") << "'" << r.line << "'";
  EXPECT_EQ(m->axis('X')->steps(), 3.0);
}

TEST(Protocol, PacedInputGetsExactlyOneAnswerPerLine) {
  // Every kind of line, sent one at a time: each gets one answer, and no
  // answer is left over for the next line to take (the host counts every
  // "ok" and "error" it receives, the closing WAIT's included).
  const std::vector<std::string> lines = {"MOVE X5",   "BOGUS",         "MOVE X1.5",         " ",
                                          "MOVE X" + std::string(90, '9'), std::string("PO\0S", 4),
                                          "MOVE X5 F99999999", "MOVE X-5 A9999999", "POS", "WAIT",
                                          "MODE U2",   "RELEASE",       "MOVE Q1",           "MOVE U4"};
  auto m = simtest::run("m32", lines);
  ASSERT_EQ(m->serial().responses().size(), lines.size());
  size_t answers = 0;
  for (const std::string& l : m->serial().received()) answers += l == "ok" || l.rfind("error", 0) == 0;
  EXPECT_EQ(answers, lines.size() + 1);  // + the host's closing WAIT
  for (const sim::Response& r : m->serial().responses()) EXPECT_FALSE(r.answer.empty()) << r.line;
}

TEST(Protocol, APositionThatWouldWrapIsRefused) {
  // Positions are 32-bit counters (1/64 full step on coil axes). Set them near
  // both ends of the range in the firmware's RAM, then move up to the end and
  // one step past it: the first is run and reported, the second refused.
  const std::string elf = simtest::image("uno");
  const uint16_t positions = sim::read_data_symbol(elf, "_ZN7planner12_GLOBAL__N_19positionsE");
  struct Case {
    char axis;
    int index;       // in the board's axis list
    int32_t units;   // position units per step
  };
  for (const Case c : {Case{'Z', 3, 1}, Case{'U', 2, 64}}) {
    for (const int sign : {1, -1}) {
      sim::Machine m(elf);
      const std::string move = std::string("MOVE ") + c.axis + std::to_string(sign * 7);
      const std::string past = std::string("MOVE ") + c.axis + std::to_string(sign);
      for (const std::string& l : {move, std::string("POS"), past, std::string("POS")}) m.serial().add_line(l);
      // The banner comes after .bss is cleared and before the first line
      // can have arrived: set the position then.
      m.run([&] { return m.serial().banner_seen(); }, 16000000);
      const int64_t limit = sign > 0 ? 2147483647ll : -2147483648ll;
      const int32_t start = int32_t(limit - sign * 7 * c.units);
      std::memcpy(&m.avr()->data[positions + 4 * c.index], &start, 4);
      ASSERT_EQ(m.run_script(16000000ull * 5), sim::RunEnd::done);
      const std::vector<sim::Response>& r = m.serial().responses();
      ASSERT_EQ(r.size(), 4u);
      EXPECT_EQ(r[0].answer, "ok");
      EXPECT_EQ(r[2].answer, "error: move would leave the position range") << c.axis << sign;
      EXPECT_EQ(m.axis(c.axis)->step_cycles.size(), 7u);
      int32_t now;
      std::memcpy(&now, &m.avr()->data[positions + 4 * c.index], 4);
      EXPECT_EQ(now, int32_t(limit));
    }
  }
}

TEST(Protocol, AFloodLosesNoAcknowledgedLineAndMergesNone) {
  // Twelve moves of 1, 2, 4 ... 2048 steps sent back to back, ignoring the
  // answers: the receive ring overflows while a move waits for the planner.
  // Each move's steps are one bit of the final position, so the position
  // says exactly which moves ran. The flood is repeated with the overflow
  // falling at every offset of a line (0..23 junk bytes first):
  //   - every move that ran was answered "ok" once (popcount = oks), and no
  //     move ran twice or merged with another (a merged line would add a
  //     number that is no single bit, or be refused);
  //   - every other answer is the overrun error, and there are never more
  //     answers than lines;
  //   - the firmware answers again normally after the flood.
  for (size_t junk = 0; junk < 24; ++junk) {
    SCOPED_TRACE(junk);
    sim::Machine m(simtest::image("m32"));
    // An empty script: the host's closing WAIT goes out after the banner; its
    // answer must be in before the flood starts, or the two streams would mix.
    ASSERT_EQ(m.run_script(16000000), sim::RunEnd::done);
    const size_t before = m.serial().received().size();
    std::string flood = std::string(junk, ' ');
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
    EXPECT_EQ(position & ~4095, 0);
    // A paced line afterwards is answered once and runs.
    const size_t after = got.size();
    m.serial().send_raw("MOVE X4096\nWAIT\n");
    const auto oks_after = [&] { return std::count(got.begin() + long(after), got.end(), std::string("ok")); };
    m.run([&] { return oks_after() == 2; }, 16000000ull * 3);
    EXPECT_EQ(oks_after(), 2);
    EXPECT_EQ(got.size(), after + 2);  // the two answers and nothing else
    EXPECT_EQ(int(m.axis('X')->steps()), position + 4096);
  }
}
