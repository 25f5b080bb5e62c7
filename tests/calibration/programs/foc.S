/* Fault F: FOC1A forces the COM1A action on OC1A at once, without setting
 * OCF1A; FOC bits read as zero. Timer1 normal mode, clock stopped.
 * ATmega328P: strobe = STS TCCR1C <- FOC1A. ATmega16/32: FOC1A lives in
 * TCCR1A, so the strobe is STS TCCR1A <- COM1A bits | FOC1A.
 *   S: OUT (MARK high) | S+1: strobe with COM1A = set -> OC1A high at S+1
 *
 * EXPECT force_set: MARK^#0 -> OC1A^#0 = 1
 * EXPECT force_clear: MARKv#0 -> OC1Av#0 = 1
 *   same with COM1A = clear
 * EXPECT force_toggle: MARK^#1 -> OC1A^#1 = 1
 *   same with COM1A = toggle, from low
 * EXPECT no_ocf1a: count C1* = 0
 *   TIFR1 bit OCF1A copied to PC1: a strobe sets no flag
 * EXPECT foc_reads_zero: count C3* = 0
 *   the FOC1A bit read back, moved to bit 3, copied to PC3
 */
#include "calib.h"

#ifdef TCCR1C
/* COM1A bits go to TCCR1A, the strobe to TCCR1C */
.macro STROBE com
	ldi r16, \com
	sts MEM(TCCR1A), r16
	ldi r16, (1 << FOC1A)
	out IO(MARK_PORT), r20	; marker (r20 = level chosen by the caller)
	sts MEM(TCCR1C), r16
.endm
#define FOC_REG TCCR1C
#define FOC_SHIFT swap r17	/* FOC1A: bit 7 -> bit 3 */
#else
.macro STROBE com
	ldi r16, \com | (1 << FOC1A)
	out IO(MARK_PORT), r20
	sts MEM(TCCR1A), r16
.endm
#define FOC_REG TCCR1A
#define FOC_SHIFT nop		/* FOC1A is bit 3 already */
#endif

	.global main
main:
	sbi IO(MARK_DDR), 0	; marker pin (MARK)
	sbi IO(OC1A_DDR), OC1A_BIT
	ldi r16, 0x0f
	out IO(DDRC), r16

	ldi r20, 0x01
	STROBE (1 << COM1A1) | (1 << COM1A0)	; set on match
	NOPS 10
	ldi r20, 0x00
	STROBE (1 << COM1A1)			; clear on match
	NOPS 10
	ldi r20, 0x01
	STROBE (1 << COM1A0)			; toggle on match
	NOPS 10
	lds r16, MEM(TIFR1)
	andi r16, (1 << OCF1A)
	lds r17, MEM(FOC_REG)
	FOC_SHIFT
	andi r17, 0x08
	or r16, r17
	out IO(PORTC), r16
	FINISH
