// Reads the board descriptor (core/board/descriptor.h) out of a firmware ELF,
// so the simulator knows the MCU, the clock and every axis's wiring without a
// second copy of any board definition.
#pragma once
#include <cstdint>
#include <string>

#include "../core/board/descriptor.h"

namespace sim {

// Throws std::runtime_error with a readable reason when the file is not an
// avrmotion image.
am::BoardDescriptor read_board_descriptor(const std::string& elf_path);

// The data-space address of a variable in the image's symbol table (its
// mangled name), for tests that set firmware state directly; throws when the
// image has no such symbol.
uint16_t read_data_symbol(const std::string& elf_path, const std::string& mangled_name);

}  // namespace sim
