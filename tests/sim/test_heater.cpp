// The heater service on the real m32 image against the simulated 40 W hot
// end (sim/thermal_plant.h): the heat-up and hold, a fan step, the M-codes'
// answers, and every fault cutting the heater within its deadline with its
// message. Times are simulated (cycles at 16 MHz).
// This file: heat-up and hold, the M-codes, autotune, power-on, the sim's
// plant scenario, the gains in EEPROM and the heater's flash; the faults:
// test_heater_faults.cpp; the rig: heater_rig.h.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <regex>
#include <string>

#include <sim_avr.h>
#include <sys/wait.h>

#include <fstream>

#include "sim_fixture.h"
#include "thermal_plant.h"

#include "heater_rig.h"

namespace {

using heatertest::HotEnd;
using heatertest::kHz;
using heatertest::kStatus;

constexpr double kFanAt = 165, kEnd = 235;

// 25 -> 200 C with M109 and Marlin's default gains, a print streaming while it
// holds, then a part-fan step: the whole run in one simulation (235 s).
TEST(Heater, HeatsTo200HoldsItAndRecoversFromAFanStep) {
  HotEnd h;
  const auto& temp_ok = h.m->watch_pin('D', 6);
  h.send("M109 S200");
  h.send("M105");
  // Then a print streams while the heater holds: G-code moves (about 10 s),
  // the step engine never starved.
  for (int k = 0; k < 20; ++k) h.send(k % 2 ? "G1 X0 Y0 E0 F3000" : "G1 X20 Y15 E2 F3000");
  h.plant->fan_at(kFanAt, 1.0);
  h.run_until(kEnd);

  // M109 waited until the reading was within 1 C (T >= 199 C), printing the
  // status once a second, then the next line ran.
  const sim::Response* wait = h.answer_of("M109 S200");
  ASSERT_NE(wait, nullptr);
  EXPECT_EQ(wait->answer, "ok");
  const double waited = double(wait->answer_cycle - wait->sent_cycle) / kHz;
  const double reached = h.crossed_s(198.5, true);
  EXPECT_GT(waited, 60);  // it did wait: 60-90 s of full power from 25 C
  EXPECT_NEAR(wait->answer_cycle / kHz, h.crossed_s(199, true), 1.5);
  int status_lines = 0;
  for (const std::string& l : h.m->serial().messages()) status_lines += std::regex_match(l, kStatus);
  EXPECT_NEAR(status_lines, waited, 1.5);
  const sim::Response* m105 = h.answer_of("M105");
  ASSERT_NE(m105, nullptr);
  EXPECT_GE(m105->sent_cycle, wait->answer_cycle);
  EXPECT_TRUE(std::regex_match(m105->answer, std::regex(R"(ok T:(199|200)\.\d\d /200\.00 @:\d+)"))) << m105->answer;

  // Overshoot and the hold before the fan.
  double peak = 0, lo = 1e9, hi = -1e9, settled = -1;
  for (const sim::ThermalSample& s : h.plant->log()) {
    if (s.t_s > kFanAt) break;
    peak = std::max(peak, s.sensor_c);
    if (s.t_s >= 150) lo = std::min(lo, s.sensor_c), hi = std::max(hi, s.sensor_c);
  }
  for (const sim::ThermalSample& s : h.plant->log()) {  // last time outside +-0.3 C before the fan
    if (s.t_s > kFanAt) break;
    if (std::fabs(s.sensor_c - 200) > 0.3) settled = s.t_s;
  }
  EXPECT_LE(peak - 200, 1.0);
  EXPECT_GE(lo, 199.7);
  EXPECT_LE(hi, 200.3);
  std::printf("heat-up: 25 -> 198.5 C in %.1f s, M109 done after %.1f s, overshoot %.2f C, within +-0.3 C from %.1f s,"
              " 150..%.0f s: %.2f .. %.2f C\n",
              reached, waited, peak - 200, settled, kFanAt, lo, hi);

  // The fan (8.75 W more loss at 200 C, 35 % of the heater): the dip, and
  // back within +-0.3 C.
  double dip = 1e9, back = -1;
  for (const sim::ThermalSample& s : h.plant->log()) {
    if (s.t_s < kFanAt) continue;
    dip = std::min(dip, s.sensor_c);
    if (std::fabs(s.sensor_c - 200) > 0.3) back = s.t_s;
  }
  EXPECT_LT(dip, 199.7);              // the step is felt
  EXPECT_LT(back, kEnd - 10);         // and corrected
  std::printf("fan step at %.0f s: dip to %.2f C, within +-0.3 C again after %.1f s\n", kFanAt, dip, back - kFanAt);

  // TEMP_OK (PD6): high from the reading's first |T - 200| <= 3 C on, through
  // the fan's dip.
  std::vector<double> rises, falls;
  for (const sim::PinEdge& e : temp_ok) (e.level ? rises : falls).push_back(double(e.cycle) / kHz);
  ASSERT_EQ(rises.size(), 1u);
  EXPECT_TRUE(falls.empty() || falls.back() < rises.front());
  // It rises when the thermistor is at 197 C within the reading's accuracy
  // (docs/heater.md: a 12-bit count is 0.12 C there, the table within 0.22 C).
  double at_rise = 0;
  for (const sim::ThermalSample& s : h.plant->log())
    if (s.t_s <= rises.front()) at_rise = s.sensor_c;
  EXPECT_NEAR(at_rise, 197, 0.5);
  std::printf("TEMP_OK rises at %.3f s, the thermistor at %.2f C\n", rises.front(), at_rise);

  // The moves ran whole while the heater held.
  EXPECT_EQ(h.m->starvations(), 0);
  for (const char axis : {'X', 'Y', 'E'}) EXPECT_DOUBLE_EQ(h.m->axis(axis)->steps(), 0.0) << axis;
  EXPECT_EQ(h.m->axis('X')->step_cycles.size(), 20u * 20000u);
  EXPECT_EQ(h.m->serial().errors().size(), 0u);
}

// M105 in Marlin's format, M155 auto-reports, M301, bad input refused.
TEST(Heater, CommandsAnswerInMarlinsFormatAndRefuseBadInput) {
  HotEnd h;
  for (const char* l : {"M105", "M155 S1", "M104 S300", "M104 S-5", "M301 P1001", "M301 P30.5 I2 D80", "M301",
                        "M104 S150", "G4 S3.2", "M400", "M155 S0", "M105", "M104 S0"})
    h.send(l);
  h.run_until(6);
  ASSERT_TRUE(h.m->serial().finished());
  const auto ans = [&](const char* l) { return h.answer_of(l) ? h.answer_of(l)->answer : std::string("none"); };
  // At power-up: the first reading is taken before the banner.
  const std::string first = h.m->serial().responses().at(0).answer;
  EXPECT_TRUE(std::regex_match(first, std::regex(R"(ok T:2[45]\.\d\d /0\.00 @:0)"))) << first;
  EXPECT_EQ(ans("M104 S300"), "Error:temperature must be 0 .. 260 C");
  EXPECT_EQ(ans("M104 S-5"), "Error:temperature must be 0 .. 260 C");
  EXPECT_EQ(ans("M301 P1001"), "Error:gains must be P, I 0 .. 1000, D 0 .. 10000");
  // The refused lines changed nothing: the target was still 0 (M105 above),
  // the gains Marlin's until M301 set them.
  std::vector<std::string> echo;
  for (const std::string& l : h.m->serial().messages())
    if (l.rfind("echo:", 0) == 0) echo.push_back(l);
  ASSERT_EQ(echo.size(), 2u);
  EXPECT_EQ(echo[0], "echo: p:30.50 i:2.00 d:80.00");
  EXPECT_EQ(echo[1], "echo: p:30.50 i:2.00 d:80.00");
  // Auto-report: one status line a second from M155 S1 until M155 S0.
  std::vector<double> at;
  const auto& r = h.m->serial().received();
  for (size_t i = 0; i < r.size(); ++i)
    if (std::regex_match(r[i], kStatus)) at.push_back(double(h.m->serial().received_cycles()[i]) / kHz);
  ASSERT_GE(at.size(), 3u);
  for (size_t i = 1; i < at.size(); ++i) EXPECT_NEAR(at[i] - at[i - 1], 1.0, 0.002) << i;
  const double m155_off = double(h.answer_of("M155 S0")->answer_cycle) / kHz;
  EXPECT_LT(at.back(), m155_off);
  // The heater heated while M104 S150 held (pin high).
  EXPECT_GT(h.last_high_s(), 1.0);
  const std::string last = ans("M105");
  EXPECT_TRUE(std::regex_match(last, std::regex(R"(ok T:\d+\.\d\d /150\.00 @:\d+)"))) << last;
}

// M109 ends early when the host sends a line (M108); the target stays.
TEST(Heater, M109IsAbortedByAnyLineFromTheHost) {
  HotEnd h;
  h.send("M109 S200");
  h.run_until(3);
  const double sent = h.now_s();
  h.m->serial().send_raw("M108\n");
  h.run_until(4);
  const sim::Response* wait = h.answer_of("M109 S200");
  ASSERT_NE(wait, nullptr);
  EXPECT_EQ(wait->answer, "Error:wait ended by the host");
  EXPECT_GT(wait->answer_cycle / kHz, sent);
  EXPECT_LT(wait->answer_cycle / kHz, sent + 0.01);
  EXPECT_DOUBLE_EQ(h.last_high_s(), h.now_s());  // still heating: the target stays
}

// M303 from 25 C: Marlin's relay at 200 C over 3 cycles, its Ziegler-Nichols
// gains reported and applied; a new heat-up with them meets the bounds. On
// the m32-grbl image, which has the autotune (the Marlin image has the
// printer codes in its flash instead: firmware/board.h), so the lines are
// grbl's `[MSG:...]`.
TEST(Heater, AutotuneAt200GivesGainsThatMeetTheBounds) {
  HotEnd h(25, 40, "m32-grbl");
  h.send("M303 S200 C3");
  h.send("M301");
  h.run_until(136);
  ASSERT_TRUE(h.m->serial().finished());
  std::string done, echo;
  ASSERT_GT(h.line_time("[MSG:PID Autotune finished: ", &done), 0);
  ASSERT_GT(h.line_time("[MSG:p:", &echo), 0);
  std::smatch g;
  ASSERT_TRUE(std::regex_match(done, g, std::regex(R"(\[MSG:PID Autotune finished: (p:\d+\.\d\d i:\d+\.\d\d d:\d+\.\d\d)\])")))
      << done;
  EXPECT_EQ(echo, "[MSG:" + g[1].str() + "]");  // applied
  EXPECT_EQ(h.answer_of("M303 S200 C3")->answer, "ok");
  // It oscillated around the target, within Marlin's 30 C overshoot guard.
  double lo = 1e9, hi = -1e9;
  for (const sim::ThermalSample& s : h.plant->log())
    if (s.t_s > 95 && s.t_s < h.answer_of("M303 S200 C3")->answer_cycle / kHz)
      lo = std::min(lo, s.sensor_c), hi = std::max(hi, s.sensor_c);
  EXPECT_LT(lo, 200);
  EXPECT_GT(hi, 200);
  EXPECT_LT(hi, 230);
  std::printf("autotune: %s after %.1f s, oscillation %.2f .. %.2f C\n", done.c_str(),
              h.answer_of("M303 S200 C3")->answer_cycle / kHz, lo, hi);

  HotEnd t;
  float p = 0, i = 0, d = 0;
  ASSERT_EQ(std::sscanf(g[1].str().c_str(), "p:%f i:%f d:%f", &p, &i, &d), 3);
  char m301[64];
  std::snprintf(m301, sizeof m301, "M301 P%.2f I%.2f D%.2f", p, i, d);
  t.send(m301);
  t.send("M109 S200");
  t.send("G4 S80");
  t.run_until(125);
  double peak = 0, lo2 = 1e9, hi2 = -1e9, settled = 0;
  for (const sim::ThermalSample& s : t.plant->log()) {
    peak = std::max(peak, s.sensor_c);
    if (s.t_s >= 105) lo2 = std::min(lo2, s.sensor_c), hi2 = std::max(hi2, s.sensor_c);
    if (s.t_s > 60 && std::fabs(s.sensor_c - 200) > 0.3) settled = s.t_s;
  }
  EXPECT_LE(peak - 200, 1.0);
  EXPECT_GE(lo2, 199.7);
  EXPECT_LE(hi2, 200.3);
  std::printf("tuned heat-up 25 -> 200 C: overshoot %.2f C, within +-0.3 C from %.1f s, 105..125 s: %.2f .. %.2f C\n",
              peak - 200, settled, lo2, hi2);
}

// Power-up: the MOSFET's pin is a low output before any other peripheral is
// set up, OC2 disconnected, TEMP_OK low, and nothing pulses it.
TEST(Heater, PowerOnDrivesTheHeaterOffFirst) {
  sim::Machine m(simtest::image("m32"));
  const auto& heater = m.watch_pin('D', 7);
  const auto& temp_ok = m.watch_pin('D', 6);
  const uint8_t* d = m.avr()->data;
  constexpr uint16_t kDDRD = 0x31, kPORTD = 0x32, kUCSRB = 0x2A, kTCCR0 = 0x53, kTCCR1B = 0x4E, kTCCR2 = 0x45;
  const uint8_t at_reset[4] = {d[kUCSRB], d[kTCCR0], d[kTCCR1B], d[kTCCR2]};
  ASSERT_EQ(m.run([&] { return (d[kDDRD] & 0x80) != 0; }, 100000), sim::RunEnd::done);
  EXPECT_EQ(d[kPORTD] & 0x80, 0);
  // Nothing else is set up yet: the UART and the timers as at reset.
  EXPECT_EQ(d[kUCSRB], at_reset[0]);
  EXPECT_EQ(d[kTCCR0], at_reset[1]);
  EXPECT_EQ(d[kTCCR1B], at_reset[2]);
  EXPECT_EQ(d[kTCCR2], at_reset[3]);
  std::printf("heater pin a low output %llu cycles after reset\n", (unsigned long long)m.cycles());
  m.run([&] { return m.serial().banner_seen(); }, 16000000);
  m.serial().add_line("G4 S1");
  ASSERT_EQ(m.run_script(uint64_t(2 * kHz)), sim::RunEnd::done);
  for (const sim::PinEdge& e : heater) EXPECT_FALSE(e.level);
  for (const sim::PinEdge& e : temp_ok) EXPECT_FALSE(e.level);
  EXPECT_EQ(d[kTCCR2] & 0x30, 0);  // COM21:0 = 00: OC2 disconnected
  EXPECT_EQ(d[kTCCR2] & 0x4F, 0x4D);  // fast PWM, clk/128: 488 Hz once it is connected
}

// avrmotion-sim runs the hot end for an image with a heater: a hot start,
// a fan, a fault at a time, and the report's "thermal" figures; on a board
// without a heater the thermal options are a usage error.
TEST(Heater, TheSimCommandTakesAPlantScenario) {
  const std::string job = simtest::temp_path("heater-job.txt"), json = simtest::temp_path("heater.json");
  { std::ofstream(job) << "M104 S200\nG4 S3\n"; }
  const std::string sim = std::string("'") + AVRMOTION_SIM_EXE + "' --input '" + job + "'";
  const std::string cmd = sim + " --board m32 --report '" + json +
                          "' --thermal-initial 100 --thermal-fan 0.5@0.5 --thermal-fault open@1.5 2>/dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const std::string report = simtest::slurp(json);
  // The host's closing M400 waits out the 3 s dwell: Marlin's keep-alive
  // once, 2 s after it arrived; the fault's line once, about 0.5 s after
  // the break at 1.5 s. Which of the two comes first depends on a few
  // milliseconds of sampling phase, so either order.
  const bool fault_first =
      report.find("\"messages\": [\"Error:Thermistor open, heater halted until reset\", \"busy: processing\"]") !=
      std::string::npos;
  const bool busy_first =
      report.find("\"messages\": [\"busy: processing\", \"Error:Thermistor open, heater halted until reset\"]") !=
      std::string::npos;
  EXPECT_TRUE(fault_first || busy_first) << report;
  std::smatch t;
  ASSERT_TRUE(std::regex_search(report, t,
                                std::regex(R"("thermal": \{"peak_c": ([0-9.]+), "final_c": ([0-9.]+), )"
                                           R"("final_block_c": ([0-9.]+), "fault": "open"\})")))
      << report;
  EXPECT_GT(std::stod(t[1]), 100.0);  // it heated from 100 C until the break
  EXPECT_LT(std::stod(t[1]), 105.0);
  const int rc = std::system((sim + " --board uno --report /dev/null --thermal-fault open@1 2>/dev/null").c_str());
  EXPECT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) == 2) << rc;
  std::remove(job.c_str());
  std::remove(json.c_str());
}

