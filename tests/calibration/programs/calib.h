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
