// A bipolar stepper on the Adafruit Motor Shield v1: its four bridge inputs
// sit on the shield's 74HC595 and its two L293D enables on PWM channels.
//
// Contract
//   Modes (set_mode, docs/modes.md): 0 wave, 1 two-phase (power-up default),
//   2 half step, 16/32/64 microsteps per full step. The rotor is one angle in
//   1/64 full step (am::ExcitationCursor), so a mode change never moves it.
//   - full/half/wave: the latch shows the half-step state, both enables at 255
//     (constant high in fast PWM);
//   - microsteps: the enables carry the sine currents (8-bit fast PWM, EnableA
//     = winding A, EnableB = winding B), the latch the coils that carry
//     current and their polarity (a winding at duty 0 gets both inputs low).
//   energise() shows the current angle (the first one after power-up snaps to
//   the mode's grid, as PhaseSequencer does); release() turns both windings off
//   and keeps the angle. EnableA/EnableB: types with init() and set(uint8_t)
//   (hal/avr/pwm8.h). energise() may run while the step interrupt moves
//   this or the other shield stepper (the planner holds the next move's axis
//   once the previous move is queued), so the main-context entry points
//   update the shared latch image with interrupts off.
//
// Both shield steppers share the latch, so the latch image lives in one place
// (ShieldLatch) and a step rewrites only the four bits of its own stepper
// before shifting the whole byte out. What a step shows comes from a table in
// flash built at compile time (768 bytes a stepper): the step interrupt does
// the angle arithmetic, three LPM reads, two OCR writes and the latch shift,
// the same instructions in every mode but for one branch (sine table or
// half-step table).
#pragma once
#include <avr/io.h>
#include <avr/pgmspace.h>
#include <stdint.h>

#include "../../core/board/descriptor.h"
#include "../../core/motor/microstep.h"
#include "../../core/motor/phase_sequencer.h"
#include "../../core/motor/shield_wiring.h"
#include "../../hal/avr/gpio.h"
#include "../../hal/avr/latch595.h"
#include "axis_set.h"

template <typename Latch>
struct ShieldLatch {
  static uint8_t image;
  static bool dirty;  // a step changed the image; the latch has not seen it
};
template <typename Latch>
uint8_t ShieldLatch<Latch>::image = 0;
template <typename Latch>
bool ShieldLatch<Latch>::dirty = false;

// One table per shield stepper number, in flash.
template <uint8_t Number>
struct ShieldTable {
  static constexpr am::ShieldStepperWiring wiring = am::shield_wiring(Number);
  static const am::ExcitationTable value;
};
template <uint8_t Number>
const am::ExcitationTable ShieldTable<Number>::value PROGMEM =
    am::ExcitationTable(wiring.a_pos, wiring.b_pos, wiring.a_neg, wiring.b_neg);

template <char Name, uint8_t Number, typename Latch, typename EnableA, typename EnableB,
          uint32_t StepsPerMetre>
struct ShieldStepper {
  static constexpr char name = Name;
  static constexpr uint32_t claims = EnableA::claims | EnableB::claims;
  static am::ExcitationCursor cursor;
  static bool energised;
  static bool placed;  // the angle is where the rotor is (energised once)

