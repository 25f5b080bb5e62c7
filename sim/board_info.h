// Reads the board descriptor (core/board_descriptor.h) out of a firmware ELF,
// so the simulator knows the MCU, the clock and every axis's wiring without a
// second copy of any board definition.
#pragma once
#include <string>

#include "../core/board_descriptor.h"

namespace sim {

// Throws std::runtime_error with a readable reason when the file is not an
// avrmotion image.
am::BoardDescriptor read_board_descriptor(const std::string& elf_path);

}  // namespace sim
