// The settings in the EEPROM (firmware/services/settings.h, docs/settings.md)
// on the real m32-direct image: `$$` with the board's figures, `$N=value`
// changing what the pins do, refusals that change nothing, the block kept
// through a power cycle, and a corrupt or older block loading the defaults
// with one line that says so.
#include <sim_avr.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "endstops.h"
#include "sim_fixture.h"

namespace {

const char kImage[] = "m32-direct";
constexpr uint32_t kBytes = 4 + 4 * 30 + 2;  // the m32-direct block: header, 30 values, sum
const char kCorrupt[] = "[MSG:EEPROM settings corrupt: defaults loaded]";
const char kOlder[] = "[MSG:EEPROM settings of another version: defaults loaded]";

std::vector<uint8_t> eeprom_of(sim::Machine& m, uint32_t bytes = kBytes) {
  std::vector<uint8_t> got = m.eeprom(bytes);
  EXPECT_EQ(got.size(), bytes);
  return got;
}

// A fresh machine whose EEPROM starts as `bytes`, running `lines`.
std::unique_ptr<sim::Machine> boot_with(std::vector<uint8_t> bytes, const std::vector<std::string>& lines,
                                        double seconds = 5) {
  std::unique_ptr<sim::Machine> m(new sim::Machine(simtest::image(kImage)));
  m->set_eeprom(bytes);
  for (const std::string& l : lines) m->serial().add_line(l);
  EXPECT_EQ(m->run_script(uint64_t(seconds * m->f_cpu())), sim::RunEnd::done);
  return m;
}

// `$N=value` lines of a run, by number.
std::map<int, std::string> settings_of(sim::Machine& m) {
  std::map<int, std::string> s;
  for (const std::string& l : m.serial().messages()) {
    const size_t eq = l.find('=');
    if (l.size() > 1 && l[0] == '$' && eq != std::string::npos) s[std::stoi(l.substr(1, eq - 1))] = l.substr(eq + 1);
  }
  return s;
}

size_t count_of(sim::Machine& m, const std::string& line) {
  size_t n = 0;
  for (const std::string& l : m.serial().received()) n += l == line;
  return n;
}

std::string mm(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

// The board's figures (firmware/boards/common/m32_wiring.h: kMaxStepRate
// 40000 steps/s, kDefaultAccel 500000 steps/s^2, printer_homing()), written
// here again on their own and turned into mm with the image's own steps/mm
// (its descriptor, as the simulator reads it).
std::map<int, std::string> board_defaults(sim::Machine& m) {
  std::map<int, std::string> d;
  const char* names = "XYZE";
  d[11] = "0.010";
  d[20] = "1";
  d[21] = "1";
  d[22] = "1";
  d[23] = "0";
  d[200] = "0";
  for (int a = 0; a < 4; ++a) {
    const double spmm = m.axis(names[a])->steps_per_mm;
    d[100 + a] = mm(spmm);
    d[110 + a] = mm(40000.0 * 60 / spmm);
    d[120 + a] = mm(500000.0 / spmm);
    if (a == 3) continue;  // E has no switch
    const double seek = a == 2 ? 4000 : 25000, locate = a == 2 ? 500 : 1000, travel = a == 2 ? 180000 : 200000;
    d[130 + a] = mm(travel / spmm);
    d[240 + a] = mm(locate * 60 / spmm);
    d[250 + a] = mm(seek * 60 / spmm);
    d[270 + a] = mm(1000 / spmm);
  }
  return d;
}

TEST(Settings, DollarDollarListsEverySettingWithTheBoardsDefaults) {
  auto m = simtest::run(kImage, {"$$", "$"});
  for (const std::string& l : m->serial().received()) std::printf("  %s\n", l.c_str());  // docs/settings.md
  const std::vector<sim::Response>& r = m->serial().responses();
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].answer, "ok");
  const std::map<int, std::string> listed = settings_of(*m), expected = board_defaults(*m);
  EXPECT_EQ(listed, expected);
  EXPECT_EQ(listed.size(), 30u);
  // In grbl's order, one line each, and the help names them.
  std::vector<int> order;
  for (const std::string& l : m->serial().messages())
    if (l[0] == '$') order.push_back(std::stoi(l.substr(1)));
  EXPECT_TRUE(std::is_sorted(order.begin(), order.end()));
  EXPECT_EQ(order.size(), 30u);
  EXPECT_EQ(m->serial().messages().back(), "[HLP:$ $$ $x=val $RST=$ $I $G $X]");
  // An erased EEPROM is no corruption: nothing said at boot.
  EXPECT_EQ(count_of(*m, kCorrupt) + count_of(*m, kOlder), 0u);
}

