// Hard and soft limits on the m32 image (docs/homing.md): a switch closing
// mid-move stops every axis within one step period, measured in simavr
// cycles from the switch's edge to the last step edge of any axis; the
// alarm then refuses every motion command until M999; with the machine
// homed, a move beyond the travel is refused before it starts and nothing
// moves.
#include <gtest/gtest.h>

#include <sim_avr.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "board_info.h"
#include "endstops.h"
#include "sim_fixture.h"
#include "thermal_plant.h"

namespace {

// An answer as "ok" or "error: <reason>" (grbl's number aside).
std::string said(const sim::Response& r) { return sim::SerialHost::is_ok(r.answer) ? r.answer : "error: " + r.reason; }

constexpr const char* kAlarmRefusal = "error: alarm (hard limit, failed homing, reset in motion): M999 or $X unlocks";
// grbl's alarm 1 (hard limit) and its reason (reply::alarm()).
constexpr const char* kAlarmLine = "ALARM:1";
constexpr const char* kAlarmReason = "[MSG:hard limit: endstop hit, axes stopped, position lost]";

uint64_t last_step(const sim::Machine& m) {
  uint64_t last = 0;
  for (const sim::AxisTrace& a : m.axes())
    if (!a.step_cycles.empty()) last = std::max(last, a.step_cycles.back());
  return last;
}

// The step period of `a` at `cycle`: its last interval before it (the
// dominant axis's at cruise or on the ramp).
uint64_t period_at(const sim::AxisTrace& a, uint64_t cycle) {
  const auto it = std::upper_bound(a.step_cycles.begin(), a.step_cycles.end(), cycle);
  EXPECT_GE(it - a.step_cycles.begin(), 2) << "fewer than two steps before the switch";
  return *(it - 1) - *(it - 2);
}

int count(const std::vector<std::string>& v, const std::string& s) { return int(std::count(v.begin(), v.end(), s)); }

}  // namespace

TEST(Limits, ASwitchReachedMidMoveStopsEveryAxisWithinOneStepPeriod) {
  // X's switch at -3000 steps, the machine unhomed at 0: moves toward it at
  // several feeds (one axis and three together), clean or bouncing.
  struct Case {
    std::string move;
    const char* dominant;
  };
  const Case cases[] = {{"G1 X-10 F300", "X"},  {"G1 X-10 F1200", "X"}, {"G1 X-10 F2400", "X"},
                        {"G1 X-6 Y9 Z1 F2400", "Y"}, {"G1 X-8 Y-3 E2 F900", "X"}};
  for (const Case& c : cases) {
    for (const double bounce : {0.0, 100.0, 400.0}) {
      sim::Machine m(simtest::image("m32-direct"));
      sim::Endstops switches(m, sim::EndstopParams{bounce, 6});
      switches.set_position('X', -3000);
      switches.set_position('Y', -100000);
      for (const char* l : {c.move.c_str(), "WAIT", "G1 X-20 F600", "MOVE X-100", "G28", "M999", "G1 X0 F1200"})
        m.serial().add_line(l);
      const std::string where = c.move + ", bounce " + std::to_string(int(bounce)) + " us";
      ASSERT_EQ(m.run_script(uint64_t(20 * m.f_cpu())), sim::RunEnd::done) << where;
      // The switch's first closing edge once X moves (it was set up open).
      ASSERT_FALSE(m.axis('X')->step_cycles.empty()) << where;
      uint64_t edge = 0;
      for (const sim::PinEdge& e : switches.edges('X'))
        if (!e.level && e.cycle > m.axis('X')->step_cycles.front()) {
          edge = e.cycle;
          break;
        }
      ASSERT_NE(edge, 0u) << where;
      // The stop: the last step edge of any axis before the recovery move.
      const uint64_t unlock = m.serial().responses().at(5).answer_cycle;
      uint64_t last = 0;
      for (const sim::AxisTrace& a : m.axes())
        for (uint64_t t : a.step_cycles)
          if (t < unlock) last = std::max(last, t);
      const uint64_t period = period_at(*m.axis(c.dominant[0]), edge);
      EXPECT_LE(last, edge + period) << where << ": last step " << (int64_t(last) - int64_t(edge))
                                     << " cycles after the switch, period " << period;
      // The alarm: said once; the next motion commands refused, G28 too.
      EXPECT_EQ(count(m.serial().messages(), kAlarmLine), 1) << where;
      EXPECT_EQ(count(m.serial().messages(), kAlarmReason), 1) << where;
      const auto& r = m.serial().responses();
      EXPECT_EQ(said(r.at(0)), "ok") << where;  // accepted before the switch closed
      EXPECT_EQ(said(r.at(1)), "ok") << where;  // the motion ended (stopped)
      EXPECT_EQ(said(r.at(2)), kAlarmRefusal) << where;
      EXPECT_EQ(said(r.at(3)), kAlarmRefusal) << where;
      EXPECT_EQ(said(r.at(4)), kAlarmRefusal) << where;
      EXPECT_EQ(said(r.at(5)), "ok") << where;
      EXPECT_EQ(said(r.at(6)), "ok") << where;
      // Unlocked, the move away from the switch runs (to X0 as the planner
      // has it: the position was lost, so not 0 on the pins).
      EXPECT_GT(m.axis('X')->step_cycles.back(), unlock) << where;
      EXPECT_GT(m.axis('X')->position, -3000 + 1) << where;
    }
  }
}

