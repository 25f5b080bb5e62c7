/* Fault A: a timer continues from the value held in TCNT when its clock
 * starts, and holds its count while stopped.
 * Timer1 normal mode, prescaler 1, OC1A and OC1B toggle on match,
 * OCR1A = 999, OCR1B = 1199, TCNT1 = 900 written while stopped.
 *   S: OUT (MARK high) | S+1: STS TCCR1B = clk/1 -> count 900 at S+1
 *   match A when the count leaves 999: S+1 + (999 + 1 - 900) = S+101
 *   S+3: 247 NOPs | S+250: OUT (MARK low) | S+251: STS TCCR1B = 0 (stop):
 *     held count = 900 + (S+251 - (S+1)) = 1150 = 0x047E
 *   S+253: LDS TCNT1L (0x7E) | S+255: OUT PORTC | S+256: 47 NOPs
 *   S+303: OUT (MARK high) | S+304: restart -> match B when the count
 *     leaves 1199: (1199 + 1 - 1150) = 50 ticks later = S+354
 *
 * EXPECT preload: MARK^#0 -> OC1A*#0 = 101
 * EXPECT resume: MARK^#1 -> OC1B*#0 = 51
 *   (S+354) - (S+303) = 51
 * EXPECT held_lsb0: count C0* = 0
 * EXPECT held_lsb1: count C1^ = 1
 * EXPECT held_lsb6: count C6^ = 1
 *   TCNT1L read while stopped is 0x7E: bits 1-6 set, bit 0 clear
 */
#include "calib.h"

	.global main
main:
	sbi IO(MARK_DDR), 0	; marker pin (MARK)
	sbi IO(OC1A_DDR), OC1A_BIT
	sbi IO(OC1B_DDR), OC1B_BIT
	ldi r16, 0x7f
	out IO(DDRC), r16
	STS16 MEM(OCR1AL), 999
	STS16 MEM(OCR1BL), 1199
	ldi r16, (1 << COM1A0) | (1 << COM1B0)
	sts MEM(TCCR1A), r16
	STS16 MEM(TCNT1L), 900
	ldi r20, 0x01
	ldi r21, (1 << CS10)
	ldi r22, 0x00
	out IO(MARK_PORT), r20	; S
	sts MEM(TCCR1B), r21	; S+1: start
	NOPS 247
	out IO(MARK_PORT), r22	; S+250
	sts MEM(TCCR1B), r22	; S+251: stop
	lds r24, MEM(TCNT1L)	; S+253
	out IO(PORTC), r24	; S+255
	NOPS 47
	out IO(MARK_PORT), r20	; S+303
	sts MEM(TCCR1B), r21	; S+304: restart
	NOPS 100
	FINISH