// Steps/mm sweep: each axis's steps on the pins are the setting times the
// distance, rounded to the step, and M114 reports the distance asked.
TEST(Settings, StepsPerMmSetTheStepsOnThePins) {
  struct Case {
    const char* setting;
    const char* move;
    char axis;
    double steps;       // on the pins, computed by hand
    std::string report;  // M114's word for the axis
  };
  const Case cases[] = {
      {"$100=80", "G1 X10 F600", 'X', 800, "X:10.0000"},
      {"$101=12.5", "G1 Y8 F600", 'Y', 100, "Y:8.0000"},
      {"$102=400.25", "G1 Z2 F300", 'Z', 801, "Z:2.0000"},           // 800.5 steps: 801
      {"$103=93.0005", "G1 E-3.3 F300", 'E', -307, "E:-3.3000"},     // 93.001 * -3.3 = -306.9
      {"$100=625.5", "G1 X1.2345 F600", 'X', 772, "X:1.2345"},        // 772.18
      {"$101=833.333", "G1 Y-0.51 F100", 'Y', -425, "Y:-0.5100"},     // -424.9998
  };
  for (const Case& c : cases) {
    auto m = simtest::run(kImage, {c.setting, c.move, "M400", "M114"});
    const std::vector<sim::Response>& r = m->serial().responses();
    ASSERT_EQ(r.size(), 4u) << c.setting;
    for (const sim::Response& x : r) EXPECT_EQ(x.answer, "ok") << c.setting << " " << x.line << " " << x.reason;
    EXPECT_EQ(m->axis(c.axis)->steps(), c.steps) << c.setting << " " << c.move;
    EXPECT_EQ(m->axis(c.axis)->step_cycles.size(), size_t(std::fabs(c.steps))) << c.setting;
    for (const sim::AxisTrace& a : m->axes()) {
      if (a.name != c.axis) {
        EXPECT_TRUE(a.step_cycles.empty()) << c.setting << " " << a.name;
      }
    }
    const std::string report = m->serial().messages().back();
    EXPECT_NE(report.find(c.report), std::string::npos) << report;
    const size_t counted = report.find(" Count ");
    ASSERT_NE(counted, std::string::npos) << report;
    const std::string count = std::string(1, c.axis) + ":" + std::to_string(long(c.steps));
    EXPECT_NE((report.substr(counted) + " ").find(" " + count + " "), std::string::npos) << report << " " << count;
  }
}

// X's time from its first step to its last.
double seconds_of(sim::Machine& m, char axis) {
  const std::vector<uint64_t>& c = m.axis(axis)->step_cycles;
  return c.size() < 2 ? 0 : double(c.back() - c.front()) / m.f_cpu();
}

