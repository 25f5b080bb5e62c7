// G-code line parser (RS274/NGC subset, docs/gcode.md): one assembled line in,
// one syntactically valid block out. What the block means for the machine is
// the interpreter's business (gcode_interpreter.h); this layer only knows the
// grammar and which codes exist, so it can reject every malformed line before
// anything is decided on it.
//
// Contract
//   parse_gcode(line, block[, end]) reads the line up to its NUL (or up to
//   `end`, which must point at a character that is not a digit or '.', such
//   as the '*' that split_checksum() found) and returns GcodeError::none with
//   `block` filled, or the first error found from the left; on an error
//   `block` is unspecified. It reads nothing past the NUL / `end` and writes
//   nothing outside `block`; it keeps no state of its own. parse_gcode<false>
//   knows none of the printer's codes (M3 M5 M73 M201 M203 M204 M205 M220
//   M221: unsupported_code), for an image that has none of them;
//   parse_gcode<P, true> knows the firmware retraction's G10 G11 M207 M208
//   (unsupported_code otherwise).
//
//   Grammar: words are a letter (either case) and a number, blanks (space,
//   tab) allowed between words and between the letter and its number, none
//   needed ("G1X10Y-2.5" is three words), none after a sign; numbers as
//   parse_fixed() reads them (fixed_number.h: no exponent, so "X1e5" is X1
//   and E5), kept in 1/10000 (X1.5 -> 15000). "( ... )" is a comment
//   (no '(' inside, must close on the line); ';' comments out the rest of the
//   line; a line holding only '%' is empty (program delimiter). An empty or
//   comment-only line is a valid block with nothing in it.
//
//   Word letters: G and M (codes; several on a line, at most one per modal
//   group), N (line number: a whole number 0..2^31-1, first word of the line,
//   kept as an integer, not in 1/10000), and the value words A B C E F I J K
//   D P R S U X Y Z, each at most once. Every other letter is
//   unsupported_word (T, Q, L, H, O, V, W: no supported code uses them). The letters
//   X Y Z E U A B C are axis words; which of them exist is the board's matter
//   (the interpreter checks).
//
//   Codes and groups (kept as GcodeCode per GcodeGroup in the block):
//     motion    G0 G1 G2 G3         plane     G17 G18 G19
//     distance  G90 G91             units     G20 G21
//     feed mode G94                 non-modal G4 G28 G92 (G10 G11)
//     stop      M2 M30              extruder  M82 M83
//     machine   M17 M18 M84 M114 M350 M999, and the heater's M104 M105
//               M108 M109 M155 M301 M303 (gcode_interpreter.h: heater codes)
//   Code numbers are whole numbers without a decimal point ("G01" is G1);
//   anything else ("G30", "G1.0", "G92.1", "M106") is unsupported_code.
//
// Layering of Marlin line numbers and checksums: split_checksum(line, end)
// checks and cuts off a trailing "*<0..255>" (the XOR of every byte before the
// '*'); the caller then parses up to `end` and finds the N word in the block.
// Expected-line-number tracking (M110, resend requests) belongs to that
// caller. grbl '$' lines never reach this parser ('$' is bad_character here):
// the protocol routes them by their first character.
//
// Error messages: gcode_error_message(e) returns a short text per error. On
// the AVR define AM_TEXT(s) as PSTR(s) (after <avr/pgmspace.h>) before
// including this header so the texts stay in flash (by default they are plain
// string literals, which avr-gcc copies to RAM), or build a PROGMEM table from
// the AM_GCODE_ERRORS(X) list (name, text) below.
#pragma once
#include <stddef.h>
#include <stdint.h>

#include "fixed_number.h"

#ifndef AM_TEXT
#define AM_TEXT(s) (s)
#endif

