// Selects the register map of the MCU being compiled for.
#pragma once
#if defined(__AVR_ATmega328P__)
#include "../atmega328p/registers.h"
#elif defined(__AVR_ATmega16__) || defined(__AVR_ATmega32__)
#include "../atmega16_32/registers.h"
#elif defined(__AVR_ATmega1284P__)
#include "../atmega1284p/registers.h"
#else
#error "avrmotion: no HAL register map for this MCU"
#endif