// The max rate and the acceleration are the planner's: a 10 mm move at a
// feed above $110 runs at $110 (said so), its ramps at $120; the time of a
// trapezoid from rest to rest is L / v + v / a, from its first step
// (sqrt(2 / a) after the start) L / v + v / a - sqrt(2 / a).
TEST(Settings, RateAndAccelerationAreWhatTheMoveRunsAt) {
  struct Case {
    const char* rate;
    const char* accel;
    double v, a;  // steps/s, steps/s^2 at 1000 steps/mm
  };
  const Case cases[] = {{"$110=600", "$120=100", 10000, 100000},
                        {"$110=1200", "$120=250", 20000, 250000},
                        {"$110=2400", "$120=500", 40000, 500000},
                        {"$110=300", "$120=800", 5000, 800000}};
  for (const Case& c : cases) {
    auto m = simtest::run(kImage, {c.rate, c.accel, "G1 X10 F6000", "M400"});
    const std::vector<sim::Response>& r = m->serial().responses();
    ASSERT_EQ(r.size(), 4u);
    for (const sim::Response& x : r) EXPECT_EQ(x.answer, "ok") << x.line;
    EXPECT_EQ(m->axis('X')->steps(), 10000);
    const double expected = 10000 / c.v + c.v / c.a - std::sqrt(2 / c.a);
    EXPECT_NEAR(seconds_of(*m, 'X'), expected, 0.0002 + expected * 0.001) << c.rate << " " << c.accel;
    // No step interval shorter than the rate's.
    EXPECT_GE(double(m->axis('X')->min_interval()), m->f_cpu() / c.v * 0.98) << c.rate;
    if (c.v < 100000) {
      const std::string clamped = "[MSG:F clamped to " + std::to_string(int(c.v * 60 / 1000)) + " mm/min]";
      EXPECT_EQ(count_of(*m, clamped), 1u) << clamped;
    }
    std::printf("%s %s: 10 mm in %.5f s (L/v + v/a - sqrt(2/a) = %.5f s)\n", c.rate, c.accel, seconds_of(*m, 'X'),
                expected);
  }
}

// The junction deviation is the planner's: a right-angle corner at a feed
// runs through faster the larger $11 is.
TEST(Settings, JunctionDeviationIsTheCornersSpeed) {
  std::vector<double> times;
  for (const char* j : {"$11=0.001", "$11=0.010", "$11=0.100", "$11=1"}) {
    auto m = simtest::run(kImage, {j, "G1 X5 F1800", "G1 Y5", "M400"});
    for (const sim::Response& x : m->serial().responses()) EXPECT_EQ(x.answer, "ok") << x.line;
    EXPECT_EQ(m->axis('X')->steps(), 5000);
    EXPECT_EQ(m->axis('Y')->steps(), 5000);
    const double t = double(m->axis('Y')->step_cycles.back() - m->axis('X')->step_cycles.front()) / m->f_cpu();
    times.push_back(t);
    std::printf("%s: the corner path in %.4f s\n", j, t);
  }
  for (size_t i = 1; i < times.size(); ++i) EXPECT_LT(times[i], times[i - 1] - 0.0005) << i;
}

// A new steps/mm at a position: the steps there stay, their mm view moves,
// and the next move counts from the steps.
TEST(Settings, ANewScaleKeepsTheMachinePositionInSteps) {
  auto m = simtest::run(kImage, {"$100=80", "G1 X10 F600", "$100=160", "M114", "G1 X10", "M400", "M114", "$$"});
  for (const sim::Response& x : m->serial().responses()) EXPECT_EQ(x.answer, "ok") << x.line;
  std::vector<std::string> reports;
  for (const std::string& l : m->serial().messages())
    if (l.rfind("X:", 0) == 0) reports.push_back(l);
  ASSERT_EQ(reports.size(), 2u);
  EXPECT_EQ(reports[0].rfind("X:5.0000 ", 0), 0u) << reports[0];  // 800 steps at 160 steps/mm
  EXPECT_NE(reports[0].find("Count X:800 "), std::string::npos) << reports[0];
  EXPECT_EQ(reports[1].rfind("X:10.0000 ", 0), 0u) << reports[1];
  EXPECT_NE(reports[1].find("Count X:1600 "), std::string::npos) << reports[1];
  EXPECT_EQ(m->axis('X')->steps(), 1600);
  EXPECT_EQ(settings_of(*m)[100], "160.000");
}

// A change that arrives while the axes move waits for them to stop: the
// move keeps its steps, the answer comes after its last step.
TEST(Settings, AChangeWaitsForTheMachineAtRest) {
  auto m = simtest::run(kImage, {"G1 X10 F1200", "$100=80", "M114", "G1 X130"});
  const std::vector<sim::Response>& r = m->serial().responses();
  ASSERT_EQ(r.size(), 4u);
  for (const sim::Response& x : r) EXPECT_EQ(x.answer, "ok") << x.line;
  const std::vector<uint64_t>& steps = m->axis('X')->step_cycles;
  ASSERT_EQ(steps.size(), 10000u + 400u);  // 10 mm at 1000, then 5 mm at 80
  EXPECT_GT(r[1].answer_cycle, steps[9999]);
  EXPECT_LT(r[1].sent_cycle, steps[9999] - uint64_t(0.3 * m->f_cpu()));  // sent well before the move ended
  bool found = false;
  for (const std::string& l : m->serial().messages()) found |= l.rfind("X:125.0000 ", 0) == 0;  // 10000 / 80
  EXPECT_TRUE(found);
}

