/* Basic instruction timing that every other derivation relies on:
 * RCALL 3, RETI 4, RET 4, JMP 3 (ATmega328P instruction set summary,
 * 16-bit PC). Markers on PB0; S = start of the first marker write.
 *
 * EXPECT rcall_reti: B0^#0 -> B0v#0 = 8
 *   S: OUT (1) | S+1: RCALL (3) | S+4: RETI (4) | S+8: OUT -> 1+3+4 = 8
 * EXPECT rcall_ret:  B0v#0 -> B0^#1 = 8
 *   same path with RET instead of RETI: 1+3+4 = 8
 * EXPECT jmp:        B0^#1 -> B0v#1 = 4
 *   OUT (1) + JMP (3) = 4
 */
#include "calib.h"

	.global main
main:
	ldi r16, 0x01
	ldi r17, 0x00
	out IO(DDRB), r16
	out IO(PORTB), r16	; S
	rcall 1f		; S+1
	out IO(PORTB), r17	; S+8
	rcall 2f
	out IO(PORTB), r16
	jmp 3f
3:	out IO(PORTB), r17
	FINISH
1:	reti			; nothing is enabled: only timing matters
2:	ret
