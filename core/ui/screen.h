// The operator's 2 x 16 character screen as a buffer, with a dirty bit per
// cell: the workflow draws into it, the LCD driver sends only what changed.
//
// Contract
//   cell[row * 16 + col] is the character shown there; every write that
//   changes a cell sets its bit in `dirty`; the driver (firmware/devices/
//   hd44780.h) clears the bit once the display shows the cell. Characters
//   1..5 are the driver's progress-bar glyphs (1..5 columns of a cell lit);
//   text is ASCII. Writes past the end of a row are dropped, never wrapped.
//   Texts passed to line()/text() are AM_TEXT strings: on the AVR the
//   firmware defines AM_TEXT(s) as PSTR(s) and AM_TEXT_BYTE(p) as
//   pgm_read_byte(p) before including core/ui, so every text stays in flash;
//   by default they are plain strings (host tests).
//
// Why a dirty mask and not a second copy of the screen: 4 bytes instead of
// 32, and redrawing a whole screen with the same text costs the LCD bus
// nothing, so the workflow may redraw freely.
#pragma once
#include <stdint.h>

#ifndef AM_TEXT
#define AM_TEXT(s) (s)
#endif
#ifndef AM_TEXT_BYTE
#define AM_TEXT_BYTE(p) (*(p))
#endif

namespace am {
namespace ui {

constexpr uint8_t kRows = 2;
constexpr uint8_t kCols = 16;
constexpr uint8_t kBarSteps = kCols * 5;  // a full row of 5-column glyphs

struct Screen {
  char cell[kRows * kCols];
  uint32_t dirty;

  // All spaces, nothing to send: what a display shows after its clear.
  void clear_sent() {
    for (uint8_t i = 0; i < kRows * kCols; ++i) cell[i] = ' ';
    dirty = 0;
  }

  void put(uint8_t row, uint8_t col, char c) {
    if (col >= kCols) return;
    const uint8_t i = uint8_t(row * kCols + col);
    if (cell[i] == c) return;
    cell[i] = c;
    dirty |= uint32_t(1) << i;
  }

  // A flash text at (row, col); returns the column after it.
  uint8_t text(uint8_t row, uint8_t col, const char* s) {
    for (char c; (c = char(AM_TEXT_BYTE(s))) != 0; ++s) put(row, col++, c);
    return col;
  }

  // Spaces from col up to (not including) `end`.
  void blank(uint8_t row, uint8_t col, uint8_t end = kCols) {
    while (col < end) put(row, col++, ' ');
  }

  // The whole row: the text, then spaces.
  void line(uint8_t row, const char* s) { blank(row, text(row, 0, s)); }

  // A RAM text (digits typed so far).
  uint8_t ram_text(uint8_t row, uint8_t col, const char* s) {
    while (*s) put(row, col++, *s++);
    return col;
  }

  // value / 10^decimals, right-aligned in `width` columns (0: as many as
  // it needs), with a '-' for negatives; returns the column after it. A
  // value too wide for its field shows as '*' in the field's first column.
  uint8_t number(uint8_t row, uint8_t col, int32_t value, uint8_t width, uint8_t decimals) {
    char text[12];
    const uint8_t n = format(text, value, decimals);
    if (width == 0) width = n;
    const uint8_t end = uint8_t(col + width);
    for (uint8_t i = 0; col < end; ++col, ++i)
      put(row, col, n > width ? (i ? ' ' : '*') : i + n < width ? ' ' : text[i + n - width]);
    return end;
  }

  // value / 10^decimals as text ("-0.05", "12.500"); returns its length (at
  // most 12: a '-', ten digits and the point).
  static uint8_t format(char* text, int32_t value, uint8_t decimals) {
    char digits[12];
    uint8_t n = 0;
    uint32_t mag = value < 0 ? uint32_t(0) - uint32_t(value) : uint32_t(value);
    do {
      if (n == decimals && decimals) digits[n++] = '.';
      digits[n++] = char('0' + mag % 10);
      mag /= 10;
    } while (mag || n <= decimals);
    if (value < 0) digits[n++] = '-';
    for (uint8_t i = 0; i < n; ++i) text[i] = digits[n - 1 - i];
    return n;
  }

  // A progress bar over the whole row: `filled` of kBarSteps columns lit.
  void bar(uint8_t row, uint8_t filled) {
    for (uint8_t col = 0; col < kCols; ++col) {
      const uint8_t lit = filled >= 5 ? 5 : filled;
      put(row, col, lit ? char(lit) : ' ');
      filled = uint8_t(filled - lit);
    }
  }
};

}  // namespace ui
}  // namespace am