// Out of range, not a number, read-only, unknown, beyond the engine: each
// refused with its error, and `$$` after them is the defaults, the moves
// as before.
TEST(Settings, RefusalsChangeNothing) {
  const std::vector<std::pair<std::string, std::string>> refused = {
      {"$100=0.999", "error:100"},  {"$100=10000.001", "error:100"}, {"$11=0", "error:100"},
      {"$11=10.001", "error:100"},  {"$20=2", "error:100"},          {"$270=1000.001", "error:100"},
      {"$100=-80", "error:100"},    {"$100=abc", "error:2"},         {"$100=", "error:2"},
      {"$20=1.0", "error:2"},       {"$21=0", "error:3"},            {"$23=1", "error:3"},
      {"$200=2", "error:100"},      {"$24=1", "error:3"},            {"$133=10", "error:3"},
      {"$110=2400.030", "error:12"}, {"$120=800.001", "error:12"},   {"$100=1000.02", "error:12"},
      {"$250=2401", "error:12"},    {"$RST=*", "error:3"},
  };
  std::vector<std::string> lines;
  for (const auto& r : refused) lines.push_back(r.first);
  lines.push_back("$$");
  lines.push_back("G1 X1 F600");
  auto m = simtest::run(kImage, lines);
  const std::vector<sim::Response>& r = m->serial().responses();
  ASSERT_EQ(r.size(), refused.size() + 2);
  for (size_t i = 0; i < refused.size(); ++i) {
    EXPECT_EQ(r[i].answer, refused[i].second) << refused[i].first << ": " << r[i].reason;
    EXPECT_FALSE(r[i].reason.empty()) << refused[i].first;
  }
  EXPECT_EQ(r[0].reason, "setting out of range");
  EXPECT_EQ(r[7].reason, "bad number");
  EXPECT_EQ(r[10].reason, "setting is read-only");
  EXPECT_EQ(r[12].reason, "setting out of range");  // $200: 0 grbl, 1 Marlin (test_protocol_switch.cpp)
  EXPECT_EQ(r[13].reason, "no such setting");
  EXPECT_EQ(r[15].reason, "setting beyond the engine's step rate or acceleration");
  EXPECT_EQ(settings_of(*m), board_defaults(*m));
  EXPECT_EQ(m->axis('X')->steps(), 1000);
  // Nothing was written.
  const std::vector<uint8_t> ee = eeprom_of(*m);
  EXPECT_EQ(ee, std::vector<uint8_t>(kBytes, 0xFF));
}

// The edges themselves are taken (the engine's: 40000 steps/s, 800000
// steps/s^2), and a rate at the top runs at it.
TEST(Settings, TheEdgesAreTaken) {
  auto m = simtest::run(kImage, {"$100=1", "$100=10000", "$100=1000", "$11=0.001", "$11=10", "$110=2400", "$120=800",
                                 "$270=0", "$133", "$$"});
  const std::vector<sim::Response>& r = m->serial().responses();
  ASSERT_EQ(r.size(), 10u);
  // 10000 steps/mm makes 2400 mm/min 400000 steps/s: refused; 1 step/mm takes.
  EXPECT_EQ(r[0].answer, "ok");
  EXPECT_EQ(r[1].answer, "error:12");
  for (size_t i = 2; i < 8; ++i) EXPECT_EQ(r[i].answer, "ok") << r[i].line << " " << r[i].reason;
  EXPECT_EQ(r[8].answer, "error:3");  // no '=': no such setting line
  std::map<int, std::string> s = settings_of(*m);
  EXPECT_EQ(s[11], "10.000");
  EXPECT_EQ(s[100], "1000.000");
  EXPECT_EQ(s[270], "0.000");
}

