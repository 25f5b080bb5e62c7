// The m1284 image (firmware/boards/m1284.h): the ATmega32 board's printer
// with an ATmega1284P in its socket, every part of the cnc program in one
// image. What only this image has, on the real image: the pin polarities
// ($3 over every mask, $5 with normally-closed switches: homing from both
// sides and a hard limit), the machine codes' settings (M301, M204, M207,
// M208: M500, a power cycle, M502), Marlin's style by default with the realtime bytes
// left in the text of its lines, and grbl's after `$200=0` with them taken.
// The other suites run their parts on the m32 images (test_realtime.cpp
// runs this one too).
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "endstops.h"
#include "sim_fixture.h"

namespace {

const char kImage[] = "m1284";
// Sends `lines` and runs until they are answered and motion has ended;
// returns the index of the first new response.
size_t send(sim::Machine& m, const std::vector<std::string>& lines, double seconds = 20) {
  const size_t first = m.serial().responses().size();
  for (const std::string& l : lines) m.serial().add_line(l);
  EXPECT_EQ(m.run_script(uint64_t(seconds * m.f_cpu())), sim::RunEnd::done);
  return first;
}

bool ok(sim::Machine& m, size_t i) { return sim::SerialHost::is_ok(m.serial().responses().at(i).answer); }

// The last received line that starts with `prefix` ("" if none).
std::string last_starting(sim::Machine& m, const std::string& prefix) {
  const std::vector<std::string>& r = m.serial().received();
  for (auto it = r.rbegin(); it != r.rend(); ++it)
    if (it->rfind(prefix, 0) == 0) return *it;
  return "";
}

// M114's `Count X:.. Y:.. Z:.. E:..` value of axis `a`.
long count_of(const std::string& m114, char a) {
  const size_t at = m114.find(std::string(" ") + a + ":", m114.find("Count"));
  return at == std::string::npos ? -999999 : std::strtol(m114.c_str() + at + 3, nullptr, 10);
}

}  // namespace

// Every mask of the four axes: a move of +1 mm on each axis reaches the
// pins backwards on exactly the masked axes (the simulator decodes the
// direction lines), and the firmware's counts go forward on all of them.
TEST(M1284, DirectionInvertMaskFlipsExactlyTheMaskedAxes) {
  sim::Machine m(simtest::image(kImage));
  const char axes[] = {'X', 'Y', 'Z', 'E'};
  ASSERT_TRUE(ok(m, send(m, {"G91", "M83"})));
  long pins[4] = {0, 0, 0, 0};
  for (int mask = 0; mask < 16; ++mask) {
    const size_t first = send(m, {"$3=" + std::to_string(mask), "G1 X1 Y1 Z1 E1 F600", "M400", "M114"});
    ASSERT_TRUE(ok(m, first)) << mask;
    ASSERT_TRUE(ok(m, first + 1)) << mask;
    const std::string m114 = last_starting(m, "X:");
    for (int a = 0; a < 4; ++a) {
      const long now = long(m.axis(axes[a])->position);
      EXPECT_EQ(now - pins[a], (mask >> a & 1) ? -1000 : 1000) << "mask " << mask << " axis " << axes[a];
      pins[a] = now;
      EXPECT_EQ(count_of(m114, axes[a]), 1000L * (mask + 1)) << "mask " << mask << " axis " << axes[a];
    }
  }
  // Beyond the axes, and not a whole number: refused, the mask kept.
  const size_t refused = send(m, {"$3=16", "$3=1.5", "M503"});
  EXPECT_FALSE(ok(m, refused));
  EXPECT_FALSE(ok(m, refused + 1));
  EXPECT_EQ(last_starting(m, "echo:  $3="), "echo:  $3=15");
}

