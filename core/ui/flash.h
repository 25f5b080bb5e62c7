// Constant data that stays in flash on the AVR, read the same way on the host.
//
// Contract
//   AM_FLASH marks a constant for program memory (the firmware defines it as
//   PROGMEM before including core/ui; empty on the host), AM_TEXT_BYTE reads
//   one byte of it (screen.h). flash_copy() copies an object out of it.
//   FlashRows<T, N> holds a copy of a constexpr array (core/lathe's pitch
//   tables) made at compile time, so the table is stored once, in flash, and
//   the original array is never emitted (nothing takes its address).
#pragma once
#include <stddef.h>
#include <stdint.h>

#include "screen.h"

#ifndef AM_FLASH
#define AM_FLASH
#endif

namespace am {
namespace ui {

template <class T>
inline T flash_copy(const T* from) {
  T to;
  const char* src = reinterpret_cast<const char*>(from);
  char* dst = reinterpret_cast<char*>(&to);
  for (size_t i = 0; i < sizeof(T); ++i) dst[i] = char(AM_TEXT_BYTE(src + i));
  return to;
}

template <size_t... I>
struct Indices {};
template <size_t N, size_t... I>
struct MakeIndices : MakeIndices<N - 1, N - 1, I...> {};
template <size_t... I>
struct MakeIndices<0, I...> {
  using type = Indices<I...>;
};

template <class T, size_t N>
struct FlashRows {
  T row[N];
};

template <class T, size_t N, size_t... I>
constexpr FlashRows<T, N> flash_rows(const T (&a)[N], Indices<I...>) {
  return {{a[I]...}};
}
template <class T, size_t N>
constexpr FlashRows<T, N> flash_rows(const T (&a)[N]) {
  return flash_rows(a, typename MakeIndices<N>::type());
}

}  // namespace ui
}  // namespace am