// The block survives a power cycle: the EEPROM of one run, copied into a
// fresh machine, is what it boots with; `$RST=$` stores the defaults.
TEST(Settings, SettingsSurviveARebootAndRstRestoresTheDefaults) {
  const std::vector<std::string> changes = {"$100=80", "$111=1234.5", "$122=12.25", "$11=0.05",
                                            "$20=0",   "$132=95.5",   "$251=900",   "$272=2.5"};
  auto first = simtest::run(kImage, changes);
  for (const sim::Response& x : first->serial().responses()) EXPECT_EQ(x.answer, "ok") << x.line << " " << x.reason;
  const std::vector<uint8_t> stored = eeprom_of(*first);
  auto second = boot_with(stored, {"$$", "G1 X10 F600", "M400"});
  std::map<int, std::string> expected = board_defaults(*second);
  expected[100] = "80.000";
  expected[111] = "1234.500";
  expected[122] = "12.250";
  expected[11] = "0.050";
  expected[20] = "0";
  expected[132] = "95.500";
  expected[251] = "900.000";
  expected[272] = "2.500";
  EXPECT_EQ(settings_of(*second), expected);
  EXPECT_EQ(second->axis('X')->steps(), 800);
  EXPECT_EQ(count_of(*second, kCorrupt) + count_of(*second, kOlder), 0u);
  auto third = boot_with(eeprom_of(*second), {"$RST=$"});
  auto fourth = boot_with(eeprom_of(*third), {"$$", "G1 X10 F600", "M400"});
  EXPECT_EQ(settings_of(*fourth), board_defaults(*fourth));
  EXPECT_EQ(fourth->axis('X')->steps(), 10000);
}

// A corrupted block (any one byte of it changed) and a block of another
// version load the defaults and say so once, right after the banner.
TEST(Settings, ACorruptOrOlderBlockLoadsTheDefaultsAndSaysSoOnce) {
  auto first = simtest::run(kImage, {"$100=80", "$101=160"});
  const std::vector<uint8_t> stored = eeprom_of(*first);
  ASSERT_EQ(stored[0], 0x77);  // the tag 0x5E77, little-endian
  ASSERT_EQ(stored[1], 0x5E);
  // Byte 3 is the header's count (another layout: not this version's).
  for (size_t at : {size_t(3), size_t(4), size_t(7), size_t(8), size_t(60), size_t(kBytes - 2), size_t(kBytes - 1)}) {
    std::vector<uint8_t> torn = stored;
    torn[at] ^= 0x04;
    auto m = boot_with(torn, {"$$", "G1 X10 F600", "M400", "$$"});
    const std::vector<std::string>& rx = m->serial().received();
    const char* said = at == 3 ? kOlder : kCorrupt;
    ASSERT_GE(rx.size(), 3u);
    EXPECT_EQ(rx[2], said) << at;  // after the two banner lines
    EXPECT_EQ(count_of(*m, kCorrupt) + count_of(*m, kOlder), 1u) << at;
    EXPECT_EQ(settings_of(*m), board_defaults(*m)) << at;
    EXPECT_EQ(m->axis('X')->steps(), 10000) << at;  // 1000 steps/mm, the board's
  }
  // Version 0 under the same tag, its sum made right: another version.
  std::vector<uint8_t> older = stored;
  older[2] = 0;
  uint16_t sum = 0x5A5A;
  for (size_t i = 0; i + 2 < kBytes; ++i) sum = uint16_t((sum << 1 | sum >> 15) ^ older[i]);
  older[kBytes - 2] = uint8_t(sum);
  older[kBytes - 1] = uint8_t(sum >> 8);
  auto m = boot_with(older, {"$$", "G1 X10 F600", "M400"});
  ASSERT_GE(m->serial().received().size(), 3u);
  EXPECT_EQ(m->serial().received()[2], kOlder);
  EXPECT_EQ(count_of(*m, kOlder), 1u);
  EXPECT_EQ(count_of(*m, kCorrupt), 0u);
  EXPECT_EQ(settings_of(*m), board_defaults(*m));
  EXPECT_EQ(m->axis('X')->steps(), 10000);
  // A changed tag is no block of ours (another image's bytes, docs/settings.md):
  // the defaults, without a word.
  std::vector<uint8_t> other = stored;
  other[0] ^= 0x01;
  auto o = boot_with(other, {"$$"});
  EXPECT_EQ(count_of(*o, kCorrupt) + count_of(*o, kOlder), 0u);
  EXPECT_EQ(settings_of(*o), board_defaults(*o));
  // Its sum checked the same way, the stored block itself is taken.
  auto good = boot_with(stored, {"G1 X10 F600", "M400"});
  EXPECT_EQ(good->axis('X')->steps(), 800);
}

