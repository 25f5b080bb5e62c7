// G28 on the m32 image against the simulator's endstop switches
// (sim/endstops.h, docs/homing.md): the switch found within one step of
// where it is, from either side, clean or bouncing, over several positions
// and speeds; every axis in order; what a homed axis's position then means
// on the pins; a switch that never closes or never opens.
#include <gtest/gtest.h>

#include <sim_avr.h>

#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "board_info.h"
#include "endstops.h"
#include "sim_fixture.h"

namespace {

// The firmware's settings struct (firmware/axes/endstops.h HomingAxis, one
// per switch: X Y Z), written in RAM before G28 to sweep the speeds.
struct Homing {
  uint16_t seek_rate, locate_rate, back_off, pull_off;
  int32_t home;
  uint32_t travel;
};
static_assert(sizeof(Homing) == 16, "HomingAxis on the AVR");

class Printer {
 public:
  explicit Printer(double bounce_us = 0)
      : m_(simtest::image("m32-direct")), switches_(m_, sim::EndstopParams{bounce_us, 6}),
        settings_(sim::read_data_symbol(m_.elf_path(), "_ZN6limits8settingsE")) {}

  sim::Machine& m() { return m_; }
  sim::Endstops& switches() { return switches_; }
  Homing get(int k) {
    Homing h;
    std::memcpy(&h, &m_.avr()->data[settings_ + 16 * k], sizeof h);
    return h;
  }
  void set(int k, const Homing& h) { std::memcpy(&m_.avr()->data[settings_ + 16 * k], &h, sizeof h); }
  // Runs `lines`; `setup` runs once the banner is out (the settings are
  // .data, copied at start-up), before the first line arrives.
  void send(const std::vector<std::string>& lines, double seconds, const std::function<void()>& setup = nullptr) {
    for (const std::string& l : lines) m_.serial().add_line(l);
    ASSERT_EQ(m_.run([this] { return m_.serial().banner_seen(); }, 16000000), sim::RunEnd::done);
    if (setup) setup();
    ASSERT_EQ(m_.run_script(uint64_t(seconds * m_.f_cpu())), sim::RunEnd::done);
  }
  int64_t at(char axis) { return m_.axis(axis)->position; }
  // The answer as "ok" or "error: <reason>" (grbl's number aside).
  std::string answer(size_t i) {
    const sim::Response& r = m_.serial().responses().at(i);
    return sim::SerialHost::is_ok(r.answer) ? r.answer : "error: " + r.reason;
  }
  size_t answers() { return m_.serial().responses().size(); }

 private:
  sim::Machine m_;
  sim::Endstops switches_;
  uint16_t settings_;
};

// The POS report's steps of axis `a` in "pos X:.. Y:.. Z:.. E:..".
long reported(sim::Machine& m, char a) {
  const std::vector<std::string> msgs = m.serial().messages();
  for (auto it = msgs.rbegin(); it != msgs.rend(); ++it) {
    if (it->rfind("pos ", 0) != 0) continue;
    const size_t at = it->find(std::string(" ") + a + ":");
    if (at != std::string::npos) return std::strtol(it->c_str() + at + 3, nullptr, 10);
  }
  ADD_FAILURE() << "no POS report";
  return 0;
}


}  // namespace

TEST(Homing, FindsTheSwitchWithinOneStepFromEitherSideCleanOrBouncing) {
  // Switch positions below the start (open there: the seek finds it) and at
  // or above it within the back-off (closed at the start: backed off first);
  // seek and locate speeds and bounce swept. After G28 X0 the axis is
  // pull_off steps off the switch and reported at home (0): the trip point,
  // where the pins say the axis was when the switch stopped it, is within
  // one step of the switch.
  struct Speeds {
    uint16_t seek, locate;
  };
  const Speeds speeds[] = {{25000, 1000}, {40000, 4000}, {8000, 250}};
  const int64_t positions[] = {-2345, -301, -1, 0, 7, 640};
  const double bounces[] = {0, 150, 600};
  int runs = 0;
  for (const Speeds& sp : speeds) {
    for (const int64_t s : positions) {
      for (const double bounce : bounces) {
        // The locate's step period must outlast the bounce for one step.
        if (bounce * 1e-6 * sp.locate >= 1) continue;
        Printer p(bounce);
        p.switches().set_position('X', s);
        p.send({"G28 X0", "POS"}, 20, [&] {
          Homing h = p.get(0);
          h.seek_rate = sp.seek;
          h.locate_rate = sp.locate;
          h.back_off = 700;
          h.pull_off = 450;
          p.set(0, h);
        });
        const std::string where = "switch at " + std::to_string(s) + ", seek " + std::to_string(sp.seek) +
                                  ", locate " + std::to_string(sp.locate) + ", bounce " + std::to_string(bounce) + " us";
        ASSERT_EQ(p.answer(0), "ok") << where;
        EXPECT_EQ(reported(p.m(), 'X'), 0) << where;
        const int64_t trip = p.at('X') - 450;
        EXPECT_LE(std::llabs(trip - s), 1) << where << ": stopped at " << trip;
        EXPECT_FALSE(p.switches().closed('X')) << where;
        // The other axes never moved.
        EXPECT_EQ(p.at('Y'), 0);
        EXPECT_EQ(p.at('E'), 0);
        ++runs;
      }
    }
  }
  EXPECT_EQ(runs, 48);
}

