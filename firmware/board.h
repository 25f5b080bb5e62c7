// The board this image is built for. CMake passes the header of one board
// (firmware/boards/<name>.h) as AVRMOTION_BOARD_HEADER; nothing else in the
// firmware names a board.
#pragma once
#include AVRMOTION_BOARD_HEADER

// Every board lists its hardware claims; completing the type runs their
// compile-time checks (hal/avr/claims.h).
static_assert(sizeof(board::Claims) > 0, "board::Claims");
