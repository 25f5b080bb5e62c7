// The board descriptor record (core/board_descriptor.h) for this image, kept
// in its own ELF section at a fixed address far outside flash and RAM: the
// simulator reads it, the .hex for flashing leaves it out.
#include "../core/board/descriptor.h"
#include "board.h"

namespace {

template <typename Set>
struct Describe;

template <typename... Axes>
struct Describe<AxisSet<Axes...>> {
  static_assert(sizeof...(Axes) <= am::kMaxAxes, "the descriptor holds six axes");
  static constexpr am::BoardDescriptor make() {
    return am::BoardDescriptor{{'A', 'M', 'B', '1'}, AVRMOTION_BOARD_NAME, AVRMOTION_MCU_NAME,
                               F_CPU, board::kBaud, uint8_t(sizeof...(Axes)), {0, 0, 0},
                               {Axes::descriptor()...}};
  }
};

}  // namespace

extern "C" __attribute__((used, section(".avrmotion_board")))
const am::BoardDescriptor avrmotion_board = Describe<board::Axes>::make();
