// The board descriptor record (core/board_descriptor.h) for this image, kept
// in its own ELF section at a fixed address far outside flash and RAM: the
// simulator reads it, the .hex for flashing leaves it out.
#include "../core/board/descriptor.h"
#include "board.h"

namespace {

// The heater's wiring, on a board that declares one (board.h: kHeater).
template <bool Present, typename Hw = board::Heater>
struct HeaterWiring {
  static constexpr uint8_t pwm = am::kNoPin, adc = am::kNoPin, ok = am::kNoPin;
};
template <typename Hw>
struct HeaterWiring<true, Hw> {
  static constexpr uint8_t pwm = am::pin_code(Hw::Pwm::OutPin::port, Hw::Pwm::OutPin::bit);
  static constexpr uint8_t adc = Hw::adc_channel;
  static constexpr uint8_t ok = am::pin_code(Hw::TempOk::port, Hw::TempOk::bit);
};
using Heater = HeaterWiring<board::kHeater>;

// An axis's entry with its endstop (firmware/axes/endstops.h), if it has one.
constexpr am::AxisDescriptor with_endstop(am::AxisDescriptor d) {
  using Endstops = board::Endstops;
  const uint8_t bit = endstops_detail::Letter<board::Axes>::bit(d.name);
  d.endstop = Endstops::Each::pin_of(bit);
  if (d.endstop == am::kNoPin) return d;
  if (Endstops::max_end & bit) d.option = uint8_t(d.option | am::kEndstopAtMax);
  if (Endstops::closed_high) d.option = uint8_t(d.option | am::kEndstopClosedHigh);
  return d;
}

// The spindle encoder's wiring, on a lathe board (board.h: kSpindleEncoder).
template <bool Present, typename Hw = board::SpindlePins>
struct SpindleWiring {
  static constexpr uint8_t a = am::kNoPin, b = am::kNoPin, index = am::kNoPin, limit = am::kNoPin;
};
// Channel B, on a board whose spindle has one (a quadrature encoder).
template <typename Hw, typename = void>
struct SpindleB {
  static constexpr uint8_t pin = am::kNoPin;
};
template <typename Hw>
struct SpindleB<Hw, decltype(void(Hw::B::bit))> {
  static constexpr uint8_t pin = am::pin_code(Hw::B::port, Hw::B::bit);
};
template <typename Hw>
struct SpindleWiring<true, Hw> {
  static constexpr uint8_t a = am::pin_code(Hw::A::port, Hw::A::bit);
  static constexpr uint8_t b = SpindleB<Hw>::pin;
  static constexpr uint8_t index = am::pin_code(Hw::Index::port, Hw::Index::bit);
  static constexpr uint8_t limit = am::pin_code(Hw::Limit::port, Hw::Limit::bit);
};
using Spindle = SpindleWiring<board::kSpindleEncoder>;

// A DC-servo leadscrew's wiring (board.h: kServoLeadscrew).
template <bool Present, typename Hw = board::ServoPins>
struct ServoWiring {
  static constexpr uint8_t pwm = am::kNoPin, in1 = am::kNoPin, in2 = am::kNoPin, encoder = am::kNoPin;
};
template <typename Hw>
struct ServoWiring<true, Hw> {
  static constexpr uint8_t pwm = am::pin_code(Hw::Pwm::port, Hw::Pwm::bit);
  static constexpr uint8_t in1 = am::pin_code(Hw::In1::port, Hw::In1::bit);
  static constexpr uint8_t in2 = am::pin_code(Hw::In2::port, Hw::In2::bit);
  static constexpr uint8_t encoder = am::pin_code(Hw::Encoder::port, Hw::Encoder::bit);
};
using Servo = ServoWiring<board::kServoLeadscrew>;

template <typename Set>
struct Describe;

template <typename... Axes>
struct Describe<AxisSet<Axes...>> {
  static_assert(sizeof...(Axes) <= am::kMaxAxes, "the descriptor holds six axes");
  static constexpr am::BoardDescriptor make() {
    return am::BoardDescriptor{{'A', 'M', 'B', '4'}, AVRMOTION_BOARD_NAME, AVRMOTION_MCU_NAME,
                               F_CPU, board::kBaud, uint8_t(sizeof...(Axes)), Heater::pwm, Heater::adc, Heater::ok,
                               uint8_t((board::kGcode ? am::kProgramGcode : 0) |
                                       (board::kCommands ? am::kProgramCommands : 0) |
                                       (board::kRealtime ? am::kProgramRealtime : 0)),
                               {0, 0, 0},
                               {with_endstop(Axes::descriptor())...},
                               {Spindle::a, Spindle::b, Spindle::index, Spindle::limit},
                               {Servo::pwm, Servo::in1, Servo::in2, Servo::encoder}};
  }
};

}  // namespace

extern "C" __attribute__((used, section(".avrmotion_board")))
const am::BoardDescriptor avrmotion_board = Describe<board::Axes>::make();
