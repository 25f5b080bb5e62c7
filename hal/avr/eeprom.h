// The EEPROM, as blocks (avr-libc's eeprom_*_block: each byte waits for the
// previous write, about 3.4 ms a byte; update writes only the bytes that
// differ, which spares the cells' 100000 write cycles).
#pragma once
#include <avr/eeprom.h>
#include <stdint.h>

namespace hal {
namespace eeprom {

inline void read(uint16_t address, void* to, uint16_t bytes) {
  eeprom_read_block(to, reinterpret_cast<const void*>(address), bytes);
}
inline void update(uint16_t address, const void* from, uint16_t bytes) {
  eeprom_update_block(from, reinterpret_cast<void*>(address), bytes);
}

}  // namespace eeprom
}  // namespace hal
