/* Fault G: in non-PWM modes OC1x changes only on compare match (or FOC1x);
 * writing a compare register must not drive the pin.
 * Timer1 CTC, TOP = OCR1A = 199, prescaler 1, OCR1B = 99, OC1B = clear on
 * match at first, then set on match.
 *   S: OUT (MARK high) | S+1: STS TCCR1B = CTC clk/1, count 0 at S+1
 *   S+27: OCR1BL := 99 again (clear mode; count 26)
 *   S+30: TCCR1A := set on match
 *   B match when the count leaves 99: S+1 + 100 = S+101 -> OC1B high
 *   S+136: OCR1BL := 150 (count 135; next B match at S+152, pin stays high)
 *
 * EXPECT set_on_match: MARK^#0 -> OC1B^#0 = 101
 * EXPECT single_edge: count OC1B* = 1
 *   the genuine rise only: no edge from either OCR1B write
 */
#include "calib.h"

	.global main
main:
	sbi IO(MARK_DDR), 0	; marker pin (MARK)
	sbi IO(OC1B_DDR), OC1B_BIT
	STS16 MEM(OCR1AL), 199
	STS16 MEM(OCR1BL), 99
	ldi r16, (1 << COM1B1)			; clear OC1B on match
	sts MEM(TCCR1A), r16
	ldi r20, 0x01
	ldi r21, (1 << WGM12) | (1 << CS10)
	out IO(MARK_PORT), r20	; S
	sts MEM(TCCR1B), r21	; S+1
	NOPS 20			; S+3
	STS16 MEM(OCR1BL), 99	; S+23 (low byte written at S+27)
	ldi r16, (1 << COM1B1) | (1 << COM1B0)	; S+29: set OC1B on match
	sts MEM(TCCR1A), r16	; S+30
	NOPS 100		; S+32
	STS16 MEM(OCR1BL), 150	; S+132 (low byte at S+136)
	NOPS 40
	FINISH