  static void init() {
    EnableA::init();
    EnableB::init();
  }
  static void energise() {
    const uint8_t sreg = SREG;
    __asm__ __volatile__("cli" ::: "memory");
    if (!placed) {
      cursor.snap_down();
      placed = true;
    }
    energised = true;
    const uint8_t a = cursor.angle();
    // Off its mode's grid (after a mode change) the rotor is held where it is
    // by the sine currents of its exact angle; the next step reaches the grid.
    if (!cursor.microstepping() && cursor.on_grid()) show(&table().full[a >> 5]);
    else show(&table().micro[a]);
    SREG = sreg;
  }
  static void release() {
    const uint8_t sreg = SREG;
    __asm__ __volatile__("cli" ::: "memory");
    energised = false;
    EnableA::set(0);
    EnableB::set(0);
    write_latch(0);
    SREG = sreg;
  }
  // Rotor travel of a move, in 1/64 full step: a grid step of the current
  // mode per step, except that the first step after a mode change that left
  // the angle off the new grid only reaches the next grid point. That can
  // only be the case when the axis is idle (modes change only then), and
  // then the cursor is exactly where the move starts.
  static constexpr uint8_t units_per_full_step = am::ExcitationCursor::units_per_full_step;
  static int32_t units_for(int32_t steps, bool idle) {
    if (steps == 0) return 0;
    const bool forward = steps > 0;
    const uint32_t n = forward ? uint32_t(steps) : uint32_t(-(steps + 1)) + 1u;
    const uint8_t grid = am::excitation::grid_step(cursor.mode());
    uint32_t first = grid;
    if (idle) {
      am::ExcitationCursor probe = cursor;
      const uint8_t from = probe.angle();
      const uint8_t to = probe.step(forward);
      first = uint8_t(forward ? to - from : from - to);
    }
    const int32_t units = int32_t(first + (n - 1) * grid);
    return forward ? units : -units;
  }
  // Called only while the axis is idle (the protocol waits for motion to end).
  static bool set_mode(uint8_t mode) {
    if (!cursor.set_mode(mode)) return false;
    if (energised) energise();  // same angle: full current on a grid point
    return true;
  }
  static void set_direction(bool) {}
  // A step sets its duties and its four bits of the latch image; the latch
  // is shifted out once per step event, after every axis has staged its
  // step, so both steppers of a coordinated move change in one write.
  static void pulse_begin(bool forward) {
    const uint8_t a = cursor.step(forward);
    if (cursor.microstepping()) stage(&table().micro[a]);
    else stage(&table().full[a >> 5]);
  }
  static void pulse_commit() {
    if (!ShieldLatch<Latch>::dirty) return;
    ShieldLatch<Latch>::dirty = false;
    Latch::write(ShieldLatch<Latch>::image);
  }
  static void pulse_end() {}

  static constexpr am::AxisDescriptor descriptor() {
    // The latch pins are shared; the descriptor names them for the decoder.
    return am::AxisDescriptor{Name, am::AxisKind::shield_latch,
                              {am::pin_code(Latch::Storage::port, Latch::Storage::bit),
                               am::pin_code(Latch::Clock::port, Latch::Clock::bit),
                               am::pin_code(Latch::Data::port, Latch::Data::bit),
                               am::pin_code(Latch::Enable::port, Latch::Enable::bit)},
                              Number, 0, StepsPerMetre};
  }

 private:
  static const am::ExcitationTable& table() { return ShieldTable<Number>::value; }

  // Duties first: OCR writes take effect at the next PWM period anyway, the
  // latch at once, so the new coils never see a stale duty for long.
  static void stage(const am::ExcitationEntry* e) {
    EnableA::set(pgm_read_byte(&e->pwm_a));
    EnableB::set(pgm_read_byte(&e->pwm_b));
    stage_bits(pgm_read_byte(&e->bits));
  }
  static void stage_bits(uint8_t bits) {
    constexpr uint8_t mask = am::shield_wiring(Number).mask();
    uint8_t& image = ShieldLatch<Latch>::image;
    image = uint8_t((image & ~mask) | bits);
    ShieldLatch<Latch>::dirty = true;
  }
  static void show(const am::ExcitationEntry* e) {
    stage(e);
    pulse_commit();
  }
  static void write_latch(uint8_t bits) {
    stage_bits(bits);
    pulse_commit();
  }
};

template <char Name, uint8_t Number, typename Latch, typename EnableA, typename EnableB, uint32_t S>
am::ExcitationCursor ShieldStepper<Name, Number, Latch, EnableA, EnableB, S>::cursor;
template <char Name, uint8_t Number, typename Latch, typename EnableA, typename EnableB, uint32_t S>
bool ShieldStepper<Name, Number, Latch, EnableA, EnableB, S>::energised;
template <char Name, uint8_t Number, typename Latch, typename EnableA, typename EnableB, uint32_t S>
bool ShieldStepper<Name, Number, Latch, EnableA, EnableB, S>::placed;
