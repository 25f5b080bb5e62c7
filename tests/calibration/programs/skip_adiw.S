/* Patch U: a skip over ADIW or SBIW skips that one word. SBRS and SBRC
 * with their condition true skip the next instruction in 2 cycles when it
 * is one word (AVR instruction set manual), ADIW and SBIW included, whatever
 * their constant; stock simavr 1.6 takes ADIW/SBIW with a constant's low
 * nibble 0xc..0xf for JMP/CALL and skips two words. Markers on PB0 and PB1;
 * S = start of the first marker write.
 *
 * EXPECT adiw: B0^#0 -> B1^#0 = 3
 *   S: OUT (1) | S+1: SBRS, skipping ADIW r30, 15 (2) | S+3: OUT PB1
 * EXPECT sbiw: B1^#0 -> B0v#0 = 3
 *   S': OUT PB1 (1) | S'+1: SBRC, skipping SBIW r28, 63 (2) | S'+3: OUT PB0 low
 */
#include "calib.h"

	.global main
main:
	ldi r16, 0x03
	out IO(DDRB), r16
	ldi r17, 0x01		; bit 0 set, bit 1 clear
	ldi r18, 0x01
	ldi r19, 0x03
	ldi r20, 0x02
	out IO(PORTB), r18	; S: PB0 high
	sbrs r17, 0		; S+1: bit set, skip
	adiw r30, 15		; 0x963f: skipped
	out IO(PORTB), r19	; S+3: PB1 high
	sbrc r17, 1		; S'+1: bit clear, skip (S': the OUT above)
	sbiw r28, 63		; 0x97ff: skipped
	out IO(PORTB), r20	; S'+3: PB0 low
	NOPS 10
	FINISH