TEST(Limits, ASwitchClosedAtAnyMomentStopsWithinOneStepPeriod) {
  // The switch pin driven closed at random moments of a move toward it
  // (the ramp, the cruise), as a switch hit by something else would: the
  // step interrupt reads it at the next step and makes no step after it.
  std::mt19937 rng(9);
  int cases = 0;
  for (const char* move : {"G1 X-30 F2400", "G1 X-20 Y-20 Z-5 F1800"}) {
    for (int k = 0; k < 12; ++k) {
      sim::Machine m(simtest::image("m32-direct"));
      m.serial().add_line(move);
      m.serial().add_line("WAIT");
      m.serial().add_line("G1 X5 F600");
      ASSERT_EQ(m.run([&m] { return !m.axis('X')->step_cycles.empty(); }, uint64_t(2 * m.f_cpu())),
                sim::RunEnd::done);
      const uint64_t start = m.axis('X')->step_cycles.front();
      const uint64_t press = start + std::uniform_int_distribution<uint64_t>(1000, 6000000)(rng);
      ASSERT_EQ(m.run([&m, press] { return m.cycles() >= press; }, uint64_t(2 * m.f_cpu())), sim::RunEnd::done);
      ASSERT_LT(m.axis('X')->position, 0);
      m.hold_input('D', 2, false);  // X's min switch, closed
      ASSERT_EQ(m.run_script(uint64_t(10 * m.f_cpu())), sim::RunEnd::done);
      const uint64_t period = period_at(*m.axis('X'), press);
      const uint64_t last = last_step(m);
      EXPECT_LE(last, press + period) << move << ", pressed " << (press - start) << " cycles in";
      EXPECT_EQ(said(m.serial().responses().at(2)), kAlarmRefusal);
      EXPECT_EQ(count(m.serial().messages(), kAlarmLine), 1);
      EXPECT_EQ(count(m.serial().messages(), kAlarmReason), 1);
      ++cases;
    }
  }
  EXPECT_EQ(cases, 24);
}

TEST(Limits, AMoveBeyondTheTravelOfAHomedAxisIsRefusedAndNothingMoves) {
  sim::Machine m(simtest::image("m32-direct"));
  sim::Endstops switches(m);  // every switch at 0
  const std::vector<std::string> lines = {
      "G1 X-1 F600",  // unhomed, on the switch: stops at once (alarm)
      "WAIT", "M999", "G28", "POS", "G1 X-0.001 F1200", "G1 X5 Z3 F2400", "POS", "G1 X5.001", "G1 Z3.001",
      "MOVE X1", "MOVE Y-1", "G91", "G1 Y-0.001", "G90", "M114", "POS", "MOVE X-5000", "POS"};
  for (const std::string& l : lines) m.serial().add_line(l);
  // The travel (firmware/axes/endstops.h HomingAxis::travel, 16 bytes a
  // switch, the last field) made short for the test: X and Y 5 mm, Z 3 mm.
  const uint16_t settings = sim::read_data_symbol(m.elf_path(), "_ZN6limits8settingsE");
  ASSERT_EQ(m.run([&m] { return m.serial().banner_seen(); }, 16000000), sim::RunEnd::done);
  for (int k = 0; k < 3; ++k) {
    const uint32_t travel = k == 2 ? 3000 : 5000;
    std::memcpy(&m.avr()->data[settings + 16 * k + 12], &travel, 4);
  }
  ASSERT_EQ(m.run_script(uint64_t(60 * m.f_cpu())), sim::RunEnd::done);
  const auto& r = m.serial().responses();
  ASSERT_EQ(r.size(), lines.size());
  const std::string soft = "error: move beyond the soft limits";
  EXPECT_EQ(said(r[0]), "ok");
  for (size_t i : {1, 2, 3, 4, 6, 7, 12, 14, 15, 16, 17, 18}) EXPECT_EQ(said(r[i]), "ok") << lines[i];
  for (size_t i : {5, 8, 9, 10, 11, 13}) EXPECT_EQ(said(r[i]), soft) << lines[i];
  const std::vector<std::string> msgs = m.serial().messages();
  // The refused lines changed nothing: the program position, the count and
  // the pins stay where G1 X5 Z3 left them.
  std::vector<std::string> pos;
  for (const std::string& s : msgs)
    if (s.rfind("pos ", 0) == 0) pos.push_back(s);
  ASSERT_EQ(pos.size(), 4u);
  EXPECT_EQ(pos[0], "pos X:0 Y:0 Z:0 E:0");
  EXPECT_EQ(pos[1], "pos X:5000 Y:0 Z:3000 E:0");
  EXPECT_EQ(pos[2], pos[1]);
  EXPECT_EQ(pos[3], "pos X:0 Y:0 Z:3000 E:0");
  bool m114 = false;
  for (const std::string& s : msgs) m114 |= s.rfind("X:5.0000 Y:0.0000 Z:3.0000 E:0.0000", 0) == 0;
  EXPECT_TRUE(m114);
  // On the pins: pull_off (1000) above each switch, plus the moves.
  EXPECT_EQ(m.axis('X')->position, 1000);
  EXPECT_EQ(m.axis('Y')->position, 1000);
  EXPECT_EQ(m.axis('Z')->position, 4000);
}

