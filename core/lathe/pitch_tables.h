// Standard thread pitches and turning feeds, as plain data.
//
// Contract
//   Each table is a constexpr array of small integers (POD, no pointers), so
//   the AVR build can move it to flash with PROGMEM unchanged; the *_count
//   constants give the lengths. Hand is not in the tables: it is a flag on
//   the ThreadRequest (ratio.h), so a left-hand M10 is the same row.
//   Units: metric diameters in 0.1 mm, pitches in um (pitch_um()); inch
//   diameters in 0.0001 in, pitches as TPI x 2 (pitch_tpi_x2(), so 4.5 TPI is
//   exact); feeds in um per spindle turn.
//
// Contents
//   kIsoCoarse / kIsoFine: the diameter-pitch pairs of ISO 261 that ISO 262
//     selects for bolts and nuts, M1 to M64 (first and second choice sizes),
//     coarse and fine. ISO 261 lists further fine pitches (e.g. M6 x 0.75);
//     any pitch can still be requested directly in um.
//   kUnc / kUnf: the Unified coarse (#1 to 4 in) and fine (#0 to 1 1/2 in)
//     series.
//   kCommonTpi: inch pitches a lathe's change-gear chart carries, 4 to 80
//     TPI, including 4.5, 11.5 (NPT 1 to 2 in), 19 (BSP 1/4 and 3/8 in)
//     and 27 (NPT 1/8 in).
//   kTurningFeeds: longitudinal feeds 0.02 to 0.50 mm per turn, including
//     the seed's fine (0.04) and coarse (0.08) feeds.
#pragma once
#include <stddef.h>
#include <stdint.h>

namespace am {

struct MetricThread {
  uint16_t diameter_x10;  // nominal diameter, 0.1 mm
  uint16_t pitch_um;
};

struct InchThread {
  uint16_t diameter_x10000;  // basic major diameter, 0.0001 in
  uint8_t tpi_x2;            // threads per inch x 2
};

constexpr MetricThread kIsoCoarse[] = {
    {10, 250},   {12, 250},   {14, 300},   {16, 350},   {18, 350},   {20, 400},   {25, 450},
    {30, 500},   {35, 600},   {40, 700},   {50, 800},   {60, 1000},  {70, 1000},  {80, 1250},
    {100, 1500}, {120, 1750}, {140, 2000}, {160, 2000}, {180, 2500}, {200, 2500}, {220, 2500},
    {240, 3000}, {270, 3000}, {300, 3500}, {330, 3500}, {360, 4000}, {390, 4000}, {420, 4500},
    {450, 4500}, {480, 5000}, {520, 5000}, {560, 5500}, {600, 5500}, {640, 6000},
};

constexpr MetricThread kIsoFine[] = {
    {80, 1000},  {100, 1250}, {100, 1000}, {120, 1500}, {120, 1250}, {140, 1500}, {160, 1500},
    {180, 2000}, {180, 1500}, {200, 2000}, {200, 1500}, {220, 2000}, {220, 1500}, {240, 2000},
    {270, 2000}, {300, 2000}, {330, 2000}, {360, 3000}, {390, 3000}, {420, 3000}, {450, 3000},
    {480, 3000}, {520, 4000}, {560, 4000}, {600, 4000}, {640, 4000},
};

constexpr InchThread kUnc[] = {
    {730, 128}, {860, 112}, {990, 96}, {1120, 80}, {1250, 80}, {1380, 64},
    {1640, 64}, {1900, 48}, {2160, 48}, {2500, 40}, {3125, 36}, {3750, 32},
    {4375, 28}, {5000, 26}, {5625, 24}, {6250, 22}, {7500, 20}, {8750, 18},
    {10000, 16}, {11250, 14}, {12500, 14}, {13750, 12}, {15000, 12}, {17500, 10},
    {20000, 9}, {22500, 9}, {25000, 8}, {27500, 8}, {30000, 8}, {32500, 8},
    {35000, 8}, {37500, 8}, {40000, 8},
};

constexpr InchThread kUnf[] = {
    {600, 160}, {730, 144}, {860, 128}, {990, 112}, {1120, 96}, {1250, 88},
    {1380, 80}, {1640, 72}, {1900, 64}, {2160, 56}, {2500, 56}, {3125, 48},
    {3750, 48}, {4375, 40}, {5000, 40}, {5625, 36}, {6250, 36}, {7500, 32},
    {8750, 28}, {10000, 24}, {11250, 24}, {12500, 24}, {13750, 24}, {15000, 24},
};

constexpr uint8_t kCommonTpi[] = {  // x 2
    8,  9,  10, 12, 14, 16, 18, 20, 22, 23, 24, 26, 28,  32,  36,  38,
    40, 44, 48, 52, 54, 56, 64, 72, 80, 88, 96, 112, 128, 144, 160,
};

constexpr uint16_t kTurningFeeds[] = {  // um per spindle turn
    20, 30, 40, 50, 60, 80, 100, 120, 150, 180, 200, 250, 300, 350, 400, 500,
};

constexpr size_t kIsoCoarseCount = sizeof(kIsoCoarse) / sizeof(kIsoCoarse[0]);
constexpr size_t kIsoFineCount = sizeof(kIsoFine) / sizeof(kIsoFine[0]);
constexpr size_t kUncCount = sizeof(kUnc) / sizeof(kUnc[0]);
constexpr size_t kUnfCount = sizeof(kUnf) / sizeof(kUnf[0]);
constexpr size_t kCommonTpiCount = sizeof(kCommonTpi) / sizeof(kCommonTpi[0]);
constexpr size_t kTurningFeedsCount = sizeof(kTurningFeeds) / sizeof(kTurningFeeds[0]);

}  // namespace am
