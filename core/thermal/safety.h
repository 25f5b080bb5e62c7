// Heater safety rules as a pure state machine: fed the time, the reading, the
// target and the duty the controller asks for, it answers the duty that may
// be applied, and latches the first fault until reset.
//
// Contract
//   check(now_ms, reading, target, requested) once per controller period
//   (periods up to 500 ms keep the 1 s sensor bound; every rule is timed in
//   ms, not in samples) returns `requested`, or 0 while the reading is not a
//   temperature, or 0 for good once a fault has latched. fault() names the
//   first fault; reset() clears it and the rules start over as at power-on.
//   Times are uint32 ms compared by difference (wrap-safe). Rules, with
//   SafetyLimits' defaults (Marlin's), checked in this order:
//   - sensor_open / sensor_shorted: the reading has been a sensor fault for
//     sensor_fault_ms (500 ms) with no good reading between; always checked.
//     A break is latched within 500 ms plus one period: under 1 s.
//   - maxtemp: T > maxtemp (275 C), always.
//   - mintemp: T < mintemp (5 C) while target > 0 (a heater asked to heat
//     that reads so cold has a broken wire; off, a cold room is no fault).
//   - runaway (THERMAL_PROTECTION_PERIOD / _HYSTERESIS, 40 s / 4 C): once T
//     has reached the target (since the target was last changed), it must
//     not stay below target - 4 C for 40 s; a reading at or above target -
//     4 C restarts the 40 s. Covers a heater or a sensor that fell out while
//     holding.
//   - heating_failed (WATCH_TEMP_PERIOD / _INCREASE, 20 s / 2 C): while the
//     controller asks for full power (requested >= watch_output, 255) with
//     target > 0, T must rise by 2 C in each 20 s window, measured from T at
//     the window's start; leaving full power ends the watch.
//   The safe side of each limit is inclusive: T == maxtemp or mintemp, T ==
//   target - 4 C, a rise of exactly 2 C pass; a time limit trips when the
//   elapsed time reaches it.
//
//   Faults have stable numbers (HeaterFault) and short texts for "Error:..."
//   (Marlin-style) or "ALARM"/"[MSG:...]" (grbl-style) replies:
//   heater_fault_message() on the host; the firmware keeps a PROGMEM copy of
//   kHeaterFaultText (as the excitation table) and prints from flash.
//
//   temp_ok(): the TEMP_OK output, |T - target| <= band with a good reading,
//   target > 0 and (the member) no fault latched. Default band 3 C (Marlin's
//   TEMP_HYSTERESIS "close enough"). Given `was_ok` (the output as it is), an
//   output already high stays high out to band + kTempOkHysteresis (1 C):
//   the reading's noise at the band's edge does not make it chatter.
//
//   ATmega32 (avr-g++ 5.4 -Os): check() about 140 cycles, 39 bytes of RAM,
//   about 1.2 kB of flash with the 140-byte text table in PROGMEM.
#pragma once
#include <stdint.h>

#include "temperature.h"

namespace am {

enum class HeaterFault : uint8_t {
  none = 0,
  sensor_open = 1,
  sensor_shorted = 2,
  mintemp = 3,
  maxtemp = 4,
  runaway = 5,
  heating_failed = 6,
};

constexpr uint8_t kHeaterFaultCount = 7;
constexpr uint8_t kHeaterFaultTextSize = 20;

struct HeaterFaultText {
  char text[kHeaterFaultCount][kHeaterFaultTextSize];
};

constexpr HeaterFaultText kHeaterFaultText = {{"", "Thermistor open", "Thermistor shorted",
                                               "MINTEMP triggered", "MAXTEMP triggered",
                                               "Thermal Runaway", "Heating failed"}};

inline const char* heater_fault_message(HeaterFault f) {
  return uint8_t(f) < kHeaterFaultCount ? kHeaterFaultText.text[uint8_t(f)] : "";
}

struct SafetyLimits {
  int16_t maxtemp = centi_c(275);
  int16_t mintemp = centi_c(5);
  uint16_t sensor_fault_ms = 500;
  uint32_t runaway_period_ms = 40000;
  int16_t runaway_hysteresis = centi_c(4);
  uint32_t watch_period_ms = 20000;
  int16_t watch_increase = centi_c(2);
  uint8_t watch_output = 255;
};

constexpr int16_t kTempOkBand = centi_c(3);
constexpr int16_t kTempOkHysteresis = centi_c(1);

constexpr bool temp_ok(TempReading t, int16_t target, int16_t band = kTempOkBand, bool was_ok = false) {
  return t.ok() && target > 0 && int32_t(t.centi) - target <= band + (was_ok ? kTempOkHysteresis : 0) &&
         int32_t(target) - t.centi <= band + (was_ok ? kTempOkHysteresis : 0);
}

class HeaterSafety {
 public:
  constexpr explicit HeaterSafety(const SafetyLimits& limits = SafetyLimits()) : limits_(limits) {}

