// The lathe's operator workflow: keys in, screen out, the leadscrew driven
// through a small interface. Hardware-free; host-tested with a simulated
// lathe (tests/host/test_ui_*.cpp) and run on the m16 by
// firmware/apps/lathe/operator.cpp.
//
// Keys (the seed's 4x4 pad: 1 2 3 A / 4 5 6 B / 7 8 9 C / * 0 # D)
//   digits and '#' (decimal point) type a number; D = OK, and stops the
//   carriage at once while it moves (emergency stop); C deletes the last
//   character typed, on an empty field or elsewhere it goes back (during a
//   move it stops the carriage too); A switches a pitch between mm and TPI,
//   or steps forward through a table or the settings; B opens the pitch table,
//   or steps back; '*' changes the sign of a move.
//
// Screens (2 x 16)
//   menu       "1Cut 2Move 3Set" + the live line (spindle rpm, carriage Z mm)
//   kind       "1Feed 2Fine 3Thr": a feed (mm per turn, typed or from the
//              feed table), the seed's fine feed 0.04 mm per turn, a thread
//              (pitch in mm or TPI, typed or from the ISO/UNC/UNF/TPI table)
//   hand       "1Right 2Left"
//   length     mm with 2 decimals, 0 = until stopped (D or the limit switch)
//   ready      "OK to cut  pass N" + the live line, or the ratio's error in um
//              per spindle turn when core/lathe/ratio.h had to approximate it
//   cutting    "Wait index" until the leadscrew has synchronised, then the
//              live rpm, Z and following error; ends when the leadscrew is
//              done (length, limit switch, D)
//   done       the slip (following error when it stopped), "OK=retract"
//   retract    back to where the pass began at the rapid rate, a progress
//              bar; then ready for the next pass, which the leadscrew
//              re-enters on the same helix (it waits for the index again)
//   move       a signed distance in mm, then the move with a progress bar
//   settings   one field per screen (core/ui/settings.h), A/B to step, D to
//              edit; C leaves and writes the block to the EEPROM if changed
//   message    a refusal or notice on row 0, the valid range on row 1 for a
//              number out of range; any key or 1.5 s goes back
//
// Lathe interface (L: static functions, see tests/host/test_ui_workflow.cpp
// for a simulated one): engage(ratio, reversed, length_steps) -> accepted;
// synced() (following the spindle); busy(); stop_now(); position() (steps);
// following_error() (steps); rpm(); move_to(steps, rate) -> accepted; ms()
// (a free-running millisecond count); save(settings).
//
// Numbers: a length or move in mm becomes steps as floor(um x counts per
// turn / lead); the carriage position shows as floor(steps x lead / counts),
// both exact in 128 bits (core/lathe/wide.h), so nothing rounds twice.
#pragma once
#include <stdint.h>

#include "../lathe/ratio.h"
#include "screen.h"
#include "settings.h"
#include "tables.h"

