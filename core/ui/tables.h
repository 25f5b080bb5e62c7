// The pitch tables the operator steps through on the pitch entry, as flash
// copies of core/lathe's arrays.
//
// Contract
//   Three lists, in the order of the entries that use them (workflow.h):
//   kFeedList (turning feeds, um per turn), kMetricList (the ISO coarse
//   pitches, um, ascending, a pitch repeated for each size that has it),
//   kInchList (the common TPI, which hold every UNC and UNF pitch, in 0.1
//   TPI). list_size(list) rows each; table_value(list, i) is row i in the
//   entry's own units (um, 0.1 TPI), so a picked row is typed into the entry
//   as a number and read back exactly. ISO fine, UNC and UNF and the
//   sizes' names are left out of the image for flash: their pitches are all
//   in these lists, and any pitch can be typed.
#pragma once
#include <stdint.h>

#include "../lathe/pitch_tables.h"
#include "flash.h"

namespace am {
namespace ui {

enum List : uint8_t { kFeedList, kMetricList, kInchList };

template <size_t... I>
constexpr FlashRows<uint16_t, sizeof...(I)> iso_pitches(Indices<I...>) {
  return {{kIsoCoarse[I].pitch_um...}};
}

struct Tables {
  FlashRows<uint16_t, kTurningFeedsCount> feeds;
  FlashRows<uint16_t, kIsoCoarseCount> iso;
  FlashRows<uint8_t, kCommonTpiCount> tpi;
};

inline const Tables& tables() {
  static const Tables kTables AM_FLASH = {flash_rows(kTurningFeeds),
                                          iso_pitches(MakeIndices<kIsoCoarseCount>::type()), flash_rows(kCommonTpi)};
  return kTables;
}

inline uint8_t list_size(List list) {
  return list == kFeedList ? uint8_t(kTurningFeedsCount)
         : list == kMetricList ? uint8_t(kIsoCoarseCount)
                               : uint8_t(kCommonTpiCount);
}

inline uint16_t table_value(List list, uint8_t i) {
  const Tables& t = tables();
  return list == kFeedList ? flash_copy(&t.feeds.row[i])
         : list == kMetricList ? flash_copy(&t.iso.row[i])
                               : uint16_t(flash_copy(&t.tpi.row[i]) * 5);
}

}  // namespace ui
}  // namespace am
