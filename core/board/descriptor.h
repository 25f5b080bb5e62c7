// The board descriptor: a fixed-layout record that every firmware image
// carries in its ELF (section .avrmotion_board, outside flash and RAM), so the
// simulator decodes any board's outputs without a second copy of its pin map.
//
// Contract
//   The layout is identical on the AVR and on the host: every field sits at a
//   naturally aligned offset and the sizes are checked below. A pin is encoded
//   as (port << 4) | bit with port 0 = A ... 3 = D; kNoPin = not connected.
//   Bump kBoardDescriptorMagic when the layout changes.
#pragma once
#include <stdint.h>

namespace am {

constexpr uint8_t kNoPin = 0xFF;
constexpr uint8_t pin_code(char port, uint8_t bit) { return uint8_t(((port - 'A') << 4) | bit); }
constexpr char pin_port(uint8_t code) { return char('A' + (code >> 4)); }
constexpr uint8_t pin_bit(uint8_t code) { return code & 7; }

enum class AxisKind : uint8_t {
  none = 0,
  step_dir = 1,      // pins: step, dir, enable; option bit0: enable active low
  shield_latch = 2,  // pins: latch, clock, data, output-enable (active low);
                     // option: stepper number on the shield (1 or 2)
  unipolar4 = 3,     // pins: IN1..IN4 (A+, B+, A-, B-)
};

struct AxisDescriptor {
  char name;              // 'X', 'Y', 'Z', 'E'
  AxisKind kind;
  uint8_t pins[4];
  uint8_t option;         // bit 0 see kind; kEndstop* bits
  uint8_t endstop;        // its endstop's pin, kNoPin if it has none
  uint32_t steps_per_m;   // full steps per metre of travel
};

// An axis's endstop (AxisDescriptor::option): at the axis's maximum end (else
// its minimum); closed reads high (else low, a switch to ground).
constexpr uint8_t kEndstopAtMax = 2, kEndstopClosedHigh = 4;

constexpr uint8_t kMaxAxes = 6;

// BoardDescriptor::program: G-code lines; the direct commands (MOVE, WAIT,
// ...); grbl's realtime bytes.
constexpr uint8_t kProgramGcode = 1, kProgramCommands = 2, kProgramRealtime = 4;

struct BoardDescriptor {
  char magic[4];          // "AMB4"
  char board[16];         // NUL-terminated
  char mcu[12];           // simavr's part name, NUL-terminated
  uint32_t f_cpu;
  uint32_t baud;
  uint8_t axis_count;
  // The heater (kNoPin for all three on a board without one): its MOSFET's
  // PWM pin, its thermistor's ADC channel (0..7), its TEMP_OK pin.
  uint8_t heater_pin;
  uint8_t heater_adc;
  uint8_t temp_ok_pin;
  uint8_t program;  // kProgram* bits: what the image's line protocol takes
  uint8_t reserved[3];
  AxisDescriptor axes[kMaxAxes];
  // A lathe's spindle encoder (kNoPin for all four on other boards): channel
  // A, channel B (quadrature), the index, the carriage's limit switch.
  uint8_t spindle_pins[4];
  // A DC-servo leadscrew (kNoPin for all four on other boards): the bridge's
  // enable (the PWM), its two direction inputs (IN1 high alone: +, IN2 high
  // alone: -, both low: brake), the motor encoder's channel.
  uint8_t servo_pins[4];
};

static_assert(sizeof(AxisDescriptor) == 12, "descriptor layout must match on host and AVR");
static_assert(sizeof(BoardDescriptor) == 128, "descriptor layout must match on host and AVR");

}  // namespace am