namespace am {

// Every error with its message, in the order of the error table
// (docs/gcode.md): parser errors first, then the interpreter's.
#define AM_GCODE_ERRORS(X)                                                   \
  X(none, "ok")                                                              \
  X(bad_character, "expected a word letter")                                 \
  X(bad_comment, "comment not closed")                                       \
  X(unsupported_word, "unsupported word letter")                             \
  X(bad_number, "bad number")                                                \
  X(out_of_range, "number out of range")                                     \
  X(bad_line_number, "N must be first and a whole number")                   \
  X(unsupported_code, "unsupported G or M code")                             \
  X(modal_group_conflict, "two codes of one modal group")                    \
  X(repeated_word, "word given twice")                                       \
  X(no_such_axis, "no such axis on this board")                              \
  X(axis_conflict, "axis words wanted by two codes")                         \
  X(multiple_actions, "more than one action on the line")                    \
  X(missing_axis_word, "code needs an axis word")                            \
  X(missing_dwell_time, "G4 needs its time word")                            \
  X(missing_arc_words, "arc needs R or the plane's I/J/K")                   \
  X(arc_mixed_form, "arc takes R or I/J/K, not both")                        \
  X(unused_word, "word not used by any code on the line")                    \
  X(bad_feed, "feed rate must be above 0")                                   \
  X(arc_zero_radius, "arc radius is zero")                                   \
  X(arc_radius_mismatch, "arc end point not on the circle")                  \
  X(arc_radius_too_small, "arc radius too small for the end point")          \
  X(arc_full_circle_r, "R arc cannot end where it starts")                   \
  X(target_out_of_range, "target beyond the position range")                 \
  X(bad_mode, "mode must be 0, 1, 2, 16, 32 or 64")                          \
  X(axis_has_no_modes, "axis has no excitation modes")                       \
  X(mode_not_available, "mode not available on this axis")                   \
  X(arcs_not_here, "G2/G3 arcs are not in this board's image")             \
  X(no_heater, "this board has no heater")                                   \
  /* heater_code_alone .. bad_limit: only a board with a heater meets them */ \
  X(heater_code_alone, "heater code must be alone on the line")            \
  X(missing_temperature, "code needs S (M109: S or R)")                     \
  X(bad_temperature, "temperature must be 0 .. 260 C")                       \
  X(bad_interval, "M155 S must be whole seconds 0 .. 60")                    \
  X(bad_gains, "gains must be P, I 0 .. 1000, D 0 .. 10000")                \
  X(bad_cycles, "M303 C must be 3 .. 20")                                   \
  X(bad_percent, "M73 P 0 .. 100 and R in whole numbers, M220/M221 S 10 .. 500")\
  X(bad_limit, "M201/M203/M204 values above 0, M205 J 0.001 .. 10 mm")

#define AM_GCODE_ERROR_ENUM(name, text) name,
enum class GcodeError : uint8_t { AM_GCODE_ERRORS(AM_GCODE_ERROR_ENUM) };
#undef AM_GCODE_ERROR_ENUM

enum class GcodeGroup : uint8_t { motion, plane, distance, units, feed_mode, non_modal, stop, extruder, machine };
constexpr uint8_t kGcodeGroups = 9;

// Contiguous per group (gcode_group() relies on it).
enum class GcodeCode : uint8_t {
  none,
  g0, g1, g2, g3,       // motion
  g17, g18, g19,        // plane
  g90, g91,             // distance
  g20, g21,             // units
  g94,                  // feed mode
  g4, g10, g11, g28, g92,  // non-modal (G10/G11: firmware retraction, a printer's)
  m2, m30,              // stop
  m82, m83,             // extruder
  m17, m18, m84, m114, m350, m400, m999,  // machine
  m104, m105, m106, m107, m108, m109, m155, m301, m303, m500,  // machine: the heater's and the fan's (M500: the gains)
  m3, m5,                                   // machine: the seed's hot end on and off (a printer's)
  m73, m201, m203, m204, m205, m220, m221,  // machine: the printer's progress, limits, feed and flow
  m207, m208,                               // machine: the firmware retraction's settings
};

inline GcodeGroup gcode_group(GcodeCode c) {
  return c <= GcodeCode::g3    ? GcodeGroup::motion
         : c <= GcodeCode::g19 ? GcodeGroup::plane
         : c <= GcodeCode::g91 ? GcodeGroup::distance
         : c <= GcodeCode::g21 ? GcodeGroup::units
         : c <= GcodeCode::g94 ? GcodeGroup::feed_mode
         : c <= GcodeCode::g92 ? GcodeGroup::non_modal
         : c <= GcodeCode::m30 ? GcodeGroup::stop
         : c <= GcodeCode::m83 ? GcodeGroup::extruder
                               : GcodeGroup::machine;
}

// Bit (letter - 'A'), built from a byte: avr-gcc shifts a uint32 by a
// variable count one bit per loop turn (up to 25 turns for 'Z').
constexpr uint32_t gcode_letter_bit(char upper_letter) {
  return (upper_letter - 'A') < 8    ? uint32_t(uint8_t(1u << ((upper_letter - 'A') & 7)))
         : (upper_letter - 'A') < 16 ? uint32_t(uint8_t(1u << ((upper_letter - 'A') & 7))) << 8
         : (upper_letter - 'A') < 24 ? uint32_t(uint8_t(1u << ((upper_letter - 'A') & 7))) << 16
                                     : uint32_t(uint8_t(1u << ((upper_letter - 'A') & 7))) << 24;
}

constexpr uint32_t kGcodeAxisLetters = gcode_letter_bit('X') | gcode_letter_bit('Y') | gcode_letter_bit('Z') |
                                       gcode_letter_bit('E') | gcode_letter_bit('U') | gcode_letter_bit('A') |
                                       gcode_letter_bit('B') | gcode_letter_bit('C');
constexpr uint32_t kGcodeValueLetters = kGcodeAxisLetters | gcode_letter_bit('D') | gcode_letter_bit('F') |
                                        gcode_letter_bit('I') | gcode_letter_bit('J') | gcode_letter_bit('K') |
                                        gcode_letter_bit('N') | gcode_letter_bit('P') | gcode_letter_bit('Q') |
                                        gcode_letter_bit('R') | gcode_letter_bit('S') | gcode_letter_bit('T');

// A value letter's slot in GcodeBlock::value: how many value letters come
// before it (a constant where the letter is; the block is on the stack of
// every line, so it holds the 17 value letters, not all 26).
constexpr uint8_t gcode_value_slot(char upper_letter) {
  return uint8_t(__builtin_popcountl(kGcodeValueLetters & (gcode_letter_bit(upper_letter) - 1)));
}
constexpr uint8_t kGcodeValueSlots = gcode_value_slot('Z') + 1;

struct GcodeBlock {
  uint32_t words;                     // gcode_letter_bit() of every value word on the line
  int32_t value[kGcodeValueSlots];    // by gcode_value_slot(), valid where `words` has the bit; 1/10000 except N
  GcodeCode code[kGcodeGroups];       // by GcodeGroup; none when the line has no code of it

