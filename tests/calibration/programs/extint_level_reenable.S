/* Fault M (issue 7), the other side: a level interrupt that its handler
 * disables fires again when it is enabled again while the pin is still low.
 * INT1 (PD3 on both parts) in low-level mode (ISC11:10 = 00), enabled.
 * Driving PD3 low (DDR set, PORT bit 0) requests INT1; the handler toggles
 * PC0 and disables INT1, as level-interrupt handlers do. The main program
 * enables INT1 twice more while PD3 stays low. Datasheet: a level interrupt
 * "will trigger as long as the pin is held low" while it is enabled, and
 * INTF1 "is always cleared when INT1 is configured as a level interrupt",
 * so nothing of the disabled time is remembered and nothing is lost: each
 * enable with the pin low gives exactly one handler run.
 * simavr 1.6 goes on polling the low pin while INT1 is disabled and sets
 * INTF1 then; as long as that stale flag is set it raises nothing, so the
 * two later enables give no interrupt.
 *
 * EXPECT one_run_per_enable: count C0* = 3
 *   enable, drive low: 1; enable again: 1; and again: 1
 * BUDGET 100000
 */
#include "calib.h"

#ifndef EIMSK
#define EIMSK GICR			/* ATmega16/32 */
#endif

	.global main
main:
	sbi IO(DDRC), 0			; PC0: handler toggles
	ldi r18, 0x01
	ldi r17, (1 << INT1)
	out IO(EIMSK), r17		; INT1 enabled, low-level sense (reset)
	sei
	NOPS 10
	sbi IO(DDRD), 3			; PD3 driven low: INT1 requested
	NOPS 100
	out IO(EIMSK), r17		; enabled again, PD3 still low
	NOPS 100
	out IO(EIMSK), r17		; and again
	NOPS 100
	FINISH

	.global INT1_vect
INT1_vect:
	in r16, IO(PORTC)		; toggle PC0 (no PINx writes on the ATmega32)
	eor r16, r18
	out IO(PORTC), r16
	ldi r16, 0
	out IO(EIMSK), r16		; disabled until main enables it again
	reti
