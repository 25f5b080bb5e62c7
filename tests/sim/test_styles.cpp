// The two line protocols on the real images (docs/protocol.md): Marlin's on
// the m32 printer (numbered and checksummed lines, resend requests, M110,
// M115, M400 with its keep-alive, M112), grbl's on the others (`$` lines).
// The tests print the transcripts docs/protocol.md shows.
#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "board_info.h"
#include "sim_fixture.h"
#include "thermal_plant.h"

namespace {

// Marlin's framing, as a host computes it: `N<n> <text>*<XOR of the bytes
// before the '*'>`.
int checksum(const std::string& s) {
  int x = 0;
  for (const char c : s) x ^= uint8_t(c);
  return x;
}
std::string numbered(long n, const std::string& text) {
  const std::string l = "N" + std::to_string(n) + " " + text;
  return l + "*" + std::to_string(checksum(l));
}

// Every line each way in the order it went: `>` to the firmware, `<` from it
// (a line sent on an answer's line end comes after that answer).
void print_transcript(const char* title, const sim::SerialHost& host) {
  std::vector<std::pair<uint64_t, std::string>> all;
  const uint64_t end = host.responses().empty() ? 0 : host.responses().back().answer_cycle;
  for (size_t i = 0; i < host.received().size() && host.received_cycles()[i] <= end; ++i)  // not the host's closing line's
    all.push_back({host.received_cycles()[i], "  < " + host.received()[i]});
  for (const sim::Response& r : host.responses()) all.push_back({r.sent_cycle, "  > " + r.line});
  std::stable_sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::printf("%s\n", title);
  for (const auto& l : all) std::printf("%s\n", l.second.c_str());
}

struct Expect {
  std::string line, answer;
};

void expect_answers(const sim::SerialHost& host, const std::vector<Expect>& script) {
  const std::vector<sim::Response>& r = host.responses();
  ASSERT_EQ(r.size(), script.size());
  for (size_t i = 0; i < r.size(); ++i) EXPECT_EQ(r[i].answer, script[i].answer) << r[i].line;
}

std::vector<std::string> lines_of(const std::vector<Expect>& script) {
  std::vector<std::string> out;
  for (const Expect& e : script) out.push_back(e.line);
  return out;
}

}  // namespace

TEST(Styles, MarlinRunsNumberedLinesInTurnAndAsksAgainForTheRest) {
  // 1000 steps/mm: every move that runs is a distinct step count, so X says
  // which ran. A refused line never runs; the host sends it again from the
  // `Resend:` number.
  const std::string n2 = "N2 G1 X1 F600";
  const std::string bad_sum = n2 + "*" + std::to_string((checksum(n2) + 1) % 256);
  const std::string unnumbered = "G1 X8 F600";
  const std::vector<Expect> script = {
      {numbered(-1, "M110"), "ok"},  // printcore's first line: the next is N0
      {numbered(0, "G91"), "ok"},
      {numbered(1, "G1 X0.001 F600"), "ok"},
      {numbered(3, "G1 X0.002 F600"), "Error:Line Number is not Last Line Number+1, Last Line: 1"},
      {bad_sum, "Error:checksum mismatch, Last Line: 1"},
      {n2, "Error:No Checksum with line number, Last Line: 1"},
      {unnumbered + "*" + std::to_string(checksum(unnumbered)), "Error:No Line Number with checksum, Last Line: 1"},
      {numbered(2, "G1 X0.004 F600"), "ok"},
      {"M110 N100", "ok"},
      {numbered(101, "G1 X0.008 F600"), "ok"},
      {"G1 X0.016 F600", "ok"},  // without N: unchecked, as a person types it
      {numbered(102, "M400"), "ok"},
  };
  auto m = simtest::run("m32", lines_of(script), 10);
  print_transcript("Marlin: numbered lines, checksums, resends (m32)", m->serial());
  expect_answers(m->serial(), script);
  EXPECT_EQ(m->axis('X')->steps(), 1 + 4 + 8 + 16);
  // Each refusal names the line to send again.
  size_t resends = 0;
  for (const std::string& l : m->serial().messages()) resends += l == "Resend: 2";
  EXPECT_EQ(resends, 4u);
}

