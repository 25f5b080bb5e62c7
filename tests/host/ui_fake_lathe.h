// A simulated lathe for the workflow's host tests: what core/ui/workflow.h's
// L interface sees, with the carriage moving only when the test says so.
//
// engage() records its arguments and starts a cut that waits for the index
// (synced() false) until index(); run(n) then moves the carriage n steps in
// the cut's direction, ending it when the length is reached (0: never);
// move_to() starts a move that run(n) advances by up to n steps. stop_now()
// ends whatever runs. ms() is a clock the test advances.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "../../core/ui/workflow.h"

struct FakeLathe {
  static constexpr am::ui::Drive kDrive = am::ui::Drive::stepper;
  static constexpr bool kApproximate = false;
  struct Engage {
    am::Ratio ratio;
    bool reversed;
    int32_t length;
    uint8_t start, starts;
  };
  enum Motion { idle, cutting, moving };

  static Motion motion;
  static bool synced_now, refuse;
  static int32_t pos, target, cut_start, error;
  static uint16_t rpm_now, now_ms;
  static std::vector<Engage> engages;
  static std::vector<std::pair<int32_t, uint32_t>> moves;
  static std::vector<am::ui::Settings<am::ui::Drive::stepper>> saved;

  static void reset() {
    motion = idle;
    synced_now = refuse = false;
    pos = target = cut_start = error = 0;
    rpm_now = 0;
    now_ms = 0;
    engages.clear();
    moves.clear();
    saved.clear();
  }

  static bool engage(const am::Ratio& r, bool reversed, int32_t length, uint8_t start, uint8_t starts) {
    if (refuse) return false;
    engages.push_back({r, reversed, length, start, starts});
    motion = cutting;
    synced_now = false;
    cut_start = pos;
    return true;
  }
  static bool synced() { return motion == cutting && synced_now; }
  static bool busy() { return motion != idle; }
  static void stop_now() { motion = idle; }
  static int32_t position() { return pos; }
  static int32_t following_error() { return error; }
  static uint16_t rpm() { return rpm_now; }
  static bool move_to(int32_t steps, uint32_t rate) {
    if (refuse) return false;
    moves.push_back({steps, rate});
    target = steps;
    motion = moving;
    return true;
  }
  static uint16_t ms() { return now_ms; }
  static void save(const am::ui::Settings<am::ui::Drive::stepper>& s) { saved.push_back(s); }

  static void index() { synced_now = true; }
  static void run(int32_t n) {
    if (motion == cutting && synced_now) {
      const Engage& e = engages.back();
      const int32_t dir = e.reversed ? -1 : 1;
      for (int32_t i = 0; i < n && motion == cutting; ++i) {
        pos += dir;
        if (e.length && (pos - cut_start) * dir >= e.length) motion = idle;
      }
    } else if (motion == moving) {
      for (int32_t i = 0; i < n && pos != target; ++i) pos += pos < target ? 1 : -1;
      if (pos == target) motion = idle;
    }
  }
};

using Ui = am::ui::Workflow<FakeLathe>;

// The same lathe with a workflow that approximates what it cannot run
// exactly (a board with kApproximateRatios).
struct FakeApproxLathe : FakeLathe {
  static constexpr bool kApproximate = true;
};
using ApproxUi = am::ui::Workflow<FakeApproxLathe>;

template <class W>
std::string row(const W& ui, int r) {
  std::string s;
  for (int c = 0; c < am::ui::kCols; ++c) {
    const char ch = ui.screen().cell[r * am::ui::kCols + c];
    s += ch >= 1 && ch <= 5 ? char('0' + ch) : ch;  // bar glyphs as digits
  }
  return s;
}

template <class W>
void press(W& ui, const std::string& keys) {
  for (char k : keys) ui.poll(k);
}

// Time passes in 10 ms polls.
inline void wait_ms(Ui& ui, int ms) {
  for (int t = 0; t < ms; t += 10) {
    FakeLathe::now_ms = uint16_t(FakeLathe::now_ms + 10);
    ui.poll(0);
  }
}

// The seed's machine: a 40-slot disc counted on one edge, a 3.175 mm
// leadscrew, a 200-step motor in full steps, rapid 4000 steps/s.
inline am::ui::Settings<am::ui::Drive::stepper> seed_machine() { return {{40, 0, 3175, 0, 200, 1, 0, 4000}, 0}; }

inline am::ui::Settings<am::ui::Drive::stepper> default_settings() {
  am::ui::Settings<am::ui::Drive::stepper> s{};
  am::ui::load_settings(s, seed_machine());  // a zero block is invalid: the defaults
  return s;
}