// The homing settings are what G28 runs: X seeks at $250 (600 mm/min:
// 10000 steps/s, its fastest steps), pulls off by $270 above the switch;
// Z's travel ($132) is the soft limit, and $20=0 lifts it.
TEST(Settings, HomingRunsAtItsSettingsAndTheSoftLimitsFollowThem) {
  for (const bool soft : {true, false}) {
    sim::Machine m(simtest::image(kImage));
    sim::Endstops switches(m);
    switches.set_position('X', -3000);  // X 3 mm above its switch
    switches.set_position('Y', -1000);
    switches.set_position('Z', -500);
    const std::vector<std::string> lines = {"$250=600", "$270=2.5", "$132=3", soft ? "$20=1" : "$20=0", "G28",
                                            "G1 Z3 F600", "G1 Z3.001", "M400", "M114"};
    for (const std::string& l : lines) m.serial().add_line(l);
    ASSERT_EQ(m.run_script(uint64_t(20 * m.f_cpu())), sim::RunEnd::done);
    const std::vector<sim::Response>& r = m.serial().responses();
    ASSERT_EQ(r.size(), lines.size());
    for (size_t i = 0; i < 6; ++i) EXPECT_EQ(r[i].answer, "ok") << lines[i] << " " << r[i].reason;
    if (soft) {
      EXPECT_EQ(r[6].answer, "error:118");
      EXPECT_EQ(r[6].reason, "move beyond the soft limits");
    } else {
      EXPECT_EQ(r[6].answer, "ok");
    }
    // The switch closes within a step of -3000; X 2500 steps back up from
    // there, Y and Z the board's 1000 ($271, $272 unchanged).
    EXPECT_NEAR(double(m.axis('X')->position), -3000 + 2500, 1.5);
    EXPECT_NEAR(double(m.axis('Y')->position), -1000 + 1000, 1.5);
    EXPECT_NEAR(double(m.axis('Z')->position), -500 + 1000 + (soft ? 3000 : 3001), 1.5);
    // The shortest step interval is the seek's, less at most the software
    // edges' spread (48 cycles, docs/step-engine.md): where an edge falls in
    // its handler moves with the interrupts around it, not with the setting.
    constexpr double kEdgeSpread = 48;
    const double fastest = double(m.axis('X')->min_interval());
    EXPECT_NEAR(fastest, m.f_cpu() / 10000.0, kEdgeSpread);  // $250 = 10000 steps/s
    // Y keeps the board's 25 mm/s.
    EXPECT_NEAR(double(m.axis('Y')->min_interval()), m.f_cpu() / 25000.0, kEdgeSpread);
    std::printf("$20=%d: X's fastest step %.0f cycles; %s\n", soft, fastest, m.serial().messages().back().c_str());
  }
}

// Homing off ($22=0) refuses G28 and $H, grbl's error 5.
TEST(Settings, HomingFollowsItsSetting) {
  auto m = simtest::run(kImage, {"$22=0", "G28", "$H", "$22=1"});
  const std::vector<sim::Response>& r = m->serial().responses();
  ASSERT_EQ(r.size(), 4u);
  EXPECT_EQ(r[1].answer, "error:5");
  EXPECT_EQ(r[1].reason, "homing is off ($22=0)");
  EXPECT_EQ(r[2].answer, "error:5");
  EXPECT_EQ(r[3].answer, "ok");
}

}  // namespace