namespace am {
namespace ui {

// floor(a m1 m2 / (d1 d2)), saturated to 2^31 - 1; every factor nonzero
// except a.
inline uint32_t scale(uint32_t a, uint32_t m1, uint32_t m2, uint32_t d1, uint32_t d2) {
  U128 x = u128(a), rem;
  mul_small(x, m1);
  mul_small(x, m2);
  divmod(x, u128(d1), x, rem);
  divmod(x, u128(d2), x, rem);
  return (!fits32(x) || x.w[0] > 0x7FFFFFFFu) ? 0x7FFFFFFFu : x.w[0];
}

inline int32_t um_to_steps(const Machine& m, int32_t um) {
  const uint32_t mag = scale(um < 0 ? uint32_t(-um) : uint32_t(um), m.leadscrew_counts.num, m.leadscrew.den,
                             m.leadscrew.num, m.leadscrew_counts.den);
  return um < 0 ? -int32_t(mag) : int32_t(mag);
}

inline int32_t steps_to_um(const Machine& m, int32_t steps) {
  const uint32_t mag = scale(steps < 0 ? uint32_t(0) - uint32_t(steps) : uint32_t(steps), m.leadscrew.num,
                             m.leadscrew_counts.den, m.leadscrew.den, m.leadscrew_counts.num);
  return steps < 0 ? -int32_t(mag) : int32_t(mag);
}

enum class State : uint8_t { menu, kind, entry, table, hand, ready, cutting, done, retract, moving, settings, message };

// What a number typed on the entry screen is for.
enum class Entry : uint8_t { feed, pitch_mm, pitch_tpi, length, move, setting };

constexpr uint8_t kEntryChars = 9;  // digits, '.', '-'
constexpr uint16_t kMessageMs = 1500;
constexpr uint16_t kRefreshMs = 100;
constexpr uint32_t kFineFeedUm = 40;  // the seed's fine feed
constexpr int32_t kTooLarge = 1000000;  // a typed number saturates here

template <class L>
class Workflow {
 public:
  // After the settings block was read from the EEPROM: `loaded` says
  // whether it was valid (else the defaults are in use, and a message says
  // so).
  void start(const Settings& s, bool loaded) {
    settings_ = s;
    screen_.clear_sent();
    go(State::menu);
    if (!loaded) message(AM_TEXT("Settings reset"), AM_TEXT("to defaults"), State::menu);
    draw();
  }

  const Screen& screen() const { return screen_; }
  Screen& screen() { return screen_; }
  const Settings& settings() const { return settings_; }
  State state() const { return state_; }

  // One pass of the main loop: `key` is a new key press or 0.
  void poll(char key) {
    if (key) {
      on_key(key);
      draw();
      return;
    }
    const uint16_t now = L::ms();
    const State before = state_;
    track(now);
    if (state_ != before || uint16_t(now - drawn_ms_) >= kRefreshMs) draw();
  }

 private:
  // --- transitions ------------------------------------------------------
  void go(State s) {
    state_ = s;
    entered_ms_ = L::ms();
  }

  void message(const char* top, const char* bottom, State back) {
    msg_top_ = top;
    msg_bottom_ = bottom;
    msg_range_ = false;
    back_ = back;
    go(State::message);
  }

  void begin_entry(Entry e) {
    entry_ = e;
    typed_len_ = 0;
    typed_[0] = 0;
    go(State::entry);
  }

  Machine machine_now() const { return machine(settings_); }

  // Time-driven changes: a message times out, a motion ends.
  void track(uint16_t now) {
    if (state_ == State::message && uint16_t(now - entered_ms_) >= kMessageMs) go(back_);
    if (L::busy()) return;
    if (state_ == State::cutting) {
      slip_ = L::following_error();
      go(State::done);
    } else if (state_ == State::retract) {
      ++pass_;
      go(State::ready);
    } else if (state_ == State::moving) {
      go(State::menu);
    }
  }

  void on_key(char k) {
    switch (state_) {
      case State::menu:
        if (k == '1') go(State::kind);
        if (k == '2') begin_entry(Entry::move);
        if (k == '3') {
          field_ = 0;
          changed_ = false;
          go(State::settings);
        }
        break;
      case State::kind:
        if (k == '1') begin_entry(Entry::feed);
        if (k == '2') {
          threading_ = false;
          pitch_ = pitch_um(kFineFeedUm);
          go(State::hand);
        }
        if (k == '3') begin_entry(Entry::pitch_mm);
        if (k == 'C') go(State::menu);
        break;
      case State::entry:
        entry_key(k);
        break;
      case State::table:
        table_key(k);
        break;
      case State::hand:
        if (k == '1' || k == '2') {
          left_ = k == '2';
          begin_entry(Entry::length);
        }
        if (k == 'C') go(State::kind);
        break;
      case State::ready:
        if (k == 'D') cut();
        if (k == 'C') go(State::menu);
        break;
      case State::cutting:
      case State::retract:
      case State::moving:
        if (k == 'D' || k == 'C') L::stop_now();
        break;
      case State::done:
        if (k == 'D') move(pass_start_, State::retract, State::done);
        if (k == 'C') go(State::menu);
        break;
      case State::settings:
        settings_key(k);
        break;
      case State::message:
        go(back_);
        break;
    }
  }