// A board without a heater refuses the heater codes, clearly.
TEST(Heater, TheUnoHasNoHeater) {
  auto m = simtest::run("uno", {"M104 S200", "M105", "M303", "M500"}, 2);
  for (const sim::Response& r : m->serial().responses()) {
    EXPECT_EQ(r.answer, "error:20");  // grbl's "unsupported command"
    EXPECT_EQ(r.reason, "this board has no heater");
  }
  EXPECT_EQ(m->serial().responses().size(), 4u);
}

// M500 keeps M301's gains through a power cycle: the EEPROM of one run,
// copied into a fresh machine before it starts, is what that one boots
// with. An EEPROM that holds something else (erased, or one byte of the
// gains changed) gives Marlin's defaults.
TEST(Heater, M500StoresTheGainsAndABootTakesThemBack) {
  constexpr uint32_t kBytes = 16;
  const auto eeprom_of = [](sim::Machine& m) {
    std::vector<uint8_t> bytes = m.eeprom(kBytes);
    EXPECT_EQ(bytes.size(), size_t(kBytes));
    return bytes;
  };
  const auto boot_with = [](std::vector<uint8_t> bytes) {
    std::unique_ptr<sim::Machine> m(new sim::Machine(simtest::image("m32")));
    m->set_eeprom(bytes);
    m->serial().add_line("M301");
    EXPECT_EQ(m->run_script(uint64_t(m->f_cpu()) * 2), sim::RunEnd::done);
    return m->serial().messages().back();
  };
  auto first = simtest::run("m32", {"M301", "M301 P30.5 I2 D80", "M500"}, 5);
  EXPECT_EQ(first->serial().messages().front(), "echo: p:22.20 i:1.08 d:114.00");  // Marlin's, from an erased EEPROM
  EXPECT_EQ(first->serial().messages().back(), "echo:Settings Stored: p:30.50 i:2.00 d:80.00");
  const std::vector<uint8_t> stored = eeprom_of(*first);
  EXPECT_EQ(boot_with(stored), "echo: p:30.50 i:2.00 d:80.00");
  std::vector<uint8_t> torn = stored;
  torn[4] ^= 0x10;  // a byte of the gains
  EXPECT_EQ(boot_with(torn), "echo: p:22.20 i:1.08 d:114.00");
  EXPECT_EQ(boot_with(std::vector<uint8_t>(kBytes, 0xFF)), "echo: p:22.20 i:1.08 d:114.00");
}

}  // namespace

