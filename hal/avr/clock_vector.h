/* The time base's overflow vector (Timer0's, on every supported part:
 * hal/avr/clock_timer.h). Plain preprocessor, so that the vector's assembly
 * (firmware/engine/clock_vector.S) takes it too. */
#pragma once
#include <avr/io.h>

#define HAL_CLOCK_VECT TIMER0_OVF_vect
