// Parser for the line commands of the firmware's text protocol (see
// docs/protocol.md). G-code will arrive as its own parser; these commands stay
// as the machine's direct controls.
//
// Contract
//   parse(line, out) fills `out` and returns ParseError::none, or returns the
//   first error found and leaves `out` unspecified. It never reads past the
//   terminating NUL and never writes outside `out`. Keywords and axis letters
//   are case-insensitive; words are separated by spaces or tabs.
//
//   MOVE <axis><steps>... [F<rate>] [A<accel>]
//        relative move of one or more axes together (each letter once; F
//        and A are those of the axis with the most steps; A is both the
//        acceleration and the deceleration: one exact profile, with no
//        separate D any more)
//   POS                                                   report positions
//   RELEASE                                               coils / drivers off
//   WAIT                                                  answer once idle
//   MODE <axis><n>                                        excitation mode of a
//        coil-driven axis: n = 0 wave, 1 two-phase, 2 half step, 16/32/64
//        microsteps; the mode number is returned in `steps`
#pragma once
#include <stdint.h>

namespace am {

enum class CommandKind : uint8_t { move, position, release, wait, mode };

enum class ParseError : uint8_t {
  none,
  empty,
  unknown_command,
  bad_word,         // a word that is not <letter><number>
  bad_number,       // digits missing or junk after them
  out_of_range,     // number beyond the 32-bit range the protocol allows
  duplicate_word,
  missing_axis,     // MOVE without an axis word
  two_axes,         // MODE names more than one axis
  unexpected_word,  // a word this command does not take
  bad_mode,         // MODE number other than 0, 1, 2, 16, 32, 64
};

constexpr uint8_t kMoveAxes = 5;  // X Y Z E U

struct Command {
  CommandKind kind;
  char axis;        // 'X', 'Y', 'Z', 'E' or 'U': the first axis word (MODE's only one)
  int32_t steps;    // its number
  uint8_t axis_count;             // MOVE: axis words given, in line order:
  char axes[kMoveAxes];           //   their letters
  int32_t axis_steps[kMoveAxes];  //   and their steps
  uint32_t rate;    // steps/s
  uint32_t accel;   // steps/s^2
  uint8_t given;    // which of rate/accel the line set (kGiven* bits)
};

constexpr uint8_t kGivenRate = 2, kGivenAccel = 4;

namespace detail {

inline char upper(char c) { return (c >= 'a' && c <= 'z') ? char(c - 'a' + 'A') : c; }
inline bool blank(char c) { return c == ' ' || c == '\t'; }
inline bool digit(char c) { return c >= '0' && c <= '9'; }

// Matches a keyword (case-insensitive) followed by a blank or the end.
inline bool keyword(const char*& p, const char* word) {
  const char* q = p;
  while (*word) {
    if (upper(*q) != *word) return false;
    ++q;
    ++word;
  }
  if (*q && !blank(*q)) return false;
  p = q;
  return true;
}

// Signed decimal integer with |value| <= 2^31 - 1.
inline ParseError number(const char*& p, int32_t& value) {
  bool negative = false;
  if (*p == '-' || *p == '+') negative = (*p++ == '-');
  if (!digit(*p)) return ParseError::bad_number;
  uint32_t v = 0;
  while (digit(*p)) {
    const uint8_t d = uint8_t(*p++ - '0');
    if (v > (0x7FFFFFFFul - d) / 10) return ParseError::out_of_range;
    v = v * 10 + d;
  }
  if (*p && !blank(*p)) return ParseError::bad_number;
  value = negative ? -int32_t(v) : int32_t(v);
  return ParseError::none;
}

inline bool is_axis(char c) { return c == 'X' || c == 'Y' || c == 'Z' || c == 'E' || c == 'U'; }

}  // namespace detail

inline ParseError parse_command(const char* p, Command& out) {
  using namespace detail;
  while (blank(*p)) ++p;
  if (!*p) return ParseError::empty;
  out = Command{CommandKind::move, 0, 0, 0, {}, {}, 0, 0, 0};
  if (keyword(p, "POS")) out.kind = CommandKind::position;
  else if (keyword(p, "RELEASE")) out.kind = CommandKind::release;
  else if (keyword(p, "WAIT")) out.kind = CommandKind::wait;
  else if (keyword(p, "MODE")) out.kind = CommandKind::mode;
  else if (!keyword(p, "MOVE")) return ParseError::unknown_command;

  uint8_t seen = 0;  // bit per word letter: axis, F, A, D
  for (;;) {
    while (blank(*p)) ++p;
    if (!*p) break;
    if (out.kind != CommandKind::move && out.kind != CommandKind::mode) return ParseError::unexpected_word;
    const char letter = upper(*p++);
    if (!(letter >= 'A' && letter <= 'Z')) return ParseError::bad_word;
    int32_t value;
    const ParseError e = number(p, value);
    if (e != ParseError::none) return e;
    uint8_t bit;
    if (is_axis(letter)) {
      for (uint8_t i = 0; i < out.axis_count; ++i)
        if (out.axes[i] == letter) return ParseError::duplicate_word;
      if (out.kind == CommandKind::mode && (seen & 1)) return ParseError::two_axes;
      bit = 1;
      if (!(seen & 1)) {
        out.axis = letter;
        out.steps = value;
      }
      out.axes[out.axis_count] = letter;
      out.axis_steps[out.axis_count++] = value;
    } else if (out.kind == CommandKind::mode) {
      return ParseError::unexpected_word;  // MODE takes its axis word only
    } else if (letter == 'F' || letter == 'A') {
      bit = letter == 'F' ? kGivenRate : kGivenAccel;
      if (seen & bit) return ParseError::duplicate_word;
      if (value < 0) return ParseError::out_of_range;
      (letter == 'F' ? out.rate : out.accel) = uint32_t(value);
    } else {
      return ParseError::unexpected_word;
    }
    seen |= bit;
  }
  if ((out.kind == CommandKind::move || out.kind == CommandKind::mode) && !(seen & 1))
    return ParseError::missing_axis;
  if (out.kind == CommandKind::mode) {
    const int32_t m = out.steps;
    if (!(m == 0 || m == 1 || m == 2 || m == 16 || m == 32 || m == 64)) return ParseError::bad_mode;
  }
  out.given = uint8_t(seen & ~1);
  return ParseError::none;
}

}  // namespace am