// Normally-closed switches (their pins high while pressed): with $5=1 the
// homing finds each within one step from either side, as the normally-open
// ones are found (test_homing.cpp); without it an open contact reads
// closed, the homing backs off a switch that never opens and says so.
TEST(M1284, LimitInvertHomesOnNormallyClosedSwitchesFromEitherSide) {
  for (const int64_t at : {-2345L, -1L, 0L, 640L}) {
    sim::Machine m(simtest::image(kImage));
    sim::EndstopParams nc;
    nc.normally_closed = true;
    sim::Endstops switches(m, nc);
    for (char a : {'X', 'Y', 'Z'}) switches.set_position(a, at);
    const size_t first = send(m, {"$5=1", "G28", "M114"}, 60);
    ASSERT_TRUE(ok(m, first)) << at;
    ASSERT_TRUE(ok(m, first + 1)) << "switches at " << at;
    const std::string m114 = last_starting(m, "X:");
    for (char a : {'X', 'Y', 'Z'}) {
      EXPECT_EQ(count_of(m114, a), 0) << a;
      // 1 mm pull-off: the trip point within one step of the switch.
      const int64_t trip = m.axis(a)->position - 1000;
      EXPECT_LE(std::llabs(trip - at), 1) << a << ": switch at " << at << ", stopped at " << trip;
      EXPECT_FALSE(switches.closed(a));
    }
  }
  sim::Machine m(simtest::image(kImage));
  sim::EndstopParams nc;
  nc.normally_closed = true;
  sim::Endstops switches(m, nc);
  switches.set_position('X', -300);
  const size_t first = send(m, {"G28 X0"}, 60);
  EXPECT_FALSE(ok(m, first));
  EXPECT_EQ(m.serial().responses().at(first).reason, "homing: endstop stays closed");
  EXPECT_EQ(m.axis('X')->position, 1000);  // the back-off away from it, and no further
}

// A normally-closed switch met by a move (soft limits off), at switch
// positions from the first step on and feeds from a crawl to the top rate,
// clean and bouncing: the steps stop at the switch's step, the machine
// refuses the next move, M999 unlocks.
TEST(M1284, AHardLimitOnANormallyClosedSwitchStopsAtIt) {
  int runs = 0;
  for (const int64_t at : {-1L, -777L, -3000L}) {
    for (const int feed : {60, 1200, 2400}) {
      for (const double bounce_us : {0.0, 200.0}) {
        sim::Machine m(simtest::image(kImage));
        sim::EndstopParams nc;
        nc.normally_closed = true;
        nc.bounce_us = bounce_us;
        sim::Endstops switches(m, nc);
        switches.set_position('X', at);
        const std::string where = "switch at " + std::to_string(at) + ", F" + std::to_string(feed) + ", bounce " +
                                  std::to_string(int(bounce_us)) + " us";
        const size_t first =
            send(m, {"$5=1", "$20=0", "G1 X-4 F" + std::to_string(feed), "M400", "G1 X1"}, 10);
        ASSERT_TRUE(ok(m, first + 2)) << where;
        // The switch closes at `at` (X's pin, INT0, latches the closing
        // edge): that step is the last.
        EXPECT_EQ(m.axis('X')->position, at) << where;
        EXPECT_FALSE(ok(m, first + 4)) << where;
        EXPECT_TRUE(ok(m, send(m, {"M999", "G1 X0 F2400"}) + 1)) << where;
        ++runs;
      }
    }
  }
  EXPECT_EQ(runs, 18);
}

