// The machine settings a CNC or printer image keeps in its EEPROM (issue 9;
// docs/settings.md): one block of whole numbers with a tag, a version and a
// checksum, the table of settings with grbl's numbers, each one's unit and
// range, and the conversions from the user's millimetres to the engine's
// steps. Hardware-free: the firmware (firmware/services/settings.*) reads
// and writes the block and applies it; host-tested in
// tests/host/test_settings.cpp.
//
// Contract
//   Layout<Axes, SwitchMask, Parts> lists the settings of a board with
//   `Axes` axes, endstops on the axes of `SwitchMask` (bit i: axis i) and
//   the optional parts of `Parts` (kHeaterGains, kPinPolarities,
//   kPathAccels, kRetraction; or-ed), in grbl's numeric order (Kind's
//   order):
//     $3         direction invert mask, 0 .. 2^Axes - 1 (kPinPolarities)
//     $5         limit pins invert, 0/1          (kPinPolarities, endstops)
//     $11        junction deviation, mm            0.001 .. 10
//     $20        soft limits, 0/1                  (with endstops)
//     $21        hard limits, 1, read-only         (with endstops)
//     $22        homing, 0/1                       (with endstops)
//     $23        homing direction invert mask, read-only (with endstops)
//     $100+a     steps/mm of axis a                1 .. 10000
//     $110+a     max rate, mm/min                  1 .. 1000000
//     $120+a     acceleration, mm/s^2              1 .. 1000000
//     $130+a     max travel, mm (axis a's switch)  1 .. 100000
//     $200       the protocol style, 0 grbl, 1 Marlin
//     $210..212  M204's path accelerations P, T, R, mm/s^2, 0 .. 1000000
//                (0: none beyond the axes' own)       (kPathAccels)
//     $220..224  M207's length, feed, hop and M208's extra, feed: mm 0 .. 100,
//                mm/min 0.001 .. 100000               (kRetraction)
//     $240+a     homing locate feed, mm/min        1 .. 1000000
//     $250+a     homing seek feed, mm/min          1 .. 1000000
//     $270+a     homing pull-off, mm               0 .. 1000
//     $300..302  the heater's PID gains P, I, D    0 .. 1000, 0 .. 1000, 0 .. 10000
//                                                   (kHeaterGains)
//   (grbl has one $24/$25/$27 for every axis; the boards home Z slower than
//   X and Y, so here each switch's axis has its own, grbl's number times ten
//   plus the axis.) Every value is a uint32_t: thousandths of its unit for
//   the measures (parsed and printed with three decimals, rounded half away
//   from zero by core/text/fixed_number.h), the number itself for flags and
//   masks. count() entries; at(i) the i-th, find(number) its index or -1;
//   first(kind) the index of a kind's first entry (then one per axis, or
//   per switch in the switches' order).
//
//   Block<Count> is what the EEPROM holds: a Header (kTag, the version, the
//   count), the values in the layout's order and a checksum over all that
//   (a 16-bit rotate-and-xor: any one changed byte changes it). seal()
//   writes header and sum; examine() says what a block read back is: ok,
//   blank (no tag: an erased EEPROM or something else's bytes), older (the
//   tag with another version or count: another firmware's layout; not
//   trusted further) or corrupt (the sum is wrong, or a value out of its
//   range or beyond the engine's limits: validate()).
//
//   Engine limits: the rates and accelerations in steps are what the
//   engine runs, and must stay within the board's (EngineLimits: each
//   axis's top step rate, the top acceleration). validate() checks every
//   value's range and every derived figure: max rate 1 .. max_rate[a]
//   steps/s, acceleration 2 .. max_accel steps/s^2 (the first step from
//   rest must fit a segment), a homing feed 1 .. min(65535, max_rate[a])
//   steps/s, a pull-off at most 65535 steps, a travel 1 .. 2^31 - 1 steps.
//   set(block, number, text, limits) parses `text` as setting `number`
//   (a flag or mask is whole: no decimal point) and stores it when the
//   whole block still validates; on any error the
//   block is unchanged (Error says why: unknown, read_only, bad_number,
//   out_of_range, engine_limit). A steps/mm change is checked against the
//   rates and accelerations it makes.
//
//   Conversions (64-bit, rounded to nearest; steps_per_m is thousandths of
//   steps/mm, the board descriptor's unit): rate_steps() mm/min -> steps/s,
//   accel_steps() mm/s^2 -> steps/s^2, length_steps() mm -> steps, each
//   0xFFFFFFFF beyond 2^31 - 1; and back, for the defaults: rate_mm(),
//   accel_mm(), length_mm().
#pragma once
#include <stdint.h>