namespace {

// The heater's share of the m32 image, from its symbol table (avr-nm, of the
// toolchain that built it): the service's functions, tables and texts (the
// PID, safety, thermistor and filter code it inlines into heater::poll), the
// core's out-of-line PID and autotune functions, the interpreter's heater
// codes and their error texts; RAM: the service's variables.
TEST(Heater, FlashAndRamOnTheM32) {
  const std::string cmd = "avr-nm -S -C " + simtest::image("m32");
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  const char* const kTextErrors[] = {"no_heater_text",       "heater_code_alone_text", "missing_temperature_text",
                                     "bad_temperature_text", "bad_interval_text",      "bad_gains_text",
                                     "bad_cycles_text"};
  unsigned long flash = 0, ram = 0;
  char buf[512];
  while (fgets(buf, sizeof buf, p)) {
    unsigned long addr = 0, size = 0;
    char type = 0;
    int used = 0;
    if (std::sscanf(buf, "%lx %lx %c %n", &addr, &size, &type, &used) < 3) continue;
    const std::string name(buf + used);
    const bool heater = name.rfind("heater::", 0) == 0;
    const bool code = std::strchr("tTwW", type) != nullptr;
    bool ours = heater || name.find("HeaterPid::") != std::string::npos ||
                name.find("RelayAutotune::") != std::string::npos || name.rfind("am::mul_div_round", 0) == 0 ||
                name.find("AdcOversampler") != std::string::npos ||
                (name.find("GcodeInterpreter") != std::string::npos && name.find(">::heater(") != std::string::npos);
    for (const char* e : kTextErrors) ours = ours || name.find(e) != std::string::npos;
    if (!ours) continue;
    if (code) flash += size;
    else if (heater && std::strchr("bBdD", type)) ram += size;
  }
  pclose(p);
  std::printf("heater on the m32: %lu B of flash, %lu B of RAM\n", flash, ram);
  EXPECT_GT(flash, 4000u);  // it is there
  EXPECT_LE(flash, 8192u);
  EXPECT_LE(ram, 200u);
}

}  // namespace
