// What the time-base tests share (test_clock.cpp, test_clock_cost.cpp): the
// images and their fastest moves, the vector numbers, and the probe that
// watches the clock's and the step engine's vectors through simavr's
// interrupt IRQs.
#pragma once
#include <sim_avr.h>
#include <sim_interrupts.h>
#include <sim_irq.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "board_info.h"
#include "sim_fixture.h"

namespace clocktest {

struct ImageCase {
  const char* image;
  uint16_t prescaler;  // Timer0's, as the board claims it (firmware/boards/*.h)
  const char* move;    // a move of the image's fastest axis at its top rate
  char axis;
  uint32_t steps;
  int junk;  // NOP lines: their error answers keep the UART busy for the whole move
};

const ImageCase kImages[] = {
    {"uno", 8, "MOVE Z150000 F160000 A300000", 'Z', 150000, 600},  // 1.5 s, 0.4 s of it at 160 kHz
    {"m32-direct", 64, "MOVE X24000 F40000 A800000", 'X', 24000, 280},  // 0.6 s; the m32 printer and mill images have no MOVE
    {"m16", 64, "MOVE Z12000 F20000 A800000", 'Z', 12000, 280},    // 0.6 s
    {"m16-8mhz", 64, "MOVE Z6000 F10000 A800000", 'Z', 6000, 90},  // 0.6 s at 38400 baud
};

// Vector numbers (the datasheets' interrupt vector tables).
struct Vectors {
  int step;   // TIMER1_COMPA
  int clock;  // TIMER0_OVF
};
inline Vectors vectors_of(const std::string& mcu) {
  if (mcu == "atmega328p") return {11, 16};
  if (mcu == "atmega32") return {7, 11};
  if (mcu == "atmega16") return {6, 9};
  if (mcu == "atmega1284p") return {13, 18};
  ADD_FAILURE() << "no vector table for " << mcu;
  return {0, 0};
}

// Cycles of the jump in vector `v`'s table entry (4 bytes each on these
// parts): JMP 3, or RJMP 2 where the linker's relaxation reached the
// handler from the table (the ATmega16's 16 KB).
inline int vector_jump_cycles(sim::Machine& m, int v) {
  const uint8_t* f = m.avr()->flash + 4 * v;
  const uint16_t word = uint16_t(f[0] | f[1] << 8);
  if ((word & 0xF000) == 0xC000) return 2;
  EXPECT_EQ(word & 0xFE0E, 0x940C) << "vector " << v << " is neither JMP nor RJMP";
  return 3;
}

// A symbol's value and size from the image's symbol table.

// Watches the clock's and the step engine's vectors through simavr's
// interrupt IRQs: when TOV0 was set (the wrap), when each vector was entered
// and left, clock_high after every overflow vector, and for every step
// interrupt how long it waited and whether it nested in the overflow vector.
class Probe {
 public:
  struct StepIrq {
    uint64_t pending = 0;  // the compare match (OCF1A set)
    uint64_t entry = 0;    // its response began (simavr adds the 4 cycles before it says so)
    bool nested = false;   // it interrupted the overflow vector
    bool held = false;     // its match came while the overflow vector was being entered or ran (held())
    uint64_t wait() const { return entry - pending; }
  };

  Probe(sim::Machine& m, const std::string& elf) : m_(m), v_(vectors_of(m.board().mcu)) {
    high_addr_ = sim::read_data_symbol(elf, "clock_high");
    avr_irq_t* clock = avr_get_interrupt_irq(m.avr(), uint8_t(v_.clock));
    avr_irq_t* step = avr_get_interrupt_irq(m.avr(), uint8_t(v_.step));
    avr_irq_register_notify(clock + AVR_INT_IRQ_PENDING, &Probe::on_clock_pending, this);
    avr_irq_register_notify(clock + AVR_INT_IRQ_RUNNING, &Probe::on_clock_running, this);
    avr_irq_register_notify(step + AVR_INT_IRQ_PENDING, &Probe::on_step_pending, this);
    avr_irq_register_notify(step + AVR_INT_IRQ_RUNNING, &Probe::on_step_running, this);
  }