TEST(Styles, MarlinReportsItselfWaitsForMotionAndKeepsTheHostWaiting) {
  const std::string longest = "G1 X0.001 F600 ;" + std::string(96 - 16, '.');
  ASSERT_EQ(longest.size(), 96u);
  const std::vector<Expect> script = {
      {"M115", "ok"},
      {"M140 S60", "ok"},  // Marlin's answer to a code it does not have (no bed heater here)
      {"M106 S128", "ok"},  // the fan: no output on this board, a no-op (no echo)
      {longest, "ok"},
      {longest + ".", "Error:line too long (max 96 characters)"},
      {"G91", "ok"},
      {"G1 X5 F600", "ok"},  // 0.5 s of motion
      {"M400", "ok"},
      {"G4 S5", "ok"},  // Marlin's G4: S seconds (P would be milliseconds)
      {"M400", "ok"},  // 5 s: Marlin's keep-alive every 2 s meanwhile
  };
  auto m = simtest::run("m32", lines_of(script), 20);
  print_transcript("Marlin: M115, an unknown code, the line limit, M400 and its keep-alive (m32)", m->serial());
  expect_answers(m->serial(), script);
  const std::vector<std::string> msgs = m->serial().messages();
  const std::vector<std::string> info(msgs.begin(), msgs.begin() + 5);
  EXPECT_EQ(info, (std::vector<std::string>{"FIRMWARE_NAME:avrmotion " AVRMOTION_VERSION_STRING
                                            " SOURCE_CODE_URL:local PROTOCOL_VERSION:1.0 MACHINE_TYPE:m32 "
                                            "EXTRUDER_COUNT:1",
                                            "Cap:AUTOREPORT_TEMP:1", "Cap:EEPROM:0", "Cap:EMERGENCY_PARSER:0",
                                            "echo:Unknown command: \"M140 S60\""}));
  const auto& r = m->serial().responses();
  const auto& x = m->axis('X')->step_cycles;
  ASSERT_EQ(x.size(), 5001u);  // 1 + 5000
  EXPECT_GT(r[7].answer_cycle, x.back());  // the first M400 answered after the last step
  EXPECT_LT(r[7].answer_cycle - x.back(), 16000u * 5);
  // The second waits out the dwell: busy lines 2 s and 4 s after it came
  // (the clock's ms: 1/16 of a cycle's precision is not the point; within
  // 2 ms of its last byte), none later, the answer after the dwell.
  const uint64_t arrived = r[9].sent_cycle + 5 * 1389;  // "M400\n", 1389 cycles a byte at 115200
  std::vector<uint64_t> busy;
  for (size_t i = 0; i < m->serial().received().size(); ++i)
    if (m->serial().received()[i] == "busy: processing") busy.push_back(m->serial().received_cycles()[i]);
  ASSERT_EQ(busy.size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    const double after_s = double(busy[k] - arrived) / 16e6;
    std::printf("busy: processing %.4f s after the M400\n", after_s);
    EXPECT_NEAR(after_s, 2.0 * double(k + 1), 0.003);
  }
  EXPECT_GT(r[9].answer_cycle, busy[1]);
  EXPECT_NEAR(double(r[9].answer_cycle - r[8].answer_cycle) / 16e6, 5.0, 0.05);
}

TEST(Styles, MarlinM112StopsTheStepsAtOnceTurnsTheHeaterOffAndHaltsUntilReset) {
  sim::Machine m(simtest::image("m32"));
  sim::ThermalPlant plant(m);
  const auto& heater = m.watch_pin('D', 7);
  ASSERT_EQ(m.run([&] { return m.serial().banner_seen(); }, 16000000), sim::RunEnd::done);
  m.serial().send_raw("M104 S200\nG1 X50 F3000\n");
  const auto& x = m.axis('X')->step_cycles;
  ASSERT_EQ(m.run([&] { return x.size() >= 20000; }, 16000000ull * 3), sim::RunEnd::done);  // mid-move
  ASSERT_FALSE(heater.empty());  // heating
  const uint64_t sent = m.cycles();
  m.serial().send_raw("M112\n");
  const uint64_t last_byte = sent + 5 * 1389;
  m.run([] { return false; }, 16000000 / 2);
  const uint64_t last_step = x.back();
  const size_t steps = x.size();
  std::printf("M112: last step %.3f ms after the line's last byte, %zu steps of 50000\n",
              (double(last_step) - double(last_byte)) / 16000.0, steps);
  EXPECT_LT(steps, 50000u);
  EXPECT_LT(double(last_step) - double(last_byte), 16000.0);  // within 1 ms of the line
  EXPECT_FALSE(heater.back().level);
  EXPECT_LT(double(heater.back().cycle) - double(last_byte), 16000.0);
  // Halted: every line refused, nothing moves, until a reset.
  m.serial().send_raw("G1 X60 F3000\nM105\n");
  m.run([] { return false; }, 16000000 / 2);
  EXPECT_EQ(x.size(), steps);
  std::vector<std::string> tail;
  const auto& got = m.serial().received();
  for (size_t i = got.size() - 6; i < got.size(); ++i) tail.push_back(got[i]);
  const std::string halted = "Error:Printer halted (M112), reset to restart";
  EXPECT_EQ(tail, (std::vector<std::string>{halted, "ok", halted, "ok", halted, "ok"}));
  for (const sim::PinEdge& e : heater) {
    if (e.cycle > last_byte + 16000) {
      EXPECT_FALSE(e.level) << e.cycle;
    }
  }
}