#include "../text/fixed_number.h"

namespace am {
namespace settings {

enum class Kind : uint8_t {
  dir_invert, limit_invert, junction, soft_limits, hard_limits, homing, homing_dir, steps, rate, accel, travel, protocol,
  path_accel, retract_length, retract_feed, retract_hop, recover_extra, recover_feed, locate, seek, pull_off, gain_p,
  gain_i, gain_d, end
};

struct Entry {
  Kind kind;
  uint8_t axis;  // for the per-axis kinds (M204's: its slot P, T, R); 0 otherwise
};

// The tables below stay in flash on the AVR: the firmware defines
// AM_SETTINGS_FLASH as PROGMEM and AM_SETTINGS_BYTE(p) as pgm_read_byte(p)
// before including this header (firmware/services/settings.cpp).
#ifndef AM_SETTINGS_FLASH
#define AM_SETTINGS_FLASH
#endif
#ifndef AM_SETTINGS_BYTE
#define AM_SETTINGS_BYTE(p) (*(p))
#endif

// Per kind, in flash: grbl's number (less the axis), low byte and high
// byte, and one byte of traits: bit 7 read-only, bit 6 whole (no
// decimals), bits 4-5 the least value (0, 1 or 1000), bits 0-3 the power
// of ten that is the greatest (15: none, 0xFFFFFFFF). One table and a few
// reads instead of a comparison chain per trait.
template <bool = true>
struct KindRows {
  static constexpr uint8_t kReadOnly = 0x80, kWhole = 0x40, kNoMax = 0x0F;
  static const uint8_t row[uint8_t(Kind::end)][3];
};
// (270 = 14 + 256, 300..302 = 44..46 + 256; $3's greatest, 100, is above
// every mask: validate() holds it within the axes.) A template's member:
// one copy in the image, defined in the header.
template <bool B>
const uint8_t KindRows<B>::row[uint8_t(Kind::end)][3] AM_SETTINGS_FLASH = {
    {3, 0, 0x42},   {5, 0, 0x40},   {11, 0, 0x14},  {20, 0, 0x40},  {21, 0, 0xCF},  {22, 0, 0x40},
    {23, 0, 0xCF},  {100, 0, 0x27}, {110, 0, 0x29}, {120, 0, 0x29}, {130, 0, 0x28}, {200, 0, 0x40},
    {210, 0, 0x09}, {220, 0, 0x05}, {221, 0, 0x18}, {222, 0, 0x05}, {223, 0, 0x05}, {224, 0, 0x18},
    {240, 0, 0x29}, {250, 0, 0x29}, {14, 1, 0x06},  {44, 1, 0x06},  {45, 1, 0x06},  {46, 1, 0x07}};
using KindTable = KindRows<>;
inline uint8_t traits(Kind k) { return AM_SETTINGS_BYTE(&KindTable::row[uint8_t(k)][2]); }

[[gnu::noinline]] inline uint16_t number(Entry e) {
  const uint8_t* r = KindTable::row[uint8_t(e.kind)];
  return uint16_t((AM_SETTINGS_BYTE(r) | AM_SETTINGS_BYTE(r + 1) << 8) + e.axis);
}

// Three decimals for the measures, none for flags, masks and the protocol.
inline uint8_t digits(Kind k) { return traits(k) & KindTable::kWhole ? 0 : 3; }

inline bool read_only(Kind k) { return traits(k) & KindTable::kReadOnly; }

struct Range {
  uint32_t min, max;
};
// The range a value may be set to (a read-only one's: anything, it is not
// settable), from the kind's traits.
inline uint32_t range_min(Kind k) {
  const uint8_t m = traits(k) >> 4 & 3;
  return m == 2 ? 1000 : m;
}
inline uint32_t range_max(Kind k) {
  uint8_t e = traits(k) & 0x0F;
  if (e == KindTable::kNoMax) return 0xFFFFFFFFu;
  uint32_t r = 1;
  while (e--) r *= 10;
  return r;
}
[[gnu::noinline]] inline bool in_range(Kind k, uint32_t v) {
  const uint8_t t = traits(k), m = t >> 4 & 3;
  if (v < (m == 2 ? 1000u : m)) return false;
  uint8_t e = t & 0x0F;
  if (e == KindTable::kNoMax) return true;
  uint32_t r = 1;
  while (e--) r *= 10;
  return v <= r;
}
inline Range range(Kind k) { return Range{range_min(k), range_max(k)}; }

// round(v * steps_per_m / div) (v in thousandths of the unit): false when
// it exceeds 2^31 - 1. One out-of-line copy of the 64-bit arithmetic on the
// AVR (core/text/fixed_number.h's scale_round()).
inline bool to_steps(uint32_t v, uint32_t steps_per_m, uint32_t div, uint32_t& out) {
  int32_t r;
  if (!scale_round(int32_t(v), steps_per_m, div, r)) return false;
  out = uint32_t(r);
  return true;
}
constexpr uint32_t kPerRate = 60000000ul, kPerLength = 1000000ul;  // mm/min and mm (or mm/s^2)
// What the engine runs: steps/s, steps/s^2, steps (0xFFFFFFFF beyond 2^31 - 1).
inline uint32_t rate_steps(uint32_t mm_per_min, uint32_t steps_per_m) {
  uint32_t s;
  return to_steps(mm_per_min, steps_per_m, kPerRate, s) ? s : 0xFFFFFFFFu;
}
inline uint32_t length_steps(uint32_t mm, uint32_t steps_per_m) {
  uint32_t s;
  return to_steps(mm, steps_per_m, kPerLength, s) ? s : 0xFFFFFFFFu;
}
inline uint32_t accel_steps(uint32_t mm_per_s2, uint32_t steps_per_m) { return length_steps(mm_per_s2, steps_per_m); }
// And back, for the defaults: the board's figure in the settings' unit,
// rounded to the nearest thousandth (0xFFFFFFFF beyond 2^31 - 1). Back in
// steps it is the board's figure again whenever 0.0005 of the unit is less
// than half a step (every board here: 1000 steps/mm, exact).
inline uint32_t rate_mm(uint32_t steps_per_s, uint32_t steps_per_m) {
  uint32_t v;
  return to_steps(steps_per_s, kPerRate, steps_per_m, v) ? v : 0xFFFFFFFFu;
}
inline uint32_t length_mm(uint32_t steps, uint32_t steps_per_m) {
  uint32_t v;
  return to_steps(steps, kPerLength, steps_per_m, v) ? v : 0xFFFFFFFFu;
}
inline uint32_t accel_mm(uint32_t steps_per_s2, uint32_t steps_per_m) { return length_mm(steps_per_s2, steps_per_m); }

template <uint8_t Axes>
struct EngineLimits {
  uint32_t max_rate[Axes];  // steps/s
  uint32_t max_accel;       // steps/s^2
};

constexpr uint16_t kTag = 0x5E77;

struct Header {
  uint16_t tag;
  uint8_t version;
  uint8_t count;
};

template <uint8_t Count>
struct Block {
  Header header;
  uint32_t value[Count];
  uint16_t sum;
  // The bytes the sum covers: header and values (the host pads the struct).
  static constexpr uint16_t kSummed = uint16_t(sizeof(Header) + 4 * Count);
};

inline uint16_t checksum(const void* bytes, uint16_t n) {
  const uint8_t* b = static_cast<const uint8_t*>(bytes);
  uint16_t sum = 0x5A5A;
  for (uint16_t i = 0; i < n; ++i) sum = uint16_t((sum << 1 | sum >> 15) ^ b[i]);
  return sum;
}

enum class Loaded : uint8_t { ok, blank, older, corrupt };
enum class Error : uint8_t { none, unknown, read_only, bad_number, out_of_range, engine_limit };

constexpr uint8_t bit_count(uint8_t m) { return m ? uint8_t((m & 1) + bit_count(uint8_t(m >> 1))) : 0; }

// The optional parts of a layout (Layout's Parts, or-ed).
constexpr uint8_t kHeaterGains = 1, kPinPolarities = 2, kPathAccels = 4, kRetraction = 8;

template <uint8_t Axes, uint8_t SwitchMask, uint8_t Parts>
struct Layout {
  static constexpr uint8_t kSwitches = bit_count(SwitchMask);
  static constexpr bool has(uint8_t part) { return (Parts & part) != 0; }

