// avrmotion-sim --pty as a program on the other end sees it: the banner after
// the open, answers with one line in flight and with grbl-style character
// counting, the reset on a reopen, nothing blocking while no client is
// there, client bytes at the byte rate with no simavr loss, the pacing, and
// the report's positions against the commanded steps. The tests print the
// transcripts and figures docs/simulator.md quotes.
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include <sim_avr.h>

#include "board_info.h"
#include "pty_client.h"
#include "pty_run.h"
#include "sim_fixture.h"
#include "xml_check.h"

namespace {

using ptytest::Client;
using ptytest::report_number;
using ptytest::report_string;
using ptytest::SimProcess;
using simtest::slurp;
using simtest::temp_path;

// Steps per mm of an axis of an image (its board descriptor).
double steps_per_mm(const std::string& image, char axis) {
  const am::BoardDescriptor b = sim::read_board_descriptor(simtest::image(image));
  for (uint8_t i = 0; i < b.axis_count; ++i) {
    if (b.axes[i].name == axis) return b.axes[i].steps_per_m / 1000.0;
  }
  return 0;
}

uint64_t byte_cycles(const std::string& image) {
  const am::BoardDescriptor b = sim::read_board_descriptor(simtest::image(image));
  return uint64_t(b.f_cpu) * 10 / b.baud;
}

// Prints a transcript line as the docs show it.
void shown(const std::string& who, const std::string& line) { std::printf("  %s %s\n", who.c_str(), line.c_str()); }

std::string command_shown(Client& c, const std::string& l) {
  shown(">", l);
  std::vector<std::string> info;
  const std::string a = c.command(l, &info);
  for (const std::string& i : info) shown("<", i);
  shown("<", a);
  return a;
}

TEST(Pty, GcodeAndMovesOneLineInFlightThenAReopenGetsAFreshBanner) {
  const std::string dir = temp_path("pty-"), link = dir + "port", report = dir + "report.json", svg = dir + "run.svg";
  SimProcess sim({"--board", "m32-direct", "--pty", "--link", link, "--speed", "max", "--linger", "2", "--max-seconds",
                  "30", "--report", report, "--plot", svg});
  const std::string path = sim.pty_path();
  ASSERT_EQ(path.rfind("/dev/pts/", 0), 0u) << sim.stderr_text();
  char target[256] = {};
  ASSERT_GT(readlink(link.c_str(), target, sizeof target - 1), 0);
  EXPECT_EQ(path, target);
  const double x_mm = steps_per_mm("m32-direct", 'X'), y_mm = steps_per_mm("m32-direct", 'Y');
  ASSERT_GT(x_mm, 0);

  // Session 1: the board was held in reset until this open, so the banner is
  // the first thing the client reads.
  std::printf("session 1 (%s)\n", link.c_str());
  Client a(link);
  ASSERT_TRUE(a.is_open());
  const std::string banner = a.banner();
  shown("<", banner.substr(0, banner.find('\n')));
  shown("<", banner.substr(banner.find('\n') + 1));
  EXPECT_EQ(banner.rfind("Grbl 1.1h ['$' for help]\n[MSG:avrmotion ", 0), 0u) << banner;
  EXPECT_NE(banner.find("board=m32-direct"), std::string::npos) << banner;
  EXPECT_EQ(command_shown(a, "G21"), "ok");
  EXPECT_EQ(command_shown(a, "G90"), "ok");
  EXPECT_EQ(command_shown(a, "G1 X10 Y5 F1200"), "ok");
  EXPECT_EQ(command_shown(a, "MOVE X400 Y-200 F8000"), "ok");
  EXPECT_EQ(command_shown(a, "BOGUS"), "error:20");
  std::vector<std::string> info;
  EXPECT_EQ(a.command("POS", &info), "ok");
  const long x1 = long(10 * x_mm) + 400, y1 = long(5 * y_mm) - 200;
  ASSERT_EQ(info.size(), 1u);
  EXPECT_EQ(info[0], "pos X:" + std::to_string(x1) + " Y:" + std::to_string(y1) + " Z:0 E:0");
  shown(">", "POS");
  shown("<", info[0]);
  a.close_port();

  // Session 2: the open reset the MCU, as an Arduino's port does.
  std::printf("session 2 (closed and opened again)\n");
  Client b(link);
  ASSERT_TRUE(b.is_open());
  const std::string banner2 = b.banner();
  shown("<", banner2.substr(0, banner2.find('\n')));
  shown("<", banner2.substr(banner2.find('\n') + 1));
  EXPECT_EQ(banner2, banner);
  info.clear();
  EXPECT_EQ(b.command("POS", &info), "ok");
  ASSERT_EQ(info.size(), 1u);
  EXPECT_EQ(info[0], "pos X:0 Y:0 Z:0 E:0");  // the firmware starts again from 0
  shown(">", "POS");
  shown("<", info[0]);
  EXPECT_EQ(command_shown(b, "MOVE X-300 F4000"), "ok");
  EXPECT_EQ(command_shown(b, "WAIT"), "ok");
  // The last lines go out and the client leaves without reading the
  // answers: the move still runs, what the firmware prints meanwhile is
  // dropped without holding the simulation up, and the run ends once the
  // linger has passed with no new client.
  b.send("MOVE Y1000 F4000\nPOS\n");
  b.close_port();

  ASSERT_EQ(sim.wait_exit(), 0) << sim.stderr_text();
  const std::string json = slurp(report);
  EXPECT_EQ(report_string(json, "end"), "\"done\"");
  // The motors do not move on a reset: the decoded positions add up over both sessions.
  EXPECT_EQ(report_number(json, "X", "steps"), double(x1 - 300)) << json;
  EXPECT_EQ(report_number(json, "Y", "steps"), double(y1 + 1000)) << json;
  EXPECT_EQ(report_number(json, "pty", "sessions"), 2);
  EXPECT_GT(report_number(json, "pty", "bytes_discarded"), 0);  // "ok", "pos ...", "ok" of the last lines
  EXPECT_EQ(report_number(json, "pty", "min_byte_interval_cycles"), double(byte_cycles("m32-direct")));
  EXPECT_EQ(report_number(json, "", "lines_sent"), 11);
  EXPECT_EQ(report_string(json, "errors"), "[\"error:20\"]");
  EXPECT_EQ(access(link.c_str(), F_OK), -1) << "the link outlived the run";
  xmlcheck::Parser picture(slurp(svg));  // the picture, as for a file run
  EXPECT_TRUE(picture.parse()) << picture.error();
  EXPECT_NE(slurp(svg).find("end: done; 11 lines sent"), std::string::npos);
  std::printf("report: sessions %g, bytes to the AVR %g, from it %g, discarded %g\n",
              report_number(json, "pty", "sessions"), report_number(json, "pty", "bytes_to_avr"),
              report_number(json, "pty", "bytes_from_avr"), report_number(json, "pty", "bytes_discarded"));
  std::remove(report.c_str());
  std::remove(svg.c_str());
}

// The port on its own: raw for every client, every open counted (also one
// that was closed again before anybody looked), a client's going seen.
TEST(Pty, ThePortIsRawAndCountsEveryOpen) {
  sim::PtyPort port;
  EXPECT_EQ(port.opens(), 0u);
  EXPECT_FALSE(port.client_present());
  { Client gone(port.path()); }
  Client c(port.path());
  ASSERT_TRUE(c.is_open());
  EXPECT_EQ(port.opens(), 2u);
  EXPECT_TRUE(port.client_present());
  const int fd = open(port.path().c_str(), O_RDONLY | O_NOCTTY);  // a third open, to read the settings
  termios tio{};
  ASSERT_EQ(tcgetattr(fd, &tio), 0);
  close(fd);
  EXPECT_EQ(tio.c_lflag & (ECHO | ICANON | ISIG), 0u);
  EXPECT_EQ(tio.c_oflag & OPOST, 0u);
  EXPECT_EQ(tio.c_iflag & (ICRNL | IXON), 0u);
  EXPECT_EQ(tio.c_cflag & CSIZE, tcflag_t(CS8));
  EXPECT_EQ(port.opens(), 1u);
  c.close_port();
  EXPECT_FALSE(port.client_present());
  EXPECT_EQ(port.opens(), 0u);
}

// Ctrl-C (SIGINT) or SIGTERM ends a session that nobody closes: the report
// is still written, and the link goes.
TEST(Pty, ASignalEndsTheRunWithItsReport) {
  const std::string link = temp_path("pty-sig-port"), report = temp_path("pty-sig.json");
  SimProcess sim({"--board", "m32", "--pty", "--link", link, "--max-seconds", "30", "--report", report});
  ASSERT_FALSE(sim.pty_path().empty()) << sim.stderr_text();
  Client c(link);
  ASSERT_EQ(c.banner().rfind("start\necho:avrmotion ", 0), 0u);  // the printer: Marlin's protocol
  EXPECT_EQ(c.command("G1 X0.1 F600"), "ok");
  sim.signal(SIGTERM);
  ASSERT_EQ(sim.wait_exit(), 0) << sim.stderr_text();
  const std::string json = slurp(report);
  EXPECT_EQ(report_string(json, "end"), "\"interrupted\"");
  EXPECT_EQ(report_number(json, "pty", "sessions"), 1);
  EXPECT_EQ(access(link.c_str(), F_OK), -1);
  std::remove(report.c_str());
}

// A --max-seconds budget counts from the first open and ends the session.
TEST(Pty, ABudgetEndsASessionThatGoesOnTooLong) {
  const std::string report = temp_path("pty-budget.json");
  SimProcess sim({"--board", "m32", "--pty", "--speed", "max", "--max-seconds", "0.5", "--report", report});
  const std::string path = sim.pty_path();
  ASSERT_FALSE(path.empty()) << sim.stderr_text();
  Client c(path);
  ASSERT_EQ(c.banner().rfind("start\necho:avrmotion ", 0), 0u);
  EXPECT_EQ(c.line(), "<closed>");  // nothing more comes until the simulator goes
  ASSERT_EQ(sim.wait_exit(), 3) << sim.stderr_text();
  const std::string json = slurp(report);
  EXPECT_EQ(report_string(json, "end"), "\"timeout\"");
  const double cycles = report_number(json, "", "cycles");  // 0.5 s at 16 MHz from the open (cycle 0),
  EXPECT_GE(cycles, 8000000);                                // to within the last instruction
  EXPECT_LT(cycles, 8000000 + 8);
  std::remove(report.c_str());
}

// grbl's streaming protocol on the m32-cnc: a character-counting client
// (ptytest::stream_counting) keeps as many lines in flight as the receive
// ring holds, the size `$I` reports (`[OPT:,<blocks>,<ring>]`: 64 bytes
// today, hal/avr/uart.cpp; grbl senders count against 128, which the ring
// must grow to). The ring never overflows: every line is answered once, no
// line is refused, and the file ends exactly on its target.
TEST(Pty, ACharacterCountingClientFillsTheReceiveRingAndLosesNothing) {
  const std::string report = temp_path("pty-count.json");
  SimProcess sim({"--board", "m32-cnc", "--pty", "--speed", "max", "--linger", "0", "--max-seconds", "60", "--report",
                  report});
  const std::string path = sim.pty_path();
  ASSERT_FALSE(path.empty()) << sim.stderr_text();
  Client c(path);
  ASSERT_EQ(c.banner().rfind("Grbl 1.1h", 0), 0u);
  std::vector<std::string> info;
  ASSERT_EQ(c.command("$I", &info), "ok");
  ASSERT_EQ(info.size(), 2u);
  std::smatch opt;
  ASSERT_TRUE(std::regex_match(info[1], opt, std::regex(R"(\[OPT:,(\d+),(\d+)\])"))) << info[1];
  const size_t ring = std::stoul(opt[2]);
  EXPECT_EQ(ring, 128u);  // grbl's own figure, with the realtime bytes (docs/realtime.md)
  // A milling-style file: 400 short feeds with three decimals around a
  // square, then the end point.
  std::vector<std::string> lines{"G21", "G90"};
  for (int i = 1; i <= 400; ++i) {
    char l[64];
    std::snprintf(l, sizeof l, "G1 X%.3f Y%.3f F3000", (i * 137 % 2000) / 1000.0, (i * 71 % 1500) / 1000.0);
    lines.push_back(l);
  }
  lines.push_back("G1 X1.234 Y0.567 F3000");
  const ptytest::Streamed r = ptytest::stream_counting(c, lines, ring);
  ASSERT_TRUE(r.failure.empty()) << r.failure;
  std::printf("character counting against %zu bytes: %zu lines, up to %zu lines / %zu bytes in flight, %zu errors\n",
              ring, lines.size(), r.most_lines, r.most_bytes, r.errors);
  EXPECT_EQ(r.answered, lines.size());
  EXPECT_EQ(r.errors, 0u);
  EXPECT_GE(r.most_lines, 3u);  // it did stream
  EXPECT_LE(r.most_bytes, ring);
  EXPECT_EQ(c.command("M400", &info), "ok");  // the motion's end
  info.clear();
  EXPECT_EQ(c.command("M114", &info), "ok");
  const long x = std::lround(1.234 * steps_per_mm("m32-cnc", 'X')), y = std::lround(0.567 * steps_per_mm("m32-cnc", 'Y'));
  ASSERT_EQ(info.size(), 1u);
  EXPECT_NE(info[0].find(" Count X:" + std::to_string(x) + " Y:" + std::to_string(y) + " "), std::string::npos)
      << info[0];
  c.close_port();
  ASSERT_EQ(sim.wait_exit(), 0) << sim.stderr_text();
  const std::string json = slurp(report);
  EXPECT_EQ(report_number(json, "X", "steps"), double(x));
  EXPECT_EQ(report_number(json, "Y", "steps"), double(y));
  EXPECT_EQ(report_number(json, "", "lines_ok"), double(lines.size() + 3));  // with $I, M400 and M114
  EXPECT_EQ(report_string(json, "errors"), "[]");
  std::remove(report.c_str());
}

// A client that ignores flow control and writes 200 lines at once: the
// simulator hands them to the UART one byte time apart, so simavr's own RX
// FIFO never overruns (it would report a lost byte and fail the run, exit 5),
// and every line is answered. Prints the throughput at --speed max.
TEST(Pty, AFloodIsPacedAtTheByteRateAndSimavrLosesNoByte) {
  const std::string report = temp_path("pty-flood.json");
  SimProcess sim({"--board", "m32", "--pty", "--speed", "max", "--linger", "0", "--max-seconds", "30", "--report", report});
  const std::string path = sim.pty_path();
  ASSERT_FALSE(path.empty()) << sim.stderr_text();
  Client c(path);
  ASSERT_EQ(c.banner().rfind("start\necho:avrmotion ", 0), 0u);
  std::string flood;
  for (int i = 0; i < 200; ++i) flood += "G21\n";
  c.send(flood);
  size_t oks = 0;
  for (size_t i = 0; i < 200; ++i) oks += c.line() == "ok";
  EXPECT_EQ(oks, 200u);
  c.close_port();
  ASSERT_EQ(sim.wait_exit(), 0) << sim.stderr_text();
  const std::string json = slurp(report);
  const uint64_t byte = byte_cycles("m32");
  EXPECT_EQ(report_number(json, "pty", "bytes_to_avr"), double(flood.size()));
  EXPECT_EQ(report_number(json, "pty", "min_byte_interval_cycles"), double(byte));
  EXPECT_GE(report_number(json, "", "cycles"), double(flood.size() * byte));
  const double wall = report_number(json, "pty", "wall_seconds"), simulated = report_number(json, "pty", "simulated_seconds");
  std::printf("flood: %zu bytes in %.3f s wall (%.0f bytes/s through the pty), %.3f s simulated (%.1fx real time)\n",
              flood.size(), wall, flood.size() / wall, simulated, simulated / wall);
  std::remove(report.c_str());
}

// Paced runs: simulated time never runs ahead of wall-clock time times the
// speed (it can only lag, and the report says by how much at worst).
TEST(Pty, SimulatedTimeFollowsWallClockTimesTheSpeed) {
  for (const char* speed : {"1", "2"}) {
    const std::string report = temp_path(std::string("pty-pace-") + speed + ".json");
    SimProcess sim({"--board", "uno", "--pty", "--speed", speed, "--linger", "0", "--max-seconds", "30", "--report", report});
    const std::string path = sim.pty_path();
    ASSERT_FALSE(path.empty()) << sim.stderr_text();
    Client c(path);
    ASSERT_EQ(c.banner().rfind("Grbl 1.1h ['$' for help]\n[MSG:avrmotion ", 0), 0u);
    EXPECT_EQ(c.command("G4 P1"), "ok");
    EXPECT_EQ(c.command("WAIT"), "ok");
    c.close_port();
    ASSERT_EQ(sim.wait_exit(), 0) << sim.stderr_text();
    const std::string json = slurp(report);
    const double wall = report_number(json, "pty", "wall_seconds"), simulated = report_number(json, "pty", "simulated_seconds");
    const double lag = report_number(json, "pty", "max_lag_seconds");
    std::printf("--speed %s: %.4f s simulated in %.4f s wall (%.4fx), worst lag %.1f ms\n", speed, simulated, wall,
                simulated / wall, lag * 1000);
    EXPECT_GE(simulated, 1.0);
    EXPECT_LE(simulated, std::atof(speed) * wall + 0.002);  // never ahead (one 1 ms slice of slack)
    std::remove(report.c_str());
  }
}

avr_cycle_count_t never_mind(avr_t*, avr_cycle_count_t, void*) { return 0; }
// As Harness.ARunInWhichSimavrDropsAnEventFails: one more timer than the pool holds.
avr_cycle_count_t fill_the_timer_pool(avr_t* avr, avr_cycle_count_t, void*) {
  static char params[MAX_CYCLE_TIMERS + 1];
  for (char& p : params) avr_cycle_timer_register(avr, 1000000000, never_mind, &p);
  return 0;
}

// A pty run fails like any other when simavr reports a dropped event.
TEST(Pty, ARunInWhichSimavrDropsAnEventFails) {
  sim::Machine m(simtest::image("m32"));
  sim::PtyPort port;
  Client c(port.path());
  ASSERT_TRUE(c.is_open());
  avr_cycle_timer_register(m.avr(), 100000, fill_the_timer_pool, nullptr);
  sim::PtyStats stats;
  testing::internal::CaptureStderr();
  EXPECT_THROW(sim::run_pty(m, port, sim::PtyOptions{0, 0, 16000000, nullptr}, stats), sim::SimulatorFault);
  testing::internal::GetCapturedStderr();
  EXPECT_LT(m.cycles(), 100000u + 8);
}

TEST(Pty, UsageErrors) {
  const std::string exe = AVRMOTION_SIM_EXE, img = simtest::image("m32");
  const auto rc = [](const std::string& cmd) {
    const int r = std::system((cmd + " >/dev/null 2>&1").c_str());
    return WIFEXITED(r) ? WEXITSTATUS(r) : -1;
  };
  EXPECT_EQ(rc(exe + " --elf " + img + " --link /tmp/x"), 2);        // --link without --pty
  EXPECT_EQ(rc(exe + " --elf " + img + " --speed max"), 2);          // --speed without --pty
  EXPECT_EQ(rc(exe + " --elf " + img + " --pty --input /dev/null"), 2);
  EXPECT_EQ(rc(exe + " --elf " + img + " --pty --speed fast"), 2);
  const std::string file = temp_path("not-a-link");
  { std::ofstream(file) << "keep me"; }
  EXPECT_EQ(rc(exe + " --elf " + img + " --pty --link " + file), 2);  // a file in the way is not replaced
  EXPECT_EQ(slurp(file), "keep me");
  std::remove(file.c_str());
}

}  // namespace
