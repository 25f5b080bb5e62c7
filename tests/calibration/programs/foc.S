/* Fault F: FOC1A forces the COM1A action on OC1A at once, without setting
 * OCF1A; FOC bits read as zero. Timer1 normal mode, clock stopped.
 *   S: OUT (PD0 high) | S+1: STS TCCR1C = FOC1A with COM1A = set -> OC1A high
 *
 * EXPECT force_set: D0^#0 -> OC1A^#0 = 1
 * EXPECT force_clear: D0v#0 -> OC1Av#0 = 1
 *   same with COM1A = clear
 * EXPECT force_toggle: D0^#1 -> OC1A^#1 = 1
 *   same with COM1A = toggle, from low
 * EXPECT no_ocf1a: count C1* = 0
 *   TIFR1 bit OCF1A copied to PC1: a strobe sets no flag
 * EXPECT foc_reads_zero: count C3* = 0
 *   TCCR1C bit FOC1A (bit 7, swapped to bit 3) copied to PC3
 */
#include "calib.h"

	.global main
main:
	ldi r16, (1 << PB1)
	out IO(DDRB), r16
	ldi r16, 0x01
	out IO(DDRD), r16
	ldi r16, 0x0f
	out IO(DDRC), r16
	ldi r20, 0x01
	ldi r22, 0x00
	ldi r23, (1 << FOC1A)

	ldi r16, (1 << COM1A1) | (1 << COM1A0)	; set on match
	sts MEM(TCCR1A), r16
	out IO(PORTD), r20	; S
	sts MEM(TCCR1C), r23	; S+1
	NOPS 10
	ldi r16, (1 << COM1A1)			; clear on match
	sts MEM(TCCR1A), r16
	out IO(PORTD), r22
	sts MEM(TCCR1C), r23
	NOPS 10
	ldi r16, (1 << COM1A0)			; toggle on match
	sts MEM(TCCR1A), r16
	out IO(PORTD), r20
	sts MEM(TCCR1C), r23
	NOPS 10
	lds r16, MEM(TIFR1)
	andi r16, (1 << OCF1A)
	lds r17, MEM(TCCR1C)
	swap r17
	andi r17, 0x0c
	or r16, r17
	out IO(PORTC), r16
	FINISH