  // Not inlined, for flash: as HeaterPid::update (core/thermal/pid.h).
  [[gnu::noinline]] uint8_t check(uint32_t now_ms, TempReading t, int16_t target, uint8_t requested) {
    if (fault_ == HeaterFault::none) fault_ = evaluate(now_ms, t, target, requested);
    return fault_ == HeaterFault::none && t.ok() ? requested : 0;
  }

  HeaterFault fault() const { return fault_; }
  bool faulted() const { return fault_ != HeaterFault::none; }
  bool temp_ok(TempReading t, int16_t target, bool was_ok = false, int16_t band = kTempOkBand) const {
    return !faulted() && am::temp_ok(t, target, band, was_ok);
  }
  const SafetyLimits& limits() const { return limits_; }

  void reset() {
    fault_ = HeaterFault::none;
    sensor_bad_ = false;
    hold_ = Hold::inactive;
    tracked_target_ = 0;
    watching_ = false;
  }

 private:
  enum class Hold : uint8_t { inactive, first_heating, holding };

  HeaterFault evaluate(uint32_t now, TempReading t, int16_t target, uint8_t requested) {
    if (!t.ok()) {
      if (!sensor_bad_) {
        sensor_bad_ = true;
        bad_since_ = now;
      }
      if (now - bad_since_ < limits_.sensor_fault_ms) return HeaterFault::none;
      return t.state == SensorState::open ? HeaterFault::sensor_open : HeaterFault::sensor_shorted;
    }
    sensor_bad_ = false;
    const int32_t c = t.centi;
    if (c > limits_.maxtemp) return HeaterFault::maxtemp;
    if (target > 0 && c < limits_.mintemp) return HeaterFault::mintemp;

    if (target != tracked_target_) {
      tracked_target_ = target;
      hold_ = target > 0 ? Hold::first_heating : Hold::inactive;
    }
    if (hold_ == Hold::first_heating && c >= target) {
      hold_ = Hold::holding;
      holding_since_ = now;
    }
    if (hold_ == Hold::holding) {
      if (c >= int32_t(target) - limits_.runaway_hysteresis)
        holding_since_ = now;
      else if (now - holding_since_ >= limits_.runaway_period_ms)
        return HeaterFault::runaway;
    }

    if (target > 0 && requested >= limits_.watch_output) {
      if (!watching_) {
        watching_ = true;
        watch_since_ = now;
        watch_base_ = int16_t(c);
      } else if (now - watch_since_ >= limits_.watch_period_ms) {
        if (c < int32_t(watch_base_) + limits_.watch_increase) return HeaterFault::heating_failed;
        watch_since_ = now;
        watch_base_ = int16_t(c);
      }
    } else {
      watching_ = false;
    }
    return HeaterFault::none;
  }

  SafetyLimits limits_;
  HeaterFault fault_ = HeaterFault::none;
  bool sensor_bad_ = false;
  bool watching_ = false;
  Hold hold_ = Hold::inactive;
  int16_t tracked_target_ = 0;
  int16_t watch_base_ = 0;
  uint32_t bad_since_ = 0;
  uint32_t holding_since_ = 0;
  uint32_t watch_since_ = 0;
};

}  // namespace am
