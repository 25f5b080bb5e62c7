// The pitch tables the operator picks from, as flash copies of core/lathe's
// arrays, and one row of them as a pitch and a two-line description.
//
// Contract
//   Three lists: kFeedList (turning feeds, mm per turn), kMetricList (ISO
//   coarse, named by size), kInchList (the common TPI, which hold every UNC
//   and UNF pitch). list_size(list) rows each; list_pitch(list, i) is row
//   i's pitch, exact (core/lathe/ratio.h's Pitch); draw_row(screen, list, i)
//   writes its name on row 0 (the ISO size, "Feed", "Inch") and its pitch
//   on row 1.
//   ISO fine, UNC and UNF are left out of the image (248 bytes of flash):
//   their pitches are all in these lists, and any pitch can be typed.
#pragma once
#include <stdint.h>

#include "../lathe/pitch_tables.h"
#include "../lathe/ratio.h"
#include "flash.h"
#include "screen.h"

namespace am {
namespace ui {

enum List : uint8_t { kFeedList, kMetricList, kInchList };

struct Tables {
  FlashRows<uint16_t, kTurningFeedsCount> feeds;
  FlashRows<MetricThread, kIsoCoarseCount> iso;
  FlashRows<uint8_t, kCommonTpiCount> tpi;
};

inline const Tables& tables() {
  static const Tables kTables AM_FLASH = {flash_rows(kTurningFeeds), flash_rows(kIsoCoarse), flash_rows(kCommonTpi)};
  return kTables;
}

inline uint8_t list_size(List list) {
  return list == kFeedList ? uint8_t(kTurningFeedsCount)
         : list == kMetricList ? uint8_t(kIsoCoarseCount)
                               : uint8_t(kCommonTpiCount);
}

// Row i's pitch: um (feeds, metric) or TPI x 2 (inch).
inline uint16_t row_pitch(List list, uint8_t i) {
  const Tables& t = tables();
  return list == kFeedList ? flash_copy(&t.feeds.row[i])
         : list == kMetricList ? flash_copy(&t.iso.row[i].pitch_um)
                               : flash_copy(&t.tpi.row[i]);
}

inline Pitch list_pitch(List list, uint8_t i) {
  const uint16_t p = row_pitch(list, i);
  return list == kInchList ? pitch_tpi_x2(p) : pitch_um(p);
}

inline void draw_row(Screen& s, List list, uint8_t i) {
  const uint16_t p = row_pitch(list, i);
  uint8_t col;
  if (list == kMetricList) {  // ISO M10, ISO M2.5
    const uint16_t d = flash_copy(&tables().iso.row[i].diameter_x10);
    col = s.number(0, s.text(0, 0, AM_TEXT("ISO M")), d % 10 ? d : d / 10, 0, d % 10 ? 1 : 0);
  } else {
    col = s.text(0, 0, list == kFeedList ? AM_TEXT("Feed") : AM_TEXT("Inch"));
  }
  s.blank(0, col);
  if (list == kInchList)
    col = s.text(1, s.number(1, 0, p * 5, 0, 1), AM_TEXT("tpi"));
  else
    col = s.text(1, s.number(1, 0, p, 0, 3), list == kFeedList ? AM_TEXT("mm/rev") : AM_TEXT("mm"));
  s.blank(1, col);
}

}  // namespace ui
}  // namespace am
