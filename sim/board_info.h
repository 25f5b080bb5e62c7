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

// A symbol of the image's symbol table by its (mangled) name: its value as
// the ELF holds it (data addresses carry the 0x800000 data-space offset) and
// its size; found is false when the image has no such symbol or cannot be
// read.
struct ElfSymbol {
  uint32_t value = 0, size = 0;
  bool found = false;
};
ElfSymbol find_symbol(const std::string& elf_path, const std::string& mangled_name);

// The data-space address of a variable in the image's symbol table (its
// mangled name), for tests that set firmware state directly; throws when the
// image has no such symbol.
uint16_t read_data_symbol(const std::string& elf_path, const std::string& mangled_name);

}  // namespace sim
