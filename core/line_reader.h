// Assembles received bytes into command lines.
//
// Contract
//   feed() takes one byte; it returns Line::ready when a complete line is in
//   text() (without CR/LF, NUL-terminated), Line::too_long when a line ended
//   that did not fit (its bytes were dropped, the caller reports an error), and
//   Line::none otherwise. CR, LF and CRLF all end a line; empty lines are
//   ignored. After ready/too_long the next feed() starts the following line.
#pragma once
#include <stdint.h>

namespace am {

template <uint8_t Capacity>
class LineReader {
 public:
  enum class Line : uint8_t { none, ready, too_long };

  Line feed(char c) {
    if (c == '\n' || c == '\r') {
      const bool overflowed = overflow_;
      const uint8_t len = len_;
      len_ = 0;
      overflow_ = false;
      if (overflowed) return Line::too_long;
      if (len == 0) return Line::none;
      buf_[len] = '\0';
      return Line::ready;
    }
    if (len_ < Capacity) {
      buf_[len_++] = c;
    } else {
      overflow_ = true;
    }
    return Line::none;
  }

  const char* text() const { return buf_; }
  static constexpr uint8_t capacity() { return Capacity; }

 private:
  char buf_[Capacity + 1];
  uint8_t len_ = 0;
  bool overflow_ = false;
};

}  // namespace am
