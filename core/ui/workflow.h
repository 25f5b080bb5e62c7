// The lathe's operator workflow: keys in, screen out, the leadscrew driven
// through a small interface. Hardware-free; host-tested with a simulated
// lathe (tests/host/test_ui_workflow.cpp) and run on the m16 by
// firmware/apps/lathe/operator.cpp.
//
// Keys (the seed's 4x4 pad: 1 2 3 A / 4 5 6 B / 7 8 9 C / * 0 # D)
//   digits and '#' (decimal point, once) type a number; D = OK, and stops the
//   carriage at once while it moves (emergency stop); C deletes the last
//   character typed, on an empty field or elsewhere it goes back (while the
//   carriage moves it stops it too); A switches a pitch between mm and TPI,
//   opens the settings from the menu and steps through them (after the
//   last, the first); B on a pitch or feed entry types the table's next
//   distinct value (tables.h) in place of the text, to be taken with D or
//   edited; '*' first in a move's distance makes it negative.
//
// Screens (2 x 16)
//   menu       "1Thr 2Feed 3Move" + the live line (spindle rpm, carriage Z
//              mm): a thread (pitch in mm or TPI, typed or from the ISO or
//              TPI table), a feed (mm per turn, typed or from the feed
//              table, which holds the seed's 0.04 and 0.08), a move; A opens
//              the settings
//   entry      the prompt, and the text typed so far with a '_' cursor
//   hand       "1Right 2Left"
//   starts     a thread's starts, one key 1..8 (a feed has one and skips it)
//   length     mm with 2 decimals, 0 = until stopped (D or the limit switch);
//              the ratio is computed here (core/lathe/ratio.h): one the
//              follower cannot run exactly is refused with a message
//              (gear_ratio_exact), or, with L::kApproximate, replaced by
//              the nearest it can run (gear_ratio), shown as "Approx.
//              ratio" and its lead's error per spindle turn in um before
//              the ready screen
//   ready      "OK to cut pass N" + the live line; a multi-start thread
//              "OK pass N st K/n": start K's pass (start K of n begins K-1
//              n-ths of a turn after start 1, exactly: follower.h); A offers
//              the next start instead
//   cutting    "Wait index" until the leadscrew has synchronised, then the
//              following error and the live line; ends when the leadscrew is
//              done (length, limit switch, D)
//   done       the slip (following error when it stopped), "OK=retract"
//   retract    back to where the pass began at the rapid rate, a progress
//              bar; then ready for the next pass, which the leadscrew
//              re-enters on the same helix (it waits for the index again):
//              the next start of a multi-start thread, after its last start
//              the first one with the next pass number
//   move       a signed distance in mm, then the move with a progress bar
//   settings   one field per screen (core/ui/settings.h), A to step, D to
//              edit; C leaves and stores the block (save(): the EEPROM's
//              update writes only the bytes that changed)
//   message    a refusal or notice on row 0 ("Cut refused", "Ratio not
//              exact", ...), the valid range on row 1 for a number out of
//              range; any key or 1.5 s goes back
//
// Lathe interface (L: static functions; a simulated one in
// tests/host/ui_fake_lathe.h): engage(ratio, reversed, length_steps, start,
// starts) -> accepted, and then busy() until the pass ends; synced() (following the
// spindle, not waiting for the index); busy(); stop_now(); position()
// (steps); following_error() (steps); rpm(); move_to(steps, rate) ->
// accepted, and then busy() until it ends; ms() (a free-running millisecond
// count); save(settings); kDrive, the leadscrew's drive (settings.h: the
// settings' fields and layout); kApproximate, whether a ratio the follower
// cannot run exactly is approximated (the continued fraction, about 1.6 KB
// of AVR flash) or refused.
//
// Numbers: lengths, moves and the carriage's Z through units.h, exact.
//
// Object: zero-initialised storage is a valid state before start() (no
// constructor code in the image).
#pragma once
#include <stdint.h>

