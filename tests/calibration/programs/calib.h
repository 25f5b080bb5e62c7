/* Shared helpers for the calibration programs (assembly, avr-gcc -x
 * assembler-with-cpp). The programs link against avr-libc's startup code,
 * so every vector is a JMP (3 cycles) to the __vector_N symbol defined here,
 * and main is called with interrupts disabled.
 *
 * Timing conventions used in every derivation (see docs/simulator.md):
 *  - an instruction's "time" is the cycle at which it starts; a port write
 *    is timestamped at the start of the OUT/SBI/CBI that does it;
 *  - a timer register write (TCCRnB, TCNTn, OCRn, FOCn) takes effect at the
 *    start of the writing instruction;
 *  - a compare match is the timer tick on which the counter leaves OCRnx
 *    (datasheet: "A match will set the Output Compare Flag at the next timer
 *    clock cycle"); the OCnx pin and OCFnx change at that tick.
 * Cycle counts (ATmega328P/ATmega32 instruction set summary): NOP, OUT,
 * LDI, COM, SEI, CLI 1; SBI, CBI, STS, LDS, SBIW, taken branch, RJMP 2;
 * JMP, RCALL 3; RET, RETI, CALL 4. Interrupt response 4 (PC push + vector
 * fetch), then the vector's JMP 3.
 */
#include <avr/io.h>

#define IO(r)  _SFR_IO_ADDR(r)
#define MEM(r) _SFR_MEM_ADDR(r)

/* ATmega16/32 spellings of the ATmega328P timer-1 names used here, and the
 * OC1A/OC1B pins of each part (the ATmega1284P: the 328P's names, the 32's pins) (the runner maps "OC1A" etc. the same way).
 * Timer-1 registers are always accessed with LDS/STS (2 cycles on every
 * part), so cycle counts do not change between parts. */
#ifndef TIMSK1
#define TIMSK1 TIMSK
#define TIFR1  TIFR
#endif
#if defined(__AVR_ATmega16__) || defined(__AVR_ATmega32__) || defined(__AVR_ATmega1284P__)
#define OC1A_DDR DDRD
#define OC1A_BIT 5
#define OC1B_DDR DDRD
#define OC1B_BIT 4
#define MARK_PORT PORTB	/* marker pin: PB0 (PORTD carries OC1A/OC1B) */
#define MARK_DDR  DDRB
#else
#define OC1A_DDR DDRB
#define OC1A_BIT 1
#define OC1B_DDR DDRB
#define OC1B_BIT 2
#define MARK_PORT PORTD	/* marker pin: PD0 (PORTB carries OC1A/OC1B) */
#define MARK_DDR  DDRD
#endif
/* simavr does not model the OCnx override of the PORT bit: a plain OUT to
 * the port of an OC pin would drive that pin too. Markers therefore use
 * OUT on MARK_PORT, which holds no OC pin in use. */

/* n single-cycle instructions: keeps the CPU on a 1-cycle instruction grid,
 * so an interrupt or timer event is seen exactly at its cycle. */
.macro NOPS n
	.rept \n
	nop
	.endr
.endm

/* End of the program: simavr stops ("sleeping with interrupts off"). */
.macro FINISH
	cli
	sleep
.endm

/* 16-bit store, high byte first (the datasheet's TEMP-register order). */
.macro STS16 addr, value, tmp=r16
	ldi \tmp, hi8(\value)
	sts \addr+1, \tmp
	ldi \tmp, lo8(\value)
	sts \addr, \tmp
.endm