TEST(Styles, GrblAnswersItsDollarLinesAndReservesTheOthers) {
  const std::vector<Expect> script = {
      {"$", "ok"},
      {"$I", "ok"},
      {"$G", "ok"},
      {"G20 G91 G1 X0.01 F25", "ok"},
      {"$G", "ok"},
      {"$$", "error:3"},
      {"$H", "error:3"},
      {"$#", "error:3"},
      {"$10=1", "error:3"},
      {"?", "error:3"},
      {"G7", "error:20"},
      {"$X", "ok"},  // unlocks (not in alarm here: nothing to do)
  };
  auto m = simtest::run("uno", lines_of(script), 10);
  print_transcript("grbl: $ lines (uno)", m->serial());
  expect_answers(m->serial(), script);
  const std::vector<std::string> msgs = m->serial().messages();
  ASSERT_GE(msgs.size(), 5u);
  EXPECT_EQ(std::vector<std::string>(msgs.begin(), msgs.begin() + 5),
            (std::vector<std::string>{"[HLP:$ $I $G $X]", "[VER:1.1h.avrmotion-" AVRMOTION_VERSION_STRING ":uno]",
                                      "[OPT:,5,64]", "[GC:G0 G17 G21 G90 G94 M82 F0]",
                                      "[GC:G1 G17 G20 G91 G94 M83 F25]"}));
  // The ring $I reports is the UART's own (hal/avr/uart.cpp's rx_buf, as
  // the image holds it): a character-counting sender trusts that figure.
  for (const char* image : {"uno", "m32-cnc", "m32-direct", "m16"}) {
    auto i = simtest::run(image, {"$I"});
    const std::vector<std::string> info = i->serial().messages();
    ASSERT_GE(info.size(), 2u) << image;
    const uint32_t reported = uint32_t(std::stoul(info[1].substr(info[1].rfind(',') + 1)));
    const sim::ElfSymbol ring = sim::find_symbol(simtest::image(image), "_ZN3hal4uart12_GLOBAL__N_16rx_bufE");
    ASSERT_TRUE(ring.found) << image;
    EXPECT_EQ(ring.size, reported) << image;
    printf("%s: $I reports a %u-byte receive ring\n", image, reported);
  }
  for (size_t i = 5; i < 10; ++i) EXPECT_EQ(m->serial().responses()[i].reason, "not in this image");
  EXPECT_EQ(m->serial().responses()[10].reason, "unsupported G or M code");
}

TEST(Styles, AMarlinFloodIsRefusedFromItsGapOnAndResentLosesNothing) {
  // Twelve numbered moves of 1, 2, 4 ... 2048 steps back to back, ignoring
  // the answers: the receive ring overflows while a move waits for the
  // ring. From the first line lost or refused on, every line is refused
  // (out of turn, or spliced across the gap) and not run; the host then
  // sends again from the last `Resend:` number, one line at a time, and
  // every move has run exactly once.
  for (size_t junk = 0; junk < 24; junk += 5) {
    SCOPED_TRACE(junk);
    sim::Machine m(simtest::image("m32"));
    m.serial().add_line(numbered(1, "G91"));
    ASSERT_EQ(m.run_script(16000000), sim::RunEnd::done);
    std::vector<std::string> lines;
    for (int i = 0; i < 12; ++i)
      lines.push_back(numbered(2 + i, "G1 X" + std::to_string((1 << i) / 1000.0).substr(0, 6) + " F30000"));
    std::string flood = std::string(junk, ' ');
    for (const std::string& l : lines) flood += l + "\n";
    const auto& got = m.serial().received();
    const size_t before = got.size();
    m.serial().send_raw(flood);
    long last = -1;
    const auto oks = [&] { return std::count(got.begin() + long(before), got.end(), std::string("ok")); };
    for (int i = 0; i < 20 && oks() != last; ++i) {
      last = oks();
      m.run([] { return false; }, 16000000 / 2);
    }
    long resend = -1;
    size_t refusals = 0;
    for (size_t i = before; i < got.size(); ++i) {
      if (got[i].rfind("Resend: ", 0) == 0) resend = std::stol(got[i].substr(8));
      refusals += got[i].rfind("Error:", 0) == 0;
    }
    EXPECT_LE(oks(), 12);  // no line answered twice
    EXPECT_GT(refusals, 0u);  // the flood did overflow
    ASSERT_GE(resend, 2);
    const int ran = int(m.axis('X')->steps());
    // The lines before the first refusal ran, in order, and nothing else.
    EXPECT_EQ(ran, (1 << (resend - 2)) - 1) << "resend from " << resend;
    EXPECT_EQ(oks() - long(refusals), resend - 2);
    // Sent again from there, paced, as a host does: on every refusal from
    // its `Resend:` number (the first may still meet the flood's last,
    // unfinished line). All twelve moves, each once.
    for (long n = resend, tries = 0; n < 14 && tries < 30; ++tries) {
      m.serial().add_line(lines[size_t(n - 2)]);
      ASSERT_EQ(m.run_script(16000000ull * 2), sim::RunEnd::done);
      if (m.serial().responses().back().answer == "ok") {
        ++n;
        continue;
      }
      for (const std::string& l : got)
        if (l.rfind("Resend: ", 0) == 0) n = std::stol(l.substr(8));
    }
    EXPECT_EQ(int(m.axis('X')->steps()), 4095);
  }
}