  // The ratio for the pitch, hand and settings; a pass needs one that fits.
  void prepare() {
    const GearRatio g = gear_ratio(machine_now(), {pitch_, 1, left_ ? Hand::left : Hand::right});
    if (g.status == RatioStatus::out_of_range) {
      message(AM_TEXT("Ratio too large"), AM_TEXT("pitch or setup?"), State::kind);
      return;
    }
    ratio_ = g.ratio;
    reversed_ = g.reversed;
    approximated_ = g.status == RatioStatus::approximated;
    error_pm_ = g.error_pm;
    pass_ = 1;
    go(State::ready);
  }

  void cut() {
    pass_start_ = L::position();
    if (L::engage(ratio_, reversed_, length_steps_)) go(State::cutting);
    else message(AM_TEXT("Cut refused"), AM_TEXT("too fast?"), State::ready);
  }

  // A move at the rapid rate to `target`, shown as `moving` (retract or
  // move); refused: a message, then `refused`.
  void move(int32_t target, State moving, State refused) {
    origin_ = L::position();
    target_ = target;
    if (L::move_to(target, settings_.value[kFieldRapid])) go(moving);
    else message(AM_TEXT("Move refused"), AM_TEXT(""), refused);
  }

  // --- number entry -----------------------------------------------------
  struct Spec {
    const char* prompt;
    int32_t min, max;
    uint8_t decimals;
  };

  Spec spec() const {
    switch (entry_) {
      case Entry::feed: return {AM_TEXT("Feed mm/rev B:tb"), 1, 5000, 3};
      case Entry::pitch_mm: return {AM_TEXT("Pitch mm A:TPI"), 10, 50000, 3};
      case Entry::pitch_tpi: return {AM_TEXT("Pitch TPI A:mm"), 10, 2000, 1};
      case Entry::length: return {AM_TEXT("Length mm 0=run"), 0, 200000, 2};
      case Entry::move: return {AM_TEXT("Move mm *:sign"), -200000, 200000, 2};
      case Entry::setting: break;
    }
    const FieldSpec f = field(field_);
    return {f.label, int32_t(f.min), int32_t(f.max), f.decimals};
  }

  State entry_back() const {
    return entry_ == Entry::length ? State::hand : entry_ == Entry::setting ? State::settings
           : entry_ == Entry::move                                          ? State::menu
                                                                            : State::kind;
  }

  void entry_key(char k) {
    const bool room = typed_len_ < kEntryChars - 1;
    if ((k >= '0' && k <= '9') || k == '#') {
      if (room) typed_[typed_len_++] = k == '#' ? '.' : k;
    } else if (k == '*' && entry_ == Entry::move) {
      if (typed_len_ && typed_[0] == '-') {
        for (uint8_t i = 0; i < typed_len_; ++i) typed_[i] = typed_[i + 1];
        --typed_len_;
      } else if (room) {
        for (uint8_t i = typed_len_ + 1; i > 0; --i) typed_[i] = typed_[i - 1];
        typed_[0] = '-';
        ++typed_len_;
      }
    } else if (k == 'C') {
      if (typed_len_ == 0) go(entry_back());
      else --typed_len_;
    } else if (k == 'A' && (entry_ == Entry::pitch_mm || entry_ == Entry::pitch_tpi)) {
      begin_entry(entry_ == Entry::pitch_mm ? Entry::pitch_tpi : Entry::pitch_mm);
    } else if (k == 'B' && entry_ != Entry::length && entry_ != Entry::move && entry_ != Entry::setting) {
      list_ = entry_ == Entry::feed ? kFeedList : entry_ == Entry::pitch_mm ? kMetricList : kInchList;
      row_ = 0;
      go(State::table);
    } else if (k == 'D') {
      int32_t v;
      if (parse(v)) accept(v);
    }
    typed_[typed_len_] = 0;
  }

