// Running firmware code from the main loop's context of a simulated image,
// for tests that need the main loop to do something at a chosen instant (a
// call of clock::now() right before a timer wrap) or to do nothing for a
// while (a main loop stalled behind a long computation).
#pragma once
#include <gtest/gtest.h>

#include <cstring>

#include "machine.h"
#include <sim_avr.h>
#include <sim_core.h>

namespace simtest {

inline bool main_with_interrupts_on(avr_t* avr) { return avr->interrupts.running_ptr == 0 && avr->sreg[S_I]; }

// Runs until `cycle` has come and the CPU is in the main loop, at a point
// where an interrupt could enter: I set, and already set before the last
// instruction (the one after SEI, OUT SREG or RETI takes no interrupt).
inline bool run_to_main(sim::Machine& m, uint64_t cycle, uint64_t budget) {
  bool was_on = false;
  return m.run(
             [&] {
               const bool on = main_with_interrupts_on(m.avr());
               const bool ok = m.cycles() >= cycle && on && was_on;
               was_on = on;
               return ok;
             },
             budget) == sim::RunEnd::done;
}

struct MainCall {
  uint32_t result;      // r22..r25: a 32-bit return value
  uint64_t start, end;  // the cycles the call spanned
};

// Calls the function at `byte_address` from wherever the main loop is (at a
// point run_to_main() stopped: the stack pointer is whole there, not halfway
// through a prologue's SPH/SPL update), as a CALL there would (without the
// CALL's own 4 cycles), and runs the chip, interrupts and all, until it has
// returned. With `interrupts_off` the call runs with I clear, as from a cli
// section. The main loop's registers and SREG are put back afterwards: the
// call clobbers what the ABI lets it, which the interrupted code did not
// expect, and nothing else can have changed them (handlers restore theirs).
// I goes off and on again through simavr's avr_sreg_set(), as CLI and SEI
// would: a raw write of SREG's I bit leaves simavr's interrupt state as it
// was, and an interrupt raised while I was off then waits for the next
// event that recomputes it (a thousand cycles and more, measured).
inline MainCall call_in_main(sim::Machine& m, uint32_t byte_address, bool interrupts_off = false) {
  avr_t* avr = m.avr();
  EXPECT_TRUE(main_with_interrupts_on(avr)) << "not between two main-loop instructions";
  uint8_t regs[32], sreg[8];
  std::memcpy(regs, avr->data, sizeof regs);
  std::memcpy(sreg, avr->sreg, sizeof sreg);
  if (interrupts_off) avr_sreg_set(avr, S_I, 0);
  const avr_flashaddr_t pc = avr->pc;
  const uint16_t sp = uint16_t(avr->data[R_SPL] | avr->data[R_SPH] << 8);
  // Push the return address as CALL does: the word address, low byte first,
  // the stack growing down.
  uint32_t ret = pc >> 1;
  for (int i = 0; i < avr->address_size; ++i, ret >>= 8) avr->data[sp - i] = uint8_t(ret);
  const uint16_t sp_in = uint16_t(sp - avr->address_size);
  avr->data[R_SPL] = uint8_t(sp_in);
  avr->data[R_SPH] = uint8_t(sp_in >> 8);
  avr->pc = byte_address;
  MainCall c;
  c.start = m.cycles();
  const sim::RunEnd end = m.run(
      [&] {
        return avr->pc == pc && avr->interrupts.running_ptr == 0 &&
               uint16_t(avr->data[R_SPL] | avr->data[R_SPH] << 8) == sp;
      },
      200000);
  EXPECT_EQ(end, sim::RunEnd::done) << "the call did not return";
  c.end = m.cycles();
  c.result = uint32_t(avr->data[22]) | uint32_t(avr->data[23]) << 8 | uint32_t(avr->data[24]) << 16 |
             uint32_t(avr->data[25]) << 24;
  std::memcpy(avr->data, regs, sizeof regs);
  const uint8_t i_now = avr->sreg[S_I];
  std::memcpy(avr->sreg, sreg, sizeof sreg);
  avr->sreg[S_I] = i_now;
  avr_sreg_set(avr, S_I, sreg[S_I]);  // as SEI: one more instruction, then what is pending
  return c;
}

}  // namespace simtest