// The printer: a hard limit while the hot end heats turns the heater off at
// once (the main loop's next pass, not its next 125 ms sample) and says so;
// a new target is refused in the alarm; once M999 has unlocked it, a target
// heats again.
TEST(Limits, AnAlarmTurnsTheHeaterOffUntilUnlocked) {
  sim::Machine m(simtest::image("m32"));
  sim::ThermalPlant plant(m, sim::ThermalParams());
  sim::Endstops switches(m);
  switches.set_position('X', -3000);
  // G4 S1 (Marlin: seconds): a second for the heater to start (its PID samples every 125 ms).
  for (const char* l : {"M104 S200", "G4 S1", "G1 X-10 F1200", "M400", "M104 S200", "M999", "M104 S200", "G4 S1"})
    m.serial().add_line(l);
  ASSERT_EQ(m.run_script(uint64_t(20 * m.f_cpu())), sim::RunEnd::done);
  const auto& r_all = m.serial().responses();
  ASSERT_EQ(r_all.size(), 8u);
  const sim::Response* r = &r_all[1];  // r[k]: the k-th line after the dwell
  EXPECT_EQ(said(r_all[0]), "ok");
  EXPECT_EQ(said(r[3]), kAlarmRefusal);  // a target in the alarm
  EXPECT_EQ(said(r[4]), "ok");           // M999
  EXPECT_EQ(said(r[5]), "ok");           // heats again
  EXPECT_EQ(count(m.serial().messages(), "echo:heater off: alarm"), 1);
  // The heater pin: high (full power from 25 C) until the switch, low from
  // within one sample period after it until the unlocked target.
  const uint64_t trip = last_step(m) < r[4].answer_cycle ? m.axis('X')->step_cycles.back() : 0;
  ASSERT_GT(trip, 0u);
  // The heater PWM (488 Hz) runs until the switch; `off` is the falling edge
  // after which the pin stays low until the unlocked M104.
  const auto& pin = plant.heater_pin();
  uint64_t last_rise_before_trip = 0, off = 0, on_again = 0;
  for (const sim::PinEdge& e : pin) {
    if (e.cycle <= trip && e.level) last_rise_before_trip = e.cycle;
    if (e.cycle > trip && e.cycle < r[5].sent_cycle) {
      if (!e.level) off = e.cycle;
      else off = 0;  // high again in the alarm: no off yet
    }
    if (e.cycle > r[5].sent_cycle && e.level && !on_again) on_again = e.cycle;
  }
  EXPECT_GT(last_rise_before_trip, 0u);  // heating when the switch closed
  ASSERT_GT(off, trip);
  EXPECT_LE(off - trip, uint64_t(m.f_cpu() / 1000));  // 1 ms
  EXPECT_GT(on_again, r[5].sent_cycle);
  std::printf("heater off %.1f ms after the hard limit, on again %.1f ms after the unlocked M104\n",
              double(off - trip) / m.f_cpu() * 1000, double(on_again - r[5].sent_cycle) / m.f_cpu() * 1000);
}