  // The typed text as value x 10^decimals; false (and a message) if it is
  // not a number, has too many decimals or is out of range.
  bool parse(int32_t& out) {
    const Spec s = spec();
    int32_t v = 0;
    uint8_t frac = 0;
    bool point = false, digits = false;
    for (uint8_t i = typed_[0] == '-' ? 1 : 0; i < typed_len_; ++i) {
      if (typed_[i] == '.') {
        if (point) return refuse(AM_TEXT("Two points"));
        point = true;
        continue;
      }
      digits = true;
      // Saturated at kTooLarge, above every field's range even scaled.
      v = v >= kTooLarge ? kTooLarge : v * 10 + (typed_[i] - '0');
      if (point) ++frac;
    }
    if (!digits) return refuse(AM_TEXT("Type a number"));
    if (frac > s.decimals) return refuse(AM_TEXT("Fewer decimals"));
    for (; frac < s.decimals; ++frac) v *= 10;
    if (typed_[0] == '-') v = -v;
    if (v < s.min || v > s.max) {
      refuse(AM_TEXT("Out of range"));
      msg_range_ = true;
      return false;
    }
    out = v;
    return true;
  }

  bool refuse(const char* why) {
    message(why, AM_TEXT(""), State::entry);
    return false;
  }

  void accept(int32_t v) {
    const Machine m = machine_now();
    switch (entry_) {
      case Entry::feed:
      case Entry::pitch_mm:
        threading_ = entry_ == Entry::pitch_mm;
        pitch_ = pitch_um(uint32_t(v));
        go(State::hand);
        break;
      case Entry::pitch_tpi:
        threading_ = true;
        pitch_ = {254000, uint32_t(v)};
        go(State::hand);
        break;
      case Entry::length:
        length_steps_ = um_to_steps(m, v * 10);
        prepare();
        break;
      case Entry::move:
        move(L::position() + um_to_steps(m, v * 10), State::moving, State::menu);
        break;
      case Entry::setting:
        if (settings_.value[field_] != uint32_t(v)) changed_ = true;
        settings_.value[field_] = uint32_t(v);
        go(State::settings);
        break;
    }
  }

  void table_key(char k) {
    const uint8_t n = list_size(list_);
    if (k == 'A') row_ = uint8_t(row_ + 1 == n ? 0 : row_ + 1);
    if (k == 'B') row_ = uint8_t(row_ == 0 ? n - 1 : row_ - 1);
    if (k == 'C') go(State::entry);
    if (k == 'D') {
      threading_ = list_ != kFeedList;
      pitch_ = list_pitch(list_, row_);
      go(State::hand);
    }
  }

  void settings_key(char k) {
    if (k == 'A') field_ = uint8_t(field_ + 1 == kFieldCount ? 0 : field_ + 1);
    if (k == 'B') field_ = uint8_t(field_ == 0 ? kFieldCount - 1 : field_ - 1);
    if (k == 'D') begin_entry(Entry::setting);
    if (k == 'C') {
      if (!changed_) {
        go(State::menu);
        return;
      }
      seal(settings_);
      L::save(settings_);
      message(AM_TEXT("Settings saved"), AM_TEXT(""), State::menu);
    }
  }

  // --- drawing ----------------------------------------------------------
  // "1234rpm Z-123.45" on row 1.
  void live(uint8_t row) {
    screen_.number(row, 0, L::rpm(), 4, 0);
    screen_.text(row, 4, AM_TEXT("rpm Z"));
    screen_.number(row, 9, steps_to_um(machine_now(), L::position()) / 10, 7, 2);
  }

  // The distance covered of the current move as a bar on row 1.
  void progress() {
    uint32_t total = uint32_t(target_ - origin_), done = uint32_t(L::position() - origin_);
    if (int32_t(total) < 0) {
      total = 0u - total;
      done = 0u - done;
    }
    if (int32_t(done) < 0) done = 0;
    if (done > total) done = total;
    while (total > 0x1FFFFFF) total >>= 1, done >>= 1;
    screen_.bar(1, total ? uint8_t(done * kBarSteps / total) : kBarSteps);
  }