  static constexpr uint8_t multiplicity(Kind k) {
    return k == Kind::dir_invert                                         ? (has(kPinPolarities) ? 1 : 0)
           : k == Kind::limit_invert                                     ? (has(kPinPolarities) && kSwitches ? 1 : 0)
           : k == Kind::junction || k == Kind::protocol                  ? 1
           : k <= Kind::homing_dir                                       ? (kSwitches ? 1 : 0)
           : k == Kind::steps || k == Kind::rate || k == Kind::accel     ? Axes
           : k == Kind::path_accel                                       ? (has(kPathAccels) ? 3 : 0)
           : k >= Kind::retract_length && k <= Kind::recover_feed        ? (has(kRetraction) ? 1 : 0)
           : k == Kind::travel || k == Kind::locate || k == Kind::seek || k == Kind::pull_off ? kSwitches
           : k < Kind::end                                               ? (has(kHeaterGains) ? 1 : 0)
                                                                         : 0;
  }
  static constexpr uint8_t count(uint8_t k = 0) {
    return k == uint8_t(Kind::end) ? 0 : uint8_t(multiplicity(Kind(k)) + count(uint8_t(k + 1)));
  }
  static constexpr uint8_t kCount = count();  // a constant: -Os calls a constexpr function at run time
  using Values = Block<kCount>;

