// Assembles received bytes into command lines.
//
// Contract
//   feed() takes one byte; it returns Line::ready when a complete line is in
//   text() (without CR/LF, NUL-terminated), Line::too_long when a line ended
//   that did not fit (its bytes were dropped, the caller reports an error),
//   Line::bad_byte when a line ended that held a byte other than printable
//   ASCII and TAB (NUL, another control byte, DEL or a byte above 0x7F: the
//   whole line is refused, so no prefix of it can run as a command), and
//   Line::none otherwise. too_long wins over bad_byte. CR, LF and CRLF all end
//   a line; empty lines (nothing between two line ends) are ignored, so CRLF
//   is one line end. After ready/too_long/bad_byte the next feed() starts the
//   following line. between_lines() is true when no line has begun.
#pragma once
#include <stdint.h>

namespace am {

template <uint8_t Capacity>
class LineReader {
 public:
  enum class Line : uint8_t { none, ready, too_long, bad_byte };

  Line feed(char c) {
    if (c == '\n' || c == '\r') {
      const bool overflowed = overflow_;
      const bool bad = bad_;
      const uint8_t len = len_;
      len_ = 0;
      overflow_ = false;
      bad_ = false;
      if (overflowed) return Line::too_long;
      if (bad) return Line::bad_byte;
      if (len == 0) return Line::none;
      buf_[len] = '\0';
      return Line::ready;
    }
    const uint8_t b = uint8_t(c);
    if ((b < 0x20 && c != '\t') || b >= 0x7F) bad_ = true;
    if (len_ < Capacity) {
      buf_[len_++] = c;
    } else {
      overflow_ = true;
    }
    return Line::none;
  }

  // The protocol may cut the line in place (a checksum) before parsing it.
  char* text() { return buf_; }
  // No line begun: every byte fed so far ended in a line end.
  bool between_lines() const { return len_ == 0 && !overflow_; }
  static constexpr uint8_t capacity() { return Capacity; }

 private:
  char buf_[Capacity + 1];
  uint8_t len_ = 0;
  bool overflow_ = false;
  bool bad_ = false;
};

}  // namespace am