#include "../lathe/ratio.h"
#include "entries.h"
#include "screen.h"
#include "settings.h"
#include "tables.h"
#include "units.h"

namespace am {
namespace ui {

enum class State : uint8_t { menu, entry, hand, starts, ready, cutting, done, moving, settings, message };

// The workflow's steps stay out of line: each is called from several places
// and inlined copies cost the ATmega16 flash it does not have.
#define AM_UI_OUTLINE __attribute__((noinline))

constexpr uint16_t kMessageMs = 1500;
constexpr uint16_t kRefreshMs = 100;

template <class L>
class Workflow {
 public:
  static constexpr Drive kDrive = L::kDrive;
  using Block = Settings<kDrive>;

  // After the settings block was read from the EEPROM: `loaded` says
  // whether it was valid (else the defaults are in use, and a message says
  // so).
  void start(const Block& s, bool loaded) {
    settings_ = s;
    screen_.clear_sent();
    go(State::menu);
    if (!loaded) message(AM_TEXT("Defaults loaded"), State::menu);
    draw();
  }

  const Screen& screen() const { return screen_; }
  Screen& screen() { return screen_; }
  const Block& settings() const { return settings_; }
  State state() const { return state_; }

  // One pass of the main loop: `key` is a key pressed since the last pass, or 0.
  void poll(char key) {
    const State before = state_;
    const uint16_t now = L::ms();
    if (key) on_key(key);
    else track(now);
    if (key || state_ != before || uint16_t(now - drawn_ms_) >= kRefreshMs) draw();
  }

 private:
  // --- transitions ------------------------------------------------------
  AM_UI_OUTLINE void go(State s) {
    state_ = s;
    entered_ms_ = L::ms();
  }

  AM_UI_OUTLINE void message(const char* text, State back) {
    msg_ = text;
    msg_row_ = MessageRow::blank;
    back_ = back;
    go(State::message);
  }

  AM_UI_OUTLINE void begin_entry(Entry e) {
    entry_ = e;
    typed_.len = 0;
    row_ = 0xFF;  // the table's first row comes next
    go(State::entry);
  }

  // The entry's table (feed, metric, inch: the lists' order), one distinct
  // value on from the last one typed from it; the text becomes that value.
  AM_UI_OUTLINE void next_row() {
    const List list = List(entry_);
    const uint16_t was = row_ < list_size(list) ? table_value(list, row_) : 0;
    do row_ = uint8_t(row_ + 1 >= list_size(list) ? 0 : row_ + 1);
    while (table_value(list, row_) == was);
    // At most 6 characters ("80.0", "6.000", "0.500"): typed_ holds 8.
    typed_.len = Screen::format(typed_.c, table_value(list, row_), entry_ == Entry::pitch_tpi ? 1 : 3);
  }

  // Time-driven changes: a message times out, a motion ends.
  AM_UI_OUTLINE void track(uint16_t now) {
    if (state_ == State::message && uint16_t(now - entered_ms_) >= kMessageMs) go(back_);
    if (L::busy()) return;
    if (state_ == State::cutting) {
      slip_ = L::following_error();
      go(State::done);
    } else if (state_ == State::moving) {
      if (retracting_) next_start(true);
      go(retracting_ ? State::ready : State::menu);
    }
  }