  // The j-th axis of a kind: every axis, or the j-th with a switch.
  static constexpr uint8_t nth_switch(uint8_t j, uint8_t a = 0) {
    return (SwitchMask >> a & 1) ? (j == 0 ? a : nth_switch(uint8_t(j - 1), uint8_t(a + 1)))
                                 : nth_switch(j, uint8_t(a + 1));
  }
  static constexpr uint8_t axis_of(Kind k, uint8_t j) {
    return k == Kind::steps || k == Kind::rate || k == Kind::accel || k == Kind::path_accel ? j
           : k == Kind::travel || k == Kind::locate || k == Kind::seek || k == Kind::pull_off ? nth_switch(j)
                                                                                               : 0;
  }
  static constexpr Entry entry(uint8_t i, uint8_t k = 0) {
    return i < multiplicity(Kind(k)) ? Entry{Kind(k), axis_of(Kind(k), i)}
                                     : entry(uint8_t(i - multiplicity(Kind(k))), uint8_t(k + 1));
  }
  // Every entry, made at compile time and kept in flash (two bytes each):
  // at(i) reads its row.
  template <uint8_t... I>
  struct Rows {
    static const uint8_t row[sizeof...(I) ? sizeof...(I) : 1][2];
  };
  template <uint8_t N, uint8_t... I>
  struct MakeRows : MakeRows<uint8_t(N - 1), uint8_t(N - 1), I...> {};
  template <uint8_t... I>
  struct MakeRows<0, I...> {
    using type = Rows<I...>;
  };
  using Entries = typename MakeRows<count()>::type;

  static Entry at(uint8_t i) {
    const uint8_t* r = Entries::row[i];
    return Entry{Kind(AM_SETTINGS_BYTE(r)), AM_SETTINGS_BYTE(r + 1)};
  }

  // The index of a kind's first entry: then axis a's (steps, rate, accel:
  // first + a) or switch k's (travel, locate, seek, pull-off: first + k).
  static constexpr uint8_t first(Kind kind, uint8_t k = 0) {
    return k == uint8_t(kind) ? 0 : uint8_t(multiplicity(Kind(k)) + first(kind, uint8_t(k + 1)));
  }

  static int16_t find(uint16_t n) {
    for (uint8_t i = 0; i < kCount; ++i)
      if (number(at(i)) == n) return i;
    return -1;
  }

