// grbl's realtime bytes on the real images that take them (firmware/apps/
// cnc/realtime.h): the m32-cnc (X at 1000 steps/mm, 500 mm/s^2: 500000
// steps/s^2, board defaults, on the 16 MHz step timer), the uno-grbl (the
// motor shield's X at 25 steps/mm, 800 steps/s^2, its coils stepped by the
// same timer) and the m1284 (the m32-cnc's axes; Marlin's style by default,
// so its EEPROM holds `$200=0` from the start): `?` mid-move reports where the motors are, `!` slows the move
// to rest at its acceleration and `~` finishes it exactly, Ctrl-X stops the
// steps at once and restarts the chip.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "sim_fixture.h"

namespace {

constexpr double kTick = 16000000.0;

// An image, its X axis and a move of it at a feed.
struct Image {
  const char* name;
  double steps_per_mm;
  double accel;                                               // X's, steps/s^2
  int feed;                                                   // mm/min
  const char* zeros;                                          // the other axes in an idle status
  size_t at[3];                                               // steps at which the tests act mid-move
  double software_late;                                       // cycles a software-pulsed step may come late
                                                              // (docs/step-engine.md)
  bool marlin_default;                                        // set to grbl's style by `$200=0` first
  double rate() const { return feed / 60.0 * steps_per_mm; }  // steps/s
};
const Image kImages[] = {
    {"m32-cnc", 1000, 500000, 1200, ",0.000,0.000,0.000", {300, 6000, 25000}, 48, false},
    {"uno-grbl", 25, 800, 600, ",0.000,0.000", {20, 300, 600}, 48, false},
    {"m1284", 1000, 500000, 1200, ",0.000,0.000,0.000", {300, 6000, 25000}, 48, true},
};

// The EEPROM of an image once `$200=0` has been stored in it.
std::vector<uint8_t> grbl_style_eeprom(const char* name) {
  sim::Machine m(simtest::image(name));
  m.serial().add_line("$200=0");
  EXPECT_EQ(m.run_script(uint64_t(kTick)), sim::RunEnd::done);
  return m.eeprom();
}

// A fresh machine of the image, in grbl's style from its banner on.
std::unique_ptr<sim::Machine> machine(const Image& im) {
  std::unique_ptr<sim::Machine> m(new sim::Machine(simtest::image(im.name)));
  if (im.marlin_default) m->set_eeprom(grbl_style_eeprom(im.name));
  return m;
}

// Runs until X has made `steps` steps.
void run_to_step(sim::Machine& m, size_t steps) {
  m.run([&] { return m.axis('X')->step_cycles.size() >= steps; }, uint64_t(10 * kTick));
  ASSERT_GE(m.axis('X')->step_cycles.size(), steps);
}

// The last line the firmware printed that starts with '<', once one has come.
std::string status_after(sim::Machine& m, size_t seen) {
  m.run(
      [&] {
        const auto& r = m.serial().received();
        for (size_t i = seen; i < r.size(); ++i)
          if (!r[i].empty() && r[i][0] == '<') return true;
        return false;
      },
      uint64_t(0.1 * kTick));
  const auto& r = m.serial().received();
  for (size_t i = seen; i < r.size(); ++i)
    if (!r[i].empty() && r[i][0] == '<') return r[i];
  return "";
}

// Sends `line` raw and returns the first answer line after it ("ok" or
// "error:N"; "" if none came within a second).
std::string answer_to(sim::Machine& m, const std::string& line) {
  const size_t seen = m.serial().received().size();
  m.serial().send_raw(line + "\n");
  auto answer = [&]() -> std::string {
    const auto& r = m.serial().received();
    for (size_t i = seen; i < r.size(); ++i)
      if (r[i] == "ok" || r[i].rfind("error:", 0) == 0) return r[i];
    return "";
  };
  m.run([&] { return !answer().empty(); }, uint64_t(kTick));
  return answer();
}

// MPos's first number, in steps.
long mpos_x_steps(const std::string& status, double steps_per_mm) {
  const size_t at = status.find("MPos:");
  if (at == std::string::npos) return -1;
  return std::lround(std::stod(status.substr(at + 5)) * steps_per_mm);
}

TEST(Realtime, StatusMidMoveIsWhereThePinsAre) {
  for (const Image& im : kImages) {
    const long total = std::lround(20 * im.steps_per_mm);
    for (size_t at : {im.at[0], im.at[1], size_t(total) - im.at[0]}) {
      const auto owned = machine(im);
      sim::Machine& m = *owned;
      m.serial().add_line("G1 X20 F" + std::to_string(im.feed));
      run_to_step(m, at);
      const size_t before = m.axis('X')->step_cycles.size(), seen = m.serial().received().size();
      m.serial().send_raw("?");
      const std::string s = status_after(m, seen);
      const size_t after = m.axis('X')->step_cycles.size();
      ASSERT_FALSE(s.empty());
      EXPECT_EQ(s.rfind("<Run|MPos:", 0), 0u) << s;
      EXPECT_NE(s.find("|FS:" + std::to_string(im.feed) + ",0>"), std::string::npos) << s;
      const long x = mpos_x_steps(s, im.steps_per_mm);
      EXPECT_GE(x, long(before)) << im.name << " " << s;
      EXPECT_LE(x, long(after)) << im.name << " " << s;
      printf("Realtime %s: '%s' with %zu..%zu steps on the pins\n", im.name, s.c_str(), before, after);
      ASSERT_EQ(m.run_script(uint64_t(10 * kTick)), sim::RunEnd::done);
      EXPECT_EQ(m.axis('X')->steps(), total);
      const size_t idle_seen = m.serial().received().size();
      m.serial().send_raw("?");
      EXPECT_EQ(status_after(m, idle_seen), std::string("<Idle|MPos:20.000") + im.zeros + "|FS:0,0>");
    }
  }
}

// Every step of a stretch against constant acceleration `a` (negative:
// slowing) from speed v0 at the step before it (cycle t0, position 0),
// after `cruise` steps at v0: the worst distance from the ideal motion, in
// steps.
double worst_from_ideal(const std::vector<uint64_t>& st, size_t first, size_t count, uint64_t t0, double v0, double a,
                        double cruise = 0) {
  double worst = 0;
  const double tc = cruise / std::max(v0, 1.0);
  for (size_t k = 0; k < count; ++k) {
    const double t = double(st[first + k] - t0) / kTick, u = std::max(0.0, t - tc);
    const double x = v0 * std::min(t, tc) + v0 * u + a * u * u / 2;
    worst = std::max(worst, std::fabs(double(k + 1) - x));
  }
  return worst;
}

TEST(Realtime, HoldSlowsToRestAndResumeEndsExactly) {
  for (const Image& im : kImages) {
    const double a = im.accel, cruise = kTick / im.rate();  // cycles a step
    const size_t total = size_t(std::lround(30 * im.steps_per_mm));
    // Steps from the cruise to rest: v^2 / 2a, and a margin.
    const size_t braking = size_t(im.rate() * im.rate() / (2 * a)) + 2;
    for (size_t at : im.at) {
      const auto owned = machine(im);
      sim::Machine& m = *owned;
      m.serial().add_line("G1 X30 F" + std::to_string(im.feed));
      run_to_step(m, at);
      const uint64_t asked = m.cycles();
      m.serial().send_raw("!");
      const auto& st = m.axis('X')->step_cycles;
      // At rest: no step for ten cruise intervals (and 100 ms).
      const uint64_t quiet = std::max(uint64_t(0.1 * kTick), uint64_t(10 * cruise));
      m.run([&] { return m.cycles() > st.back() + quiet; }, uint64_t(5 * kTick));
      const size_t stopped = st.size();
      ASSERT_LT(stopped, total);
      const size_t seen = m.serial().received().size();
      m.serial().send_raw("?");
      const std::string held = status_after(m, seen);
      EXPECT_EQ(held.rfind("<Hold:0|MPos:", 0), 0u) << held;
      EXPECT_EQ(mpos_x_steps(held, im.steps_per_mm), long(stopped)) << held;

      // The stop: n = floor(v^2 / 2a) + 1 events from the speed reached v: the
      // part of an event beyond v^2 / 2a at v, then constant deceleration to
      // rest; every step within half a step of it, anchored at the step
      // before it.
      const double v = stopped < braking + 3 ? 0 : kTick / double(st[stopped - braking] - st[stopped - braking - 1]);
      if (v > 0.95 * im.rate()) {
        const size_t events = size_t(v * v / (2 * a)) + 1, first = stopped - events;
        const double worst =
            worst_from_ideal(st, first, events, st[first - 1], v, -a, double(events) - v * v / (2 * a));
        EXPECT_LE(worst, 0.5) << im.name << " hold at " << at;
        printf(
            "Realtime %s: hold at step %zu (asked at %.1f ms): %zu steps to "
            "rest from %.0f steps/s, %.3f steps "
            "from constant deceleration, %.1f ms after the byte\n",
            im.name, at, asked / kTick * 1000, events, v, worst, (st[stopped - 1] - asked) / kTick * 1000);
      }
      // Never faster than the cruise, from the byte to rest.
      for (size_t k = at + 1; k < stopped; ++k) EXPECT_GE(double(st[k] - st[k - 1]), cruise - im.software_late) << k;

      m.serial().send_raw("~");
      ASSERT_EQ(m.run_script(uint64_t(10 * kTick)), sim::RunEnd::done);
      EXPECT_EQ(m.axis('X')->steps(), double(total));
      // From rest again: the first steps on constant acceleration.
      const size_t ramp = std::min<size_t>(300, braking - 2);
      const uint64_t t0 = st[stopped] - uint64_t(std::sqrt(2 / a) * kTick);
      EXPECT_LE(worst_from_ideal(st, stopped, ramp, t0, 0, a), 0.5) << im.name << " resume after " << at;
      for (const std::string& e : m.serial().errors()) ADD_FAILURE() << e;
    }
  }
}

TEST(Realtime, CtrlXStopsTheStepsAtOnceAndRestarts) {
  for (const Image& im : kImages) {
    const auto owned = machine(im);
    sim::Machine& m = *owned;
    m.serial().add_line("G1 X20 Y10 F" + std::to_string(im.feed));
    run_to_step(m, im.at[1]);
    const std::string banner = m.serial().banner();
    m.serial().send_raw("\x18");
    const size_t banners = m.serial().received().size();
    m.run([&] { return m.serial().received().size() > banners; }, uint64_t(0.1 * kTick));
    // simavr's UART raises the receive interrupt one frame (10 bits) after
    // the byte is handed to it: the moment the stop bit would be in.
    const uint64_t in = m.serial().last_byte_cycle() + uint64_t(10 * kTick / 115200);
    ASSERT_GT(m.serial().received().size(), banners) << "no banner after the soft reset";
    EXPECT_EQ(m.serial().received().back(), banner);
    for (char a : {'X', 'Y'}) {
      const auto& st = m.axis(a)->step_cycles;
      ASSERT_FALSE(st.empty());
      // The receive interrupt runs within a few hundred cycles of the stop bit.
      EXPECT_LT(st.back(), in + 400) << a;
      printf(
          "Realtime %s: Ctrl-X: last %c step %lld cycles after the byte was "
          "in; banner again after %.1f ms\n",
          im.name, a, (long long)(st.back()) - (long long)in,
          (m.serial().received_cycles().back() - in) / kTick * 1000);
    }
    // The position is lost: after the banner's second line, grbl's alarm;
    // motion is refused until $X. (The host's M400 in flight at the reset
    // is never answered: the lines go raw.)
    const size_t seen = m.serial().received().size();
    m.run([&] { return m.serial().received().size() >= seen + 4; }, uint64_t(0.1 * kTick));
    const auto& got = m.serial().received();
    ASSERT_GE(got.size(), seen + 4);
    EXPECT_EQ(got[seen], got[1]);  // [MSG:avrmotion ...]
    EXPECT_EQ(got[seen + 1], "ALARM:3");
    EXPECT_EQ(got[seen + 2], "[MSG:reset while in motion, position lost]");
    EXPECT_EQ(got[seen + 3], "[MSG:'$X' to unlock]");
    const double x = m.axis('X')->steps();
    const size_t before_status = m.serial().received().size();
    m.serial().send_raw("?");
    EXPECT_EQ(status_after(m, before_status).rfind("<Alarm|MPos:", 0), 0u);
    EXPECT_EQ(answer_to(m, "G1 X30 F1200"), "error:9");
    EXPECT_EQ(answer_to(m, "$X"), "ok");
    EXPECT_EQ(answer_to(m, "G91"), "ok");
    EXPECT_EQ(answer_to(m, "G1 X1 F" + std::to_string(im.feed)), "ok");
    EXPECT_EQ(answer_to(m, "M400"), "ok");
    EXPECT_EQ(m.axis('X')->steps(),
              x + im.steps_per_mm);  // only the move after $X
  }
}

TEST(Realtime, CtrlXAtRestRestartsWithoutAnAlarm) {
  for (const Image& im : kImages) {
    const auto owned = machine(im);
    sim::Machine& m = *owned;
    ASSERT_EQ(m.run([&] { return m.serial().banner_seen(); }, uint64_t(kTick)), sim::RunEnd::done);
    const size_t banner = m.serial().received().size();
    m.serial().send_raw("\x18");
    m.run([&] { return m.serial().received().size() >= banner + 2; }, uint64_t(0.1 * kTick));
    m.run([&] { return false; },
          uint64_t(0.01 * kTick));  // anything after the banner would come now
    const auto& got = m.serial().received();
    ASSERT_EQ(got.size(),
              banner + 2);  // the two banner lines again, nothing else
    EXPECT_EQ(got[banner], got[0]);
    EXPECT_EQ(answer_to(m, "G1 X1 F" + std::to_string(im.feed)), "ok");
    EXPECT_EQ(answer_to(m, "M400"), "ok");
    EXPECT_EQ(m.axis('X')->steps(), im.steps_per_mm);
  }
}

}  // namespace