  AM_UI_OUTLINE void on_key(char k) {
    const bool digit = k >= '0' && k <= '9';
    switch (state_) {
      case State::menu:
        if (k == '1') begin_entry(Entry::pitch_mm);
        if (k == '2') begin_entry(Entry::feed);
        if (k == '3') begin_entry(Entry::move);
        if (k == 'A') {
          field_ = 0;
          go(State::settings);
        }
        break;
      case State::entry:
        if (digit || (k == '#' && !typed_.has_point()) || (k == '*' && entry_ == Entry::move && typed_.len == 0)) {
          if (typed_.len < kEntryChars) typed_.c[typed_.len++] = k == '#' ? '.' : k == '*' ? '-' : k;
        } else if (k == 'C') {
          if (typed_.len == 0) go(entry_ == Entry::length ? (thread_ ? State::starts : State::hand)
                                  : entry_ == Entry::setting ? State::settings
                                                             : State::menu);
          else --typed_.len;
        } else if (k == 'A' && (entry_ == Entry::pitch_mm || entry_ == Entry::pitch_tpi)) {
          begin_entry(entry_ == Entry::pitch_mm ? Entry::pitch_tpi : Entry::pitch_mm);
        } else if (k == 'B' && entry_ <= Entry::pitch_tpi) {
          next_row();
        } else if (k == 'D') {
          int32_t v = 0;
          if (parse(v)) accept(v);
        }
        break;
      case State::hand:
        if (k == '1' || k == '2') {
          left_ = k == '2';
          if (thread_) go(State::starts);
          else begin_entry(Entry::length);
        }
        if (k == 'C') go(State::menu);
        break;
      case State::starts:
        if (k >= '1' && k <= '8') {
          starts_ = uint8_t(k - '0');
          begin_entry(Entry::length);
        }
        if (k == 'C') go(State::hand);
        break;
      case State::ready:
        if (k == 'D') {
          pass_start_ = L::position();
          if (L::engage(ratio_, reversed_, length_steps_, start_, starts_)) go(State::cutting);
          else message(AM_TEXT("Cut refused"), State::ready);
        }
        if (k == 'A') next_start(false);
        if (k == 'C') go(State::menu);
        break;
      case State::cutting:
      case State::moving:
        if (k == 'D' || k == 'C') L::stop_now();
        break;
      case State::done:
        if (k == 'D') move(pass_start_, true);
        if (k == 'C') go(State::menu);
        break;
      case State::settings:
        if (k == 'A') field_ = uint8_t(field_ + 1 == field_count(kDrive) ? 0 : field_ + 1);
        if (k == 'D') begin_entry(Entry::setting);
        if (k == 'C') {
          seal(settings_);
          L::save(settings_);  // the EEPROM's cells are written only where they differ
          message(AM_TEXT("Settings saved"), State::menu);
        }
        break;
      case State::message:
        go(back_);
        break;
    }
  }

  AM_UI_OUTLINE void choose(const Pitch& p) {
    pitch_ = p;
    thread_ = entry_ != Entry::feed;
    starts_ = 1;
    go(State::hand);
  }

  // The start the next pass cuts: the next one, after the last the first
  // again, and then (after a pass, `counted`) with the next pass number.
  AM_UI_OUTLINE void next_start(bool counted) {
    if (++start_ < starts_) return;
    start_ = 0;
    if (counted) ++pass_;
  }

  // A move at the rapid rate to `target`; refused: a message.
  AM_UI_OUTLINE void move(int32_t target, bool retract) {
    origin_ = L::position();
    target_ = target;
    retracting_ = retract;
    if (L::move_to(target, settings_.value[kFieldRapid])) go(State::moving);
    else message(AM_TEXT("Move refused"), retract ? State::done : State::menu);
  }

  // --- number entry -----------------------------------------------------
  AM_UI_OUTLINE FieldSpec spec() const {
    return flash_copy(entry_ == Entry::setting ? &field_row<kDrive>(field_) : &entry_row(entry_));
  }