  void draw() {
    drawn_ms_ = L::ms();
    Screen& s = screen_;
    switch (state_) {
      case State::menu:
        s.line(0, AM_TEXT("1Cut 2Move 3Set"));
        live(1);
        break;
      case State::kind:
        s.line(0, AM_TEXT("1Feed 2Fine 3Thr"));
        live(1);
        break;
      case State::entry: {
        const Spec sp = spec();
        s.line(0, sp.prompt);
        s.put(1, s.ram_text(1, 0, typed_), '_');
        s.blank(1, uint8_t(typed_len_ + 1));
        break;
      }
      case State::table:
        draw_row(s, list_, row_);
        break;
      case State::hand:
        s.line(0, threading_ ? AM_TEXT("Thread hand") : AM_TEXT("Feed direction"));
        s.line(1, AM_TEXT("1Right 2Left"));
        break;
      case State::ready: {
        s.line(0, AM_TEXT("OK to cut pass"));
        s.number(0, 14, pass_, 2, 0);
        if (approximated_) {  // the ratio's error in um per spindle turn
          s.text(1, 0, AM_TEXT("err"));
          s.text(1, s.number(1, 3, error_pm_ / 1000, 8, 3), AM_TEXT("um/r"));
          s.blank(1, 15);
        } else {
          live(1);
        }
        break;
      }
      case State::cutting:
        if (L::synced()) {
          s.text(0, 0, AM_TEXT("Cut  err"));
          s.number(0, 8, L::following_error(), 8, 0);
        } else {
          s.line(0, AM_TEXT("Wait index"));
        }
        live(1);
        break;
      case State::done:
        s.text(0, 0, AM_TEXT("Done slip"));
        s.number(0, 9, slip_, 7, 0);
        s.line(1, AM_TEXT("OK=retract C=end"));
        break;
      case State::retract:
      case State::moving:
        s.text(0, 0, state_ == State::retract ? AM_TEXT("Retract Z") : AM_TEXT("Move    Z"));
        s.number(0, 9, steps_to_um(machine_now(), L::position()) / 10, 7, 2);
        progress();
        break;
      case State::settings: {
        const FieldSpec f = field(field_);
        s.line(0, f.label);
        s.blank(1, s.number(1, 0, int32_t(settings_.value[field_]), 0, f.decimals), 13);
        s.number(1, 13, field_ + 1, 1, 0);
        s.put(1, 14, '/');
        s.number(1, 15, kFieldCount, 1, 0);
        break;
      }
      case State::message:
        s.line(0, msg_top_);
        if (msg_range_) {
          const Spec sp = spec();
          s.blank(1, s.number(1, s.text(1, s.number(1, 0, sp.min, 0, sp.decimals), AM_TEXT("..")), sp.max, 0,
                              sp.decimals));
        } else {
          s.line(1, msg_bottom_);
        }
        break;
    }
  }

  Screen screen_;
  Settings settings_;
  State state_ = State::menu;
  State back_ = State::menu;
  Entry entry_ = Entry::feed;
  List list_ = kFeedList;
  uint8_t row_ = 0;
  uint8_t field_ = 0;
  bool changed_ = false;
  bool threading_ = false;
  bool left_ = false;
  bool msg_range_ = false;
  uint8_t typed_len_ = 0;
  char typed_[kEntryChars + 1] = {};
  uint16_t pass_ = 1;
  uint16_t entered_ms_ = 0;
  uint16_t drawn_ms_ = 0;
  const char* msg_top_ = nullptr;
  const char* msg_bottom_ = nullptr;
  Pitch pitch_ = {1000, 1};
  Ratio ratio_ = {1, 1};
  bool reversed_ = false;
  bool approximated_ = false;
  int32_t error_pm_ = 0;
  int32_t length_steps_ = 0;
  int32_t pass_start_ = 0;  // where the pass began: the retract's target
  int32_t origin_ = 0;      // where the current retract or move began
  int32_t target_ = 0;      // and where it ends
  int32_t slip_ = 0;
};

}  // namespace ui
}  // namespace am