// The printer image (Marlin's protocol, G-code only) homes with the same
// service: switches 3 mm below the start, G28 ends every axis 1 mm off its
// switch and calls that 0 (M114's counts and program positions).
TEST(Homing, ThePrinterHomesInGcode) {
  sim::Machine m(simtest::image("m32"));
  sim::Endstops switches(m);
  for (char a : {'X', 'Y', 'Z'}) switches.set_position(a, -3000);
  for (const char* l : {"G28", "M114"}) m.serial().add_line(l);
  ASSERT_EQ(m.run_script(uint64_t(30 * m.f_cpu())), sim::RunEnd::done);
  ASSERT_EQ(m.serial().responses().size(), 2u);
  EXPECT_EQ(m.serial().responses()[0].answer, "ok");
  // Marlin's keep-alive while G28 runs, then the report.
  std::vector<std::string> reports;
  for (const std::string& l : m.serial().messages())
    if (l != "busy: processing") reports.push_back(l);
  EXPECT_EQ(reports, std::vector<std::string>{"X:0.0000 Y:0.0000 Z:0.0000 E:0.0000 Count X:0 Y:0 Z:0 E:0"});
  for (char a : {'X', 'Y', 'Z'}) EXPECT_EQ(m.axis(a)->position, -2000) << a;  // 1 mm off the switch
}

// grbl's $H on the m32-direct: G28 for every axis with an endstop, answered
// once homed; on the Uno (no endstops) it is not in the image.
TEST(Homing, GrblsDollarHHomesAndIsRefusedWithoutEndstops) {
  sim::Machine m(simtest::image("m32-direct"));
  sim::Endstops switches(m);
  for (char a : {'X', 'Y', 'Z'}) switches.set_position(a, -2500);
  for (const char* l : {"$H", "POS"}) m.serial().add_line(l);
  ASSERT_EQ(m.run_script(uint64_t(30 * m.f_cpu())), sim::RunEnd::done);
  ASSERT_EQ(m.serial().responses().size(), 2u);
  EXPECT_EQ(m.serial().responses()[0].answer, "ok");
  for (char a : {'X', 'Y', 'Z'}) EXPECT_EQ(m.axis(a)->position, -1500) << a;  // 1 mm off the switch
  EXPECT_EQ(m.serial().messages().back(), "pos X:0 Y:0 Z:0 E:0");
  auto uno = simtest::run("uno", {"$H"});
  ASSERT_EQ(uno->serial().responses().size(), 1u);
  EXPECT_EQ(uno->serial().responses()[0].answer, "error:3");
}

