// The numbers the operator types on the workflow's entry screen
// (workflow.h): what each is for, its prompt and range (entry_row(); the
// settings' fields are settings.h's field_row()), and the text typed so far
// (TypedText: at most kEntryChars digits, one '.', a leading '-'; the
// workflow reads it as value x 10^decimals, saturating at kTooLarge, above
// every range).
#pragma once
#include <stdint.h>

#include "settings.h"

namespace am {
namespace ui {

// What a number typed on the entry screen is for (entry_row()'s order).
enum class Entry : uint8_t { feed, pitch_mm, pitch_tpi, length, move, setting };

inline const FieldSpec& entry_row(Entry e) {
  static const char kFeed[] AM_FLASH = "Feed mm/rev B:tb";
  static const char kMm[] AM_FLASH = "Pitch mm A:TPI";
  static const char kTpi[] AM_FLASH = "Pitch TPI A:mm";
  static const char kLength[] AM_FLASH = "Length mm 0=run";
  static const char kMove[] AM_FLASH = "Move mm *:minus";
  static const FieldSpec kSpecs[] AM_FLASH = {
      {kFeed, 1, 5000, 3}, {kMm, 10, 50000, 3}, {kTpi, 10, 2000, 1}, {kLength, 0, 200000, 2}, {kMove, -200000, 200000, 2},
  };
  return kSpecs[uint8_t(e)];
}

constexpr uint8_t kEntryChars = 8;      // digits, '.', '-'
constexpr int32_t kTooLarge = 1000000;  // a typed number saturates here

// The text typed so far.
struct TypedText {
  uint8_t len;
  char c[kEntryChars];

  // Whether a decimal point has been typed ('#' then types no second one).
  bool has_point() const {
    for (uint8_t i = 0; i < len; ++i)
      if (c[i] == '.') return true;
    return false;
  }
};

}  // namespace ui
}  // namespace am
