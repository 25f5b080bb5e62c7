/* The time base's overflow vector (firmware/engine/clock.cpp): 256 ticks
 * more, carried into clock_high, bits 8..31 of clock::now().
 *
 * SEI is its first instruction, so a step match that comes while it runs
 * waits only for its entry: 4 cycles of response, the JMP (3; an RJMP, 2,
 * where the linker's relaxation reaches the handler from the table, as on
 * the ATmega16), SEI (1) and the one instruction the AVR executes after SEI
 * (2), then the step vector nests. The body touches one register and SREG.
 * Cycles from the overflow when nothing carries: 4 + 3 + 22 = 29 including
 * RETI (28 with an RJMP); every 256th overflow carries into the second byte
 * (6 more), every 65536th into the third (4 more again). Each instruction's
 * comment gives its own cycles and the running total on the path without a
 * carry.
 *
 * The vector table keeps this section in every image that has a clock, and
 * the word after RETI (never executed) keeps clock::now() with it: the
 * linker drops a section nothing refers to, and tests/sim/test_clock.cpp
 * calls the reader on the chip in images whose own code does not.
 */
#include <avr/io.h>

#include "../../hal/avr/clock_vector.h"

	.section .text.clock_vector,"ax",@progbits
	.global HAL_CLOCK_VECT
	.type HAL_CLOCK_VECT, @function
HAL_CLOCK_VECT:
	sei				; 1   8
	push r24			; 2  10
	in r24, _SFR_IO_ADDR(SREG)	; 1  11
	push r24			; 2  13
	lds r24, clock_high		; 2  15
	inc r24				; 1  16  Z: it wrapped to 0, carry on
	sts clock_high, r24		; 2  18
	brne 1f				; 2  20  taken; 1 not
	lds r24, clock_high+1		; 2
	inc r24				; 1
	sts clock_high+1, r24		; 2
	brne 1f				; 2 / 1
	lds r24, clock_high+2		; 2
	inc r24				; 1
	sts clock_high+2, r24		; 2
1:	pop r24				; 2  22
	out _SFR_IO_ADDR(SREG), r24	; 1  23
	pop r24				; 2  25
	reti				; 4  29
	.size HAL_CLOCK_VECT, . - HAL_CLOCK_VECT
	.word gs(_ZN5clock3nowEv)	;    clock::now(), kept (not code)