  static void seal(Values& b, uint8_t version) {
    b.header = Header{kTag, version, kCount};
    b.sum = checksum(&b, Values::kSummed);
  }

  // Every value within its range and every derived figure within the
  // engine's limits. (The kinds a layout lacks are left out at compile
  // time: the entries come from the flash table.)
  static Error validate(const Values& b, const EngineLimits<Axes>& limits) {
    for (uint8_t i = 0; i < kCount; ++i) {
      const Entry e = at(i);
      const Kind k = e.kind;
      const uint32_t v = b.value[i];
      if (!in_range(k, v) || (has(kPinPolarities) && k == Kind::dir_invert && v >> Axes)) return Error::out_of_range;
      if (k < Kind::rate || (k >= Kind::protocol && k < Kind::locate) || k >= Kind::gain_p) continue;
      constexpr uint8_t steps = first(Kind::steps);
      const uint32_t spm = b.value[steps + e.axis];
      uint32_t lo = 1, hi = limits.max_rate[e.axis], div = kPerLength;  // accel's scale is a length's
      if (k == Kind::accel) {
        lo = 2;  // the first step from rest must fit a segment
        hi = limits.max_accel;
      } else if (kSwitches && k == Kind::travel) {
        hi = 0x7FFFFFFFu;
      } else if (kSwitches && k == Kind::pull_off) {
        lo = 0;
        hi = 0xFFFFu;
      } else {  // rate, locate, seek: per minute
        div = kPerRate;
        if (kSwitches && k != Kind::rate && hi > 0xFFFFu) hi = 0xFFFFu;
      }
      uint32_t s;
      if (!to_steps(v, spm, div, s) || s < lo || s > hi) return Error::engine_limit;
    }
    return Error::none;
  }

  static Loaded examine(const Values& b, uint8_t version, const EngineLimits<Axes>& limits) {
    if (b.header.tag != kTag) return Loaded::blank;
    if (b.header.version != version || b.header.count != kCount) return Loaded::older;
    if (b.sum != checksum(&b, Values::kSummed) || validate(b, limits) != Error::none) return Loaded::corrupt;
    return Loaded::ok;
  }

  // Setting `n` to the number at `text` (the rest of the line: nothing may
  // follow the number), or with `per_second` 60 times it (Marlin's M203
  // gives mm/s for a setting in mm/min). The header and sum are left to
  // seal().
  static Error set(Values& b, uint16_t n, const char* text, const EngineLimits<Axes>& limits, bool per_second = false) {
    const int16_t i = find(n);
    if (i < 0) return Error::unknown;
    const Kind k = at(uint8_t(i)).kind;
    if (read_only(k)) return Error::read_only;
    int32_t v;
    bool point = false;
    const NumberStatus s = parse_fixed(text, digits(k), v, point);
    if (s == NumberStatus::bad || (s == NumberStatus::ok && (*text != '\0' || (point && !digits(k)))))
      return Error::bad_number;
    if (s != NumberStatus::ok || v < 0 || (per_second && v > 0x7FFFFFFF / 60)) return Error::out_of_range;
    if (per_second) v *= 60;
    if (!in_range(k, uint32_t(v))) return Error::out_of_range;
    const uint32_t was = b.value[i];
    b.value[i] = uint32_t(v);
    const Error e = validate(b, limits);
    if (e != Error::none) b.value[i] = was;
    return e;
  }
};

template <uint8_t Axes, uint8_t SwitchMask, uint8_t Parts>
template <uint8_t... I>
const uint8_t Layout<Axes, SwitchMask, Parts>::Rows<I...>::row[sizeof...(I) ? sizeof...(I) : 1][2] AM_SETTINGS_FLASH = {
    {uint8_t(entry(I).kind), entry(I).axis}...};

// `$<number>=<value>` into buf (at least 20 bytes): the value in its
// kind's decimals. Returns the length.
inline uint8_t format(char* buf, Entry e, uint32_t v) {
  uint8_t n = 0;
  buf[n++] = '$';
  n = uint8_t(n + format_fixed(buf + n, number(e), 0));
  buf[n++] = '=';
  return uint8_t(n + format_fixed(buf + n, int32_t(v), digits(e.kind)));
}

}  // namespace settings
}  // namespace am