  // The typed text as value x 10^decimals; false (and a message) if it is
  // not a number, has too many decimals or is out of range.
  AM_UI_OUTLINE bool parse(int32_t& out) {
    const FieldSpec s = spec();
    int32_t v = 0;
    uint8_t frac = 0, digits = 0;
    bool point = false;
    const bool negative = typed_.len && typed_.c[0] == '-';
    for (uint8_t i = negative; i < typed_.len; ++i) {
      if (typed_.c[i] == '.') {
        point = true;
        continue;
      }
      ++digits;
      v = v >= kTooLarge ? kTooLarge : v * 10 + (typed_.c[i] - '0');  // above every range, scaled or not
      frac = uint8_t(frac + point);
    }
    if (!digits) return refuse(AM_TEXT("Type a number"), false);
    if (frac > s.decimals) return refuse(AM_TEXT("Fewer decimals"), false);
    for (; frac < s.decimals; ++frac) v *= 10;
    if (negative) v = -v;
    if (v < s.min || v > s.max) return refuse(AM_TEXT("Out of range"), true);
    out = v;
    return true;
  }

  AM_UI_OUTLINE bool refuse(const char* why, bool range) {
    message(why, State::entry);
    msg_row_ = range ? MessageRow::range : MessageRow::blank;
    return false;
  }

  AM_UI_OUTLINE void accept(int32_t v) {
    const Machine m = machine(settings_);
    if (entry_ == Entry::feed || entry_ == Entry::pitch_mm) choose(pitch_um(uint32_t(v)));
    if (entry_ == Entry::pitch_tpi) choose({254000, uint32_t(v)});
    if (entry_ == Entry::move) move(L::position() + um_to_steps(m, v * 10), false);
    if (entry_ == Entry::setting) {
      settings_.value[field_] = uint32_t(v);
      go(State::settings);
    }
    if (entry_ == Entry::length) {
      length_steps_ = um_to_steps(m, v * 10);
      const ThreadRequest t = {pitch_, starts_, left_ ? Hand::left : Hand::right};
      const GearRatio g = L::kApproximate ? gear_ratio(m, t) : gear_ratio_exact(m, t);
      const bool approximated = L::kApproximate && g.status == RatioStatus::approximated;
      if (g.status != RatioStatus::exact && !approximated) {
        message(AM_TEXT("Ratio not exact"), State::menu);
        return;
      }
      ratio_ = g.ratio;
      reversed_ = g.reversed;
      pass_ = 1;
      start_ = 0;
      go(State::ready);
      if (approximated) {
        message(AM_TEXT("Approx. ratio"), State::ready);
        msg_row_ = MessageRow::error;
        msg_error_pm_ = g.error_pm;
      }
    }
  }

  // --- drawing (workflow_draw.h) ------------------------------------------
  // Carriage Z in mm from column 9 of `row`.
  AM_UI_OUTLINE void z(uint8_t row);
  // "1234rpm Z-123.45" on row 1.
  void live();
  // The distance covered of the current move as a bar on row 1: floor(80
  // covered / total) columns lit.
  AM_UI_OUTLINE void progress();
  // The screen of the state.
  AM_UI_OUTLINE void draw();

  Screen screen_;
  Block settings_;
  State state_;
  State back_;
  Entry entry_;
  uint8_t row_;  // the table row typed last, 0xFF for none
  uint8_t field_;
  bool left_;
  bool thread_;     // a thread (its starts asked for), not a feed
  uint8_t starts_;  // 1..8
  uint8_t start_;   // the next pass's start, 0..starts_ - 1
  bool retracting_;
  // A message's second row: blank, the entry's range, or an approximated
  // ratio's error (msg_error_pm_, L::kApproximate only).
  enum class MessageRow : uint8_t { blank, range, error } msg_row_;
  int32_t msg_error_pm_;
  TypedText typed_;
  uint16_t pass_;
  uint16_t entered_ms_;
  uint16_t drawn_ms_;
  const char* msg_;
  Pitch pitch_;
  Ratio ratio_;
  bool reversed_;
  int32_t length_steps_;
  int32_t pass_start_;  // where the pass began: the retract's target
  int32_t origin_;      // where the current move began
  int32_t target_;      // and where it ends
  int32_t slip_;
};

}  // namespace ui
}  // namespace am

// Workflow::draw() and its parts, apart (one concern a file).
#include "workflow_draw.h"
