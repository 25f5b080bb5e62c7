// Bad input on the real image: clear errors, a machine that carries on, and
// nothing acknowledged lost (docs/protocol.md).
#include <sim_avr.h>

#include <algorithm>
#include <cstring>
#include <string>

#include "board_info.h"
#include "sim_fixture.h"

// The direct controls live on the grbl-style images (the printer image m32
// takes G-code only, firmware/boards/m32.h): these run on its CNC twin, the
// m32-cnc, the same board with the same axes.
TEST(Protocol, MalformedAndOverlongLinesAreRefusedAndTheMachineCarriesOn) {
  const std::string overlong = "MOVE X1 " + std::string(89, ' ');  // 97 characters
  const std::string longest = "MOVE X3 " + std::string(88, ' ');   // 96: fits
  auto m = simtest::run("m32-direct", {"MOVE X1.5", "MOVE X99999999999", "MOVE X10 F0", "MOVE X10 A0", overlong,
                                    "MOVE X20000000", "MOVE Q5", "MOVE X10", longest, "POS"});
  const std::vector<std::string> reasons = {"bad number",
                                            "number out of range",
                                            "speed must be above 0",
                                            "acceleration must be above 0",
                                            "line too long (max 96 characters)",
                                            "move too long (max 16777216 steps)",
                                            "word not allowed here"};
  EXPECT_EQ(m->serial().reasons(), reasons);
  // grbl's numbers where the refusal has a grbl meaning, ours from 100 up.
  const std::vector<std::string> errors = {"error:2", "error:100", "error:110", "error:111",
                                           "error:11", "error:108", "error:36"};
  EXPECT_EQ(m->serial().errors(), errors);
  EXPECT_EQ(m->serial().lines_ok(), 3u);  // the last MOVEs and POS
  EXPECT_EQ(m->axis('X')->steps(), 13.0);
}

TEST(Protocol, ControlAndNonAsciiBytesRefuseTheWholeLine) {
  // No prefix of a line ever runs: a NUL (or any byte outside printable ASCII
  // and TAB) anywhere in a line makes all of it an error, on every board. The
  // Marlin image asks for the line again (a byte garbled on the wire).
  const std::string bad_bytes[] = {std::string(1, '\0'), "\x01", "\x08", "\x1b", "\x7f", "\x80", "\xff"};
  for (const char* image : {"uno", "m32-direct", "m16", "m32"}) {
    const bool marlin = std::string(image) == "m32";
    std::vector<std::string> lines;
    for (const std::string& b : bad_bytes) {
      if (marlin) {
        for (const std::string& line : {"G1 X1" + b + "6 F100", "G1 Z1" + b + "00 F100", "G1 Z5" + b + " junk F0",
                                        b + "M114", "G1 Z5 F100" + b})
          lines.push_back(line);
      } else {
        for (const std::string& line : {"MODE X1" + b + "6", "MOVE Z1" + b + "00", "MOVE Z5" + b + " junk F0",
                                        b + "POS", "MOVE Z5" + b})
          lines.push_back(line);
      }
    }
    lines.push_back(marlin ? "M114" : "POS");
    auto m = simtest::run(image, lines);
    const std::vector<std::string> errors = m->serial().errors();
    ASSERT_EQ(errors.size(), lines.size() - 1) << image;
    for (const std::string& e : errors)
      EXPECT_EQ(e, marlin ? "Error:control or non-ASCII byte in line, Last Line: 0" : "error:114") << image;
    for (const std::string& r : m->serial().reasons())
      EXPECT_EQ(r.substr(0, 33), "control or non-ASCII byte in line") << image;
    EXPECT_EQ(m->serial().lines_ok(), 1u) << image;
    for (const sim::AxisTrace& a : m->axes()) EXPECT_TRUE(a.step_cycles.empty()) << image << " " << a.name;
    std::vector<std::string> reports;  // the report, the only line besides the refusals' own
    for (const std::string& l : m->serial().messages())
      if (l.rfind("[MSG:", 0) != 0 && l.rfind("Error:", 0) != 0 && l != "Resend: 1") reports.push_back(l);
    ASSERT_EQ(reports.size(), 1u) << image;
    EXPECT_EQ(reports[0].find(":-"), std::string::npos) << reports[0];  // still all at zero
    if (marlin) {
      EXPECT_EQ(reports[0].substr(0, 7), "X:0.000") << reports[0];
    }
  }
}

TEST(Protocol, BlankLinesAreAnsweredOkAndDoNothing) {
  // docs/protocol.md: a line of spaces and tabs is answered "ok"; an empty
  // line (two line ends in a row, as in CRLF) is no line and gets no answer.
  for (const char* image : {"m32-direct", "m32"}) {
    const bool marlin = std::string(image) == "m32";
    auto m = simtest::run(image, {" ", "\t", " \t  \t", marlin ? "G1 X0.003 F100" : "MOVE X3", "   ",
                                  marlin ? "M114" : "POS"});
    ASSERT_EQ(m->serial().responses().size(), 6u);
    for (const sim::Response& r : m->serial().responses()) EXPECT_EQ(r.answer, "ok") << "'" << r.line << "'";
    EXPECT_EQ(m->axis('X')->steps(), 3.0);
  }
}

TEST(Protocol, PacedInputGetsExactlyOneAnswerPerLine) {
  // Every kind of line, sent one at a time: each gets one answer, and no
  // answer is left over for the next line to take (the host counts every
  // "ok" and "error" it receives, the closing WAIT's included).
  const std::vector<std::string> lines = {"MOVE X5",   "BOGUS",         "MOVE X1.5",         " ",
                                          "MOVE X" + std::string(90, '9'), std::string("PO\0S", 4),
                                          "MOVE X5 F99999999", "MOVE X-5 A9999999", "POS", "WAIT",
                                          "MODE U2",   "RELEASE",       "MOVE Q1",           "MOVE U4"};
  auto m = simtest::run("m32-direct", lines);
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
  for (const Case c : {Case{'Z', 2, 1}, Case{'X', 0, 64}}) {
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
      EXPECT_EQ(r[2].answer, "error:33") << c.axis << sign;
      EXPECT_EQ(r[2].reason, "move would leave the position range") << c.axis << sign;
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
    sim::Machine m(simtest::image("m32-direct"));
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
        std::count(got.begin() + long(before), got.end(), std::string("error:115"));  // serial overrun, line dropped
    EXPECT_EQ(oks + overruns, answers());  // every answer is one of the two
    EXPECT_LE(answers(), 12);
    EXPECT_GT(overruns, 0);  // the flood did overflow
    EXPECT_GT(oks, 0);
    const int position = int(m.axis('X')->steps());
    EXPECT_EQ(__builtin_popcount(unsigned(position)), oks) << "position " << position;
    EXPECT_EQ(position & ~4095, 0);
    // The flood may have lost its last line end: what is left of that line
    // waits in the line buffer, and a line end completes it, refused as
    // spliced across the gap (no more than that one line).
    const size_t flushed = got.size();
    m.serial().send_raw("\n");
    m.run([] { return false; }, 16000000 / 10);
    ASSERT_LE(got.size(), flushed + 2);
    if (got.size() > flushed) {
      EXPECT_EQ(got.back(), "error:115");
    }
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