  bool has(char upper_letter) const { return (words & gcode_letter_bit(upper_letter)) != 0; }
  int32_t get(char upper_letter) const { return value[slot(upper_letter)]; }
  // Out of line: most letters are only known at run time (an axis table's).
  __attribute__((noinline)) static uint8_t slot(char upper_letter) { return gcode_value_slot(upper_letter); }
  GcodeCode group(GcodeGroup g) const { return code[uint8_t(g)]; }
};

namespace gcode_detail {

inline char upper(char c) { return (c >= 'a' && c <= 'z') ? char(c - 'a' + 'A') : c; }
inline bool blank(char c) { return c == ' ' || c == '\t'; }

// The code of G<n> / M<n>, none if unsupported. Comparisons,
// not a switch: a switch over results becomes a lookup table, which avr-gcc
// puts in RAM.
// Printer: the printer's codes (M3 M5 M73 M201 M203 M204 M205 M220 M221)
// too; a parser without them reads them as unsupported (and links none of
// their compares). Retract: the firmware retraction's G10 G11 M207 M208.
template <bool Printer, bool Retract>
GcodeCode code_of(char letter, int32_t number) {
  if (number < 0 || number > 999) return GcodeCode::none;
  const uint16_t n = uint16_t(number);  // 16-bit compares: half the code of 32-bit ones on the AVR
  if (letter == 'G') {
    if (n <= 3) return GcodeCode(uint8_t(GcodeCode::g0) + n);
    if (n == 4) return GcodeCode::g4;
    if (Retract && (n == 10 || n == 11)) return GcodeCode(uint8_t(GcodeCode::g10) + (n - 10));
    if (n == 28) return GcodeCode::g28;
    if (n >= 17 && n <= 19) return GcodeCode(uint8_t(GcodeCode::g17) + (n - 17));
    if (n == 20 || n == 21) return GcodeCode(uint8_t(GcodeCode::g20) + (n - 20));
    if (n == 90 || n == 91) return GcodeCode(uint8_t(GcodeCode::g90) + (n - 90));
    if (n == 92) return GcodeCode::g92;
    if (n == 94) return GcodeCode::g94;
    return GcodeCode::none;
  }
  if (n == 2) return GcodeCode::m2;
  if (n == 30) return GcodeCode::m30;
  if (n == 82 || n == 83) return GcodeCode(uint8_t(GcodeCode::m82) + (n - 82));
  if (n == 17 || n == 18) return GcodeCode(uint8_t(GcodeCode::m17) + (n - 17));
  if (n == 84) return GcodeCode::m84;
  if (n == 114) return GcodeCode::m114;
  if (n == 350) return GcodeCode::m350;
  if (n == 400) return GcodeCode::m400;
  if (n == 999) return GcodeCode::m999;
  if (n >= 104 && n <= 109) return GcodeCode(uint8_t(GcodeCode::m104) + (n - 104));
  if (n == 155) return GcodeCode::m155;
  if (n == 301) return GcodeCode::m301;
  if (n == 303) return GcodeCode::m303;
  if (n == 500) return GcodeCode::m500;
  if (Retract && (n == 207 || n == 208)) return GcodeCode(uint8_t(GcodeCode::m207) + (n - 207));
  if (!Printer) return GcodeCode::none;
  if (n == 3 || n == 5) return GcodeCode(uint8_t(GcodeCode::m3) + (n == 5));
  if (n == 73) return GcodeCode::m73;
  if (n >= 201 && n <= 205 && n != 202) return GcodeCode(uint8_t(GcodeCode::m201) + (n - 201 - (n > 202)));
  if (n == 220 || n == 221) return GcodeCode(uint8_t(GcodeCode::m220) + (n - 220));
  return GcodeCode::none;
}

}  // namespace gcode_detail

template <bool Printer = true, bool Retract = false>
GcodeError parse_gcode(const char* p, GcodeBlock& b, const char* end = nullptr) {
  using namespace gcode_detail;
  b.words = 0;
  for (uint8_t g = 0; g < kGcodeGroups; ++g) b.code[g] = GcodeCode::none;
  bool first_word = true;
  bool percent_ok = true;  // '%' is accepted as the only thing on the line
  for (;;) {
    char c = p == end ? '\0' : *p;
    if (blank(c)) {
      ++p;
      continue;
    }
    if (c == '\0' || c == ';') return GcodeError::none;
    if (c == '(') {
      do {
        ++p;
        c = p == end ? '\0' : *p;
        if (c == '\0' || c == '(') return GcodeError::bad_comment;
      } while (c != ')');
      ++p;
      continue;
    }
    if (c == '%' && percent_ok) {
      const char* q = p + 1;
      while (q != end && blank(*q)) ++q;
      if (q == end || *q == '\0') return GcodeError::none;
    }
    percent_ok = false;
    const char letter = upper(c);
    if (letter < 'A' || letter > 'Z') return GcodeError::bad_character;
    const bool is_code = letter == 'G' || letter == 'M';
    if (!is_code && !(kGcodeValueLetters & gcode_letter_bit(letter))) return GcodeError::unsupported_word;
    ++p;
    while (p != end && blank(*p)) ++p;
    const bool line_number = letter == 'N';
    const bool whole = is_code || line_number;  // kept as integers
    int32_t v;
    bool had_point;
    const NumberStatus ns = parse_fixed(p, whole ? 0 : kLengthDigits, v, had_point);
    if (ns == NumberStatus::bad) return GcodeError::bad_number;
    if (ns == NumberStatus::out_of_range) return GcodeError::out_of_range;
    if (line_number && (!first_word || had_point || v < 0)) return GcodeError::bad_line_number;
    first_word = false;
    if (is_code) {
      const GcodeCode code = had_point || v < 0 ? GcodeCode::none : code_of<Printer, Retract>(letter, v);
      if (code == GcodeCode::none) return GcodeError::unsupported_code;
      GcodeCode& slot = b.code[uint8_t(gcode_group(code))];
      if (slot != GcodeCode::none) return GcodeError::modal_group_conflict;
      slot = code;
    } else {
      const uint32_t bit = gcode_letter_bit(letter);
      if (b.words & bit) return GcodeError::repeated_word;
      b.words |= bit;
      b.value[GcodeBlock::slot(letter)] = v;
    }
  }
}

enum class Checksum : uint8_t { absent, ok, mismatch, malformed };

// A trailing "*<digits>" (blanks after it allowed) is a checksum: `end` is
// set to its '*', and the result says whether the XOR of all bytes before the
// '*' equals the number (ok / mismatch; more than 3 digits or above 255:
// malformed). Without one (no '*', or a '*' not followed by digits only), the
// result is absent and `end` points at the line's NUL.
inline Checksum split_checksum(const char* line, const char*& end) {
  const char* star = nullptr;
  const char* p = line;
  for (; *p; ++p)
    if (*p == '*') star = p;
  end = p;
  if (!star) return Checksum::absent;
  const char* q = star + 1;
  uint16_t value = 0;
  uint8_t digits = 0;
  for (; *q >= '0' && *q <= '9'; ++q) {
    if (digits < 4) value = uint16_t(value * 10 + (*q - '0'));
    if (digits < 4) ++digits;
  }
  while (gcode_detail::blank(*q)) ++q;
  if (digits == 0 || *q) return Checksum::absent;
  end = star;
  if (digits > 3 || value > 255) return Checksum::malformed;
  uint8_t x = 0;
  for (const char* r = line; r != star; ++r) x = uint8_t(x ^ uint8_t(*r));
  return x == value ? Checksum::ok : Checksum::mismatch;
}

inline const char* gcode_error_message(GcodeError e) {
#define AM_GCODE_ERROR_CASE(name, text) \
  case GcodeError::name:                \
    return AM_TEXT(text);
  switch (e) { AM_GCODE_ERRORS(AM_GCODE_ERROR_CASE) }
#undef AM_GCODE_ERROR_CASE
  return AM_TEXT("?");
}

}  // namespace am