  uint32_t high() const {
    const uint8_t* d = m_.avr()->data + high_addr_;
    return uint32_t(d[0]) | uint32_t(d[1]) << 8 | uint32_t(d[2]) << 16;
  }

  std::vector<uint64_t> wraps;         // TOV0 set
  std::vector<uint64_t> clock_entries;  // overflow vector entered (response began)
  std::vector<uint64_t> clock_exits;    // and the end of its RETI
  std::vector<uint32_t> high_after;    // clock_high at each of its RETIs
  std::vector<StepIrq> steps;
  uint64_t clock_exclusive = 0;  // cycles in the overflow vector, nested handlers excluded, RETI included

 private:
  static void on_clock_pending(avr_irq_t*, uint32_t value, void* p) {
    auto* self = static_cast<Probe*>(p);
    const uint64_t now = self->m_.cycles();
    // simavr raises the pending IRQ again on a flag already set; one wrap
    // per cycle.
    if (value && (self->wraps.empty() || self->wraps.back() != now)) self->wraps.push_back(now);
  }
  static void on_clock_running(avr_irq_t*, uint32_t value, void* p) {
    auto* self = static_cast<Probe*>(p);
    avr_t* avr = self->m_.avr();
    const uint64_t now = self->m_.cycles();
    if (value) {
      const uint64_t response = uint64_t(2 + avr->address_size);
      self->clock_entries.push_back(now - response);
      self->clock_in_ = now - response;
      self->nested_ = 0;
    } else {
      self->high_after.push_back(self->high());
      // RETI's own 4 cycles are still to come.
      self->clock_exits.push_back(now + 4);
      self->clock_exclusive += now + 4 - self->clock_in_ - self->nested_;
    }
  }
  static void on_step_pending(avr_irq_t*, uint32_t value, void* p) {
    auto* self = static_cast<Probe*>(p);
    if (value) self->step_pending_ = self->m_.cycles();
  }
  static void on_step_running(avr_irq_t*, uint32_t value, void* p) {
    auto* self = static_cast<Probe*>(p);
    avr_t* avr = self->m_.avr();
    const uint64_t now = self->m_.cycles();
    const avr_int_table_p table = &avr->interrupts;
    if (value) {
      StepIrq s;
      s.pending = self->step_pending_;
      s.entry = now - uint64_t(2 + avr->address_size);
      // The vector it interrupted is still on top of simavr's stack of
      // running vectors (the step vector is pushed after this callback).
      s.nested = table->running_ptr > 0 && table->running[table->running_ptr - 1]->vector == self->v_.clock;
      self->steps.push_back(s);
      self->step_in_ = s.entry;
    } else if (table->running_ptr > 0 && table->running[table->running_ptr - 1]->vector == self->v_.clock) {
      // Leaving a step vector that nested in the overflow vector (simavr has
      // popped it already: the overflow vector is on top again).
      self->nested_ += now + 4 - self->step_in_;
    }
  }

 public:
  // Marks the step interrupts whose match came after an overflow vector's
  // response had begun (a match on that very cycle wins: the step vector
  // comes first in the table) and before its RETI had ended: the ones the
  // overflow vector could hold off.
  void classify() {
    for (StepIrq& s : steps) {
      const auto e = std::lower_bound(clock_entries.begin(), clock_entries.end(), s.pending);
      if (e == clock_entries.begin()) continue;
      const size_t k = size_t(e - clock_entries.begin()) - 1;
      s.held = k < clock_exits.size() && s.pending < clock_exits[k];
    }
  }

 private:
  sim::Machine& m_;
  Vectors v_;
  uint16_t high_addr_ = 0;
  uint64_t step_pending_ = 0, clock_in_ = 0, step_in_ = 0, nested_ = 0;
};

// A call of the image's clock::now() from the main loop's context

}  // namespace clocktest
