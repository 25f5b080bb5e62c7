// The operator workflow's drawing (workflow.h): the screen of each state,
// written into the 2x16 buffer (screen.h), which the display driver sends
// cell by cell where it changed. Included at the end of workflow.h, which
// declares what it defines.
#pragma once
#include "workflow.h"

namespace am {
namespace ui {

template <class L>
void Workflow<L>::z(uint8_t row) {
  screen_.number(row, 9, steps_to_um(machine(settings_), L::position()) / 10, 7, 2);
}

template <class L>
void Workflow<L>::live() {
  screen_.number(1, 0, L::rpm(), 4, 0);
  screen_.text(1, 4, AM_TEXT("rpm Z"));
  z(1);
}

template <class L>
void Workflow<L>::progress() {
  int32_t total = target_ - origin_, covered = L::position() - origin_;
  if (total < 0) total = -total, covered = -covered;
  const int32_t lit = total ? scale(covered, kBarSteps, uint32_t(total)) : kBarSteps;
  screen_.bar(1, lit < 0 ? 0 : lit > kBarSteps ? kBarSteps : uint8_t(lit));
}

template <class L>
void Workflow<L>::draw() {
  drawn_ms_ = L::ms();
  Screen& s = screen_;
  switch (state_) {
    case State::menu:
      s.line(0, AM_TEXT("1Thr 2Feed 3Move"));
      live();
      break;
    case State::entry: {
      s.line(0, spec().label);
      for (uint8_t i = 0; i < kCols; ++i) s.put(1, i, i < typed_.len ? typed_.c[i] : i == typed_.len ? '_' : ' ');
      break;
    }
    case State::hand:
      s.line(0, AM_TEXT("Hand"));
      s.line(1, AM_TEXT("1Right 2Left"));
      break;
    case State::starts:
      s.line(0, AM_TEXT("Starts 1..8"));
      s.line(1, AM_TEXT("1 = one start"));
      break;
    case State::ready:
      s.line(0, starts_ > 1 ? AM_TEXT("OK pass   st  /") : AM_TEXT("OK to cut pass"));
      s.number(0, starts_ > 1 ? 7 : 14, pass_, 2, 0);
      if (starts_ > 1) {  // 1..8: one digit each
        s.put(0, 13, char('1' + start_));
        s.put(0, 15, char('0' + starts_));
      }
      live();
      break;
    case State::cutting:
      if (L::synced()) {
        s.text(0, 0, AM_TEXT("Cut  err"));
        s.number(0, 8, L::following_error(), 8, 0);
      } else {
        s.line(0, AM_TEXT("Wait index"));
      }
      live();
      break;
    case State::done:
      s.text(0, 0, AM_TEXT("Done slip"));
      s.number(0, 9, slip_, 7, 0);
      s.line(1, AM_TEXT("OK=retract C=end"));
      break;
    case State::moving:
      s.text(0, 0, retracting_ ? AM_TEXT("Retract Z") : AM_TEXT("Move    Z"));
      z(0);
      progress();
      break;
    case State::settings: {
      const FieldSpec f = field<kDrive>(field_);
      s.line(0, f.label);
      // "N/M" at the row's end: one digit each for the stepper's 8
      // fields, two for the servo's 11.
      constexpr uint8_t kDigits = field_count(kDrive) > 9 ? 2 : 1, kAt = kCols - 2 * kDigits - 1;
      s.blank(1, s.number(1, 0, int32_t(settings_.value[field_]), 0, f.decimals), kAt);
      s.number(1, kAt, field_ + 1, kDigits, 0);
      s.put(1, kAt + kDigits, '/');
      s.number(1, kAt + kDigits + 1, field_count(kDrive), kDigits, 0);
      break;
    }
    case State::message:
      s.line(0, msg_);
      if (L::kApproximate && msg_row_ == MessageRow::error) {
        // The approximated lead's error per spindle turn, in um with 4
        // decimals (the error is in pm, truncated toward zero).
        s.blank(1, s.text(1, s.number(1, s.text(1, 0, AM_TEXT("err")), msg_error_pm_ / 100, 0, 4), AM_TEXT("um/rev")));
      } else if (msg_row_ == MessageRow::range) {
        const FieldSpec sp = spec();
        s.blank(1, s.number(1, s.text(1, s.number(1, 0, sp.min, 0, sp.decimals), AM_TEXT("..")), sp.max, 0,
                            sp.decimals));
      } else {
        s.blank(1, 0);
      }
      break;
  }
}

}  // namespace ui
}  // namespace am
