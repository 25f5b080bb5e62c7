// The pitch tables the operator picks from, as flash copies of core/lathe's
// arrays, and one row of them as a pitch and a two-line description.
//
// Contract
//   Three lists: kFeedList (turning feeds, mm per turn), kMetricList (ISO
//   coarse, then ISO fine), kInchList (UNC, UNF, then the common TPI).
//   list_size(list) rows each; list_pitch(list, i) is row i's pitch, exact
//   (core/lathe/ratio.h's Pitch); draw_row(screen, list, i) writes its
//   description on row 0 and its pitch and "i/n" on row 1.
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
  FlashRows<MetricThread, kIsoCoarseCount> iso_coarse;
  FlashRows<MetricThread, kIsoFineCount> iso_fine;
  FlashRows<InchThread, kUncCount> unc;
  FlashRows<InchThread, kUnfCount> unf;
  FlashRows<uint8_t, kCommonTpiCount> tpi;
};

inline const Tables& tables() {
  static const Tables kTables AM_FLASH = {flash_rows(kTurningFeeds), flash_rows(kIsoCoarse), flash_rows(kIsoFine),
                                          flash_rows(kUnc),          flash_rows(kUnf),       flash_rows(kCommonTpi)};
  return kTables;
}

inline uint8_t list_size(List list) {
  return list == kFeedList ? uint8_t(kTurningFeedsCount)
         : list == kMetricList ? uint8_t(kIsoCoarseCount + kIsoFineCount)
                               : uint8_t(kUncCount + kUnfCount + kCommonTpiCount);
}

// Row i of a list: its series text, diameter (0.1 mm or 0.0001 in, 0 for
// none) and pitch (um, or TPI x 2).
struct Row {
  const char* series;
  uint16_t diameter;
  uint16_t pitch;
};

inline Row list_row(List list, uint8_t i) {
  static const char kFeed[] AM_FLASH = "Feed";
  static const char kIso[] AM_FLASH = "ISO M";
  static const char kIsoFine[] AM_FLASH = "ISO fine M";
  static const char kUncText[] AM_FLASH = "UNC ";
  static const char kUnfText[] AM_FLASH = "UNF ";
  static const char kTpiText[] AM_FLASH = "Inch";
  const Tables& t = tables();
  if (list == kFeedList) return {kFeed, 0, flash_copy(&t.feeds.row[i])};
  if (list == kMetricList) {
    const bool fine = i >= kIsoCoarseCount;
    const MetricThread m = fine ? flash_copy(&t.iso_fine.row[i - kIsoCoarseCount]) : flash_copy(&t.iso_coarse.row[i]);
    return {fine ? kIsoFine : kIso, m.diameter_x10, m.pitch_um};
  }
  if (i < kUncCount + kUnfCount) {
    const bool fine = i >= kUncCount;
    const InchThread m = fine ? flash_copy(&t.unf.row[i - kUncCount]) : flash_copy(&t.unc.row[i]);
    return {fine ? kUnfText : kUncText, m.diameter_x10000, m.tpi_x2};
  }
  return {kTpiText, 0, flash_copy(&t.tpi.row[i - kUncCount - kUnfCount])};
}

inline Pitch list_pitch(List list, uint8_t i) {
  const Row r = list_row(list, i);
  return list == kInchList ? pitch_tpi_x2(r.pitch) : pitch_um(r.pitch);
}

inline void draw_row(Screen& s, List list, uint8_t i) {
  const Row r = list_row(list, i);
  uint8_t col = s.text(0, 0, r.series);
  if (list == kMetricList)  // M10, M2.5
    col = s.number(0, col, r.diameter % 10 ? r.diameter : r.diameter / 10, 0, r.diameter % 10 ? 1 : 0);
  else if (r.diameter)
    col = s.text(0, s.number(0, col, r.diameter, 0, 4), AM_TEXT("in"));
  s.blank(0, col);
  if (list == kInchList)
    col = s.text(1, s.number(1, 0, r.pitch * 5, 0, 1), AM_TEXT("tpi"));
  else
    col = s.text(1, s.number(1, 0, r.pitch, 0, 3), list == kFeedList ? AM_TEXT("mm/rev") : AM_TEXT("mm"));
  s.blank(1, col, 11);
  s.number(1, 11, i + 1, 2, 0);
  s.put(1, 13, '/');
  s.number(1, 14, list_size(list), 2, 0);
}

}  // namespace ui
}  // namespace am