// The machine codes' settings are in the block here: the heater's gains
// ($300..302), M204's path accelerations ($210..212), M207's and M208's
// retraction ($220..224). As in Marlin the codes change what is in force
// (M503 shows it: it reads the heater, the planner and the interpreter) and
// M500 stores it; a power cycle without M500 runs on what was stored, with
// it on the new figures (M503 again, M301's report, a G10's steps); M502
// brings back the defaults. One block in the EEPROM: nothing past it.
TEST(M1284, M500StoresTheMachineCodesSettingsInForce) {
  const std::vector<std::string> codes = {"M301 P30.5 I2.25 D100", "M204 P800 T1500 R400", "M207 S4.5 F1800 Z0.4",
                                          "M208 S0.2 F600", "M503"};
  const std::vector<std::pair<std::string, std::string>> changed = {
      {"$300=", "30.500"},  {"$301=", "2.250"},    {"$302=", "100.000"}, {"$210=", "800.000"},
      {"$211=", "1500.000"}, {"$212=", "400.000"}, {"$220=", "4.500"},   {"$221=", "1800.000"},
      {"$222=", "0.400"},   {"$223=", "0.200"},    {"$224=", "600.000"}};
  const std::vector<std::pair<std::string, std::string>> defaults = {
      {"$300=", "22.200"}, {"$301=", "1.080"},    {"$302=", "114.000"}, {"$210=", "0.000"},
      {"$211=", "0.000"},  {"$212=", "0.000"},    {"$220=", "3.000"},   {"$221=", "2700.000"},
      {"$222=", "0.000"},  {"$223=", "0.000"},    {"$224=", "480.000"}};
  const auto expect_listed = [](sim::Machine& m, const std::vector<std::pair<std::string, std::string>>& want,
                                const char* when) {
    for (const auto& w : want) EXPECT_EQ(last_starting(m, "echo:  " + w.first), "echo:  " + w.first + w.second) << when;
  };
  std::vector<uint8_t> unsaved, saved;
  {
    sim::Machine m(simtest::image(kImage));
    const size_t first = send(m, codes);
    for (size_t i = 0; i < codes.size(); ++i) EXPECT_TRUE(ok(m, first + i)) << codes[i];
    expect_listed(m, changed, "in force before M500");
    unsaved = m.eeprom();
    ASSERT_TRUE(ok(m, send(m, {"M500"})));
    saved = m.eeprom();
  }
  size_t written = 0;
  for (size_t i = 0; i < saved.size(); ++i)
    if (saved[i] != 0xFF) written = i + 1;
  EXPECT_LE(written, 4u + 4u * 43 + 2);  // header, 43 values, sum (docs/settings.md)
  {
    sim::Machine m(simtest::image(kImage));
    m.set_eeprom(unsaved);
    send(m, {"M503"});
    expect_listed(m, defaults, "after a power cycle without M500");
  }
  sim::Machine m(simtest::image(kImage));
  m.set_eeprom(saved);
  send(m, {"M503", "M301", "M83", "G10", "M400", "M114"});
  expect_listed(m, changed, "after a power cycle with M500");
  EXPECT_NE(last_starting(m, "echo: p:30.50 i:2.25 d:100.00"), "");
  const std::string m114 = last_starting(m, "X:");
  EXPECT_EQ(count_of(m114, 'E'), -4500) << m114;  // M207 S4.5 at 1000 steps/mm
  EXPECT_EQ(count_of(m114, 'Z'), 400) << m114;    // Z0.4
  send(m, {"G11", "M502", "M503", "M301"});
  expect_listed(m, defaults, "after M502");
  EXPECT_NE(last_starting(m, "echo: p:22.20 i:1.08 d:114.00"), "");
  // M204's greatest (its number in 1/10000 mm/s^2 in 32 bits) and a
  // fraction, as they are in force.
  send(m, {"M204 P214748 T0.25", "M503"});
  EXPECT_EQ(last_starting(m, "echo:  $210="), "echo:  $210=214748.000");
  EXPECT_EQ(last_starting(m, "echo:  $211="), "echo:  $211=0.250");
}

// Marlin's style (the default): `!`, `~` and `?` in a line are its text,
// a move runs through an M117 that says them. grbl's after `$200=0`: the
// same byte mid-move is a feed hold.
TEST(M1284, RealtimeBytesAreTextInMarlinsStyleAndCommandsInGrbls) {
  sim::Machine m(simtest::image(kImage));
  const size_t first = send(m, {"G1 X20 F1200", "M117 Done! ~ ?", "M400", "M114"});
  EXPECT_TRUE(ok(m, first + 1));
  EXPECT_EQ(last_starting(m, "echo:Done"), "echo:Done! ~ ?");
  EXPECT_EQ(count_of(last_starting(m, "X:"), 'X'), 20000);
  EXPECT_EQ(m.axis('X')->position, 20000);

  ASSERT_TRUE(ok(m, send(m, {"$200=0"})));
  m.serial().add_line("G1 X0 F1200");
  m.run([&] { return m.axis('X')->step_cycles.size() >= 25000; }, uint64_t(5 * m.f_cpu()));
  m.serial().send_raw("!");
  m.run([] { return false; }, uint64_t(0.5 * m.f_cpu()));
  const int64_t held = m.axis('X')->position;
  EXPECT_GT(held, 0);  // stopped short of the end
  m.run([] { return false; }, uint64_t(0.5 * m.f_cpu()));
  EXPECT_EQ(m.axis('X')->position, held);
  m.serial().send_raw("~");
  EXPECT_EQ(m.run_script(uint64_t(10 * m.f_cpu())), sim::RunEnd::done);
  EXPECT_EQ(m.axis('X')->position, 0);
}