TEST(Homing, EveryAxisInOrderThenPositionsMeanTheSameOnThePins) {
  Printer p(200);
  p.switches().set_position('X', -5000);
  p.switches().set_position('Y', 300);  // closed at the start
  p.switches().set_position('Z', -1234);
  p.send({"G1 E2 F600", "G28", "POS", "G1 X12.5 Y3 Z0.25 F2400", "POS", "M114"}, 60);
  for (size_t i = 0; i < p.answers(); ++i) EXPECT_EQ(p.answer(i), "ok") << i;
  const Homing x = p.get(0), y = p.get(1), z = p.get(2);
  // Each axis pull_off above its switch's trip point when homed, within a step.
  const sim::AxisTrace& X = *p.m().axis('X');
  const sim::AxisTrace& Z = *p.m().axis('Z');
  EXPECT_LE(std::llabs(p.at('X') - 12500 - x.pull_off - x.home - (-5000)), 1);
  EXPECT_LE(std::llabs(p.at('Y') - 3000 - y.pull_off - y.home - 300), 1);
  EXPECT_LE(std::llabs(p.at('Z') - 250 - z.pull_off - z.home - (-1234)), 1);
  EXPECT_EQ(p.at('E'), 2000);  // E is never homed
  EXPECT_EQ(reported(p.m(), 'X'), 12500);
  EXPECT_EQ(reported(p.m(), 'Z'), 250);
  const std::vector<std::string> msgs = p.m().serial().messages();
  EXPECT_EQ(msgs.back().substr(0, 36), "X:12.5000 Y:3.0000 Z:0.2500 E:2.0000");
  // X homed before Y and Y before Z: their last homing steps in that order.
  const sim::AxisTrace& Y = *p.m().axis('Y');
  ASSERT_GT(X.step_cycles.size(), 12500u);
  const uint64_t x_homed = X.step_cycles[X.step_cycles.size() - 12501];
  const uint64_t y_homed = Y.step_cycles[Y.step_cycles.size() - 3001];
  const uint64_t z_homed = Z.step_cycles[Z.step_cycles.size() - 251];
  EXPECT_LT(x_homed, Y.step_cycles.front());
  EXPECT_LT(y_homed, Z.step_cycles.front());
  EXPECT_LT(z_homed, p.m().serial().responses().at(1).answer_cycle);
}

TEST(Homing, ASwitchThatNeverClosesRaisesTheAlarm) {
  Printer p;
  p.switches().set_position('X', -100000000);  // far beyond the travel
  p.send({"G28 X0", "G1 X1 F600", "MOVE X100", "G28", "M999", "G1 X-1 F600", "POS"}, 20, [&] {
    Homing h = p.get(0);
    h.travel = 6000;  // the seek looks 9000 steps
    p.set(0, h);
  });
  EXPECT_EQ(p.answer(0), "error: homing: endstop not found");
  // The whole seek, then the error.
  EXPECT_EQ(sim::position_at(*p.m().axis('X'), p.m().serial().responses().at(0).answer_cycle), -9000);
  EXPECT_EQ(p.answer(1), "error: alarm (hard limit, failed homing, reset in motion): M999 or $X unlocks");
  EXPECT_EQ(p.answer(2), "error: alarm (hard limit, failed homing, reset in motion): M999 or $X unlocks");
  EXPECT_EQ(p.answer(3), "error: alarm (hard limit, failed homing, reset in motion): M999 or $X unlocks");
  EXPECT_EQ(p.answer(4), "ok");
  // Unhomed: no soft limits. The seek ran whole, so the planner still
  // counts what the pins did, and X-1 is reached from there.
  EXPECT_EQ(p.answer(5), "ok");
  EXPECT_EQ(p.at('X'), -1000);
  EXPECT_EQ(reported(p.m(), 'X'), -1000);
}

TEST(Homing, ASwitchThatStaysClosedFailsAndAnAxisWithoutOneIsRefused) {
  Printer p;
  p.switches().set_position('Y', 50000);  // closed far beyond the back-off
  p.send({"G28 E0", "G28 Y0", "POS"}, 20);
  EXPECT_EQ(p.answer(0), "error: G28 homes only axes with an endstop");
  EXPECT_EQ(p.answer(1), "error: homing: endstop stays closed");
  EXPECT_EQ(p.at('E'), 0);
  EXPECT_EQ(p.at('X'), 0);
  EXPECT_TRUE(p.switches().closed('Y'));
}

TEST(Homing, UnhomedTheEndstopsDoNotStopAMoveAwayFromThem) {
  // The machine starts on its switches (the default world, all at 0): a move
  // away from them runs, one toward them stops at once.
  Printer p;
  p.send({"G1 X3 Y2 Z1 F1200", "G1 X0 F1200", "G1 X-1", "M999", "POS"}, 20);
  EXPECT_EQ(p.answer(0), "ok");
  EXPECT_EQ(p.at('Y'), 2000);
  EXPECT_EQ(p.at('Z'), 1000);
  EXPECT_EQ(p.at('X'), 0);  // back on its switch (closed at the last step, after it nothing)
}
