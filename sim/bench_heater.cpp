// The benchmark's hot-end run (bench.h, HeaterFigures): the m32 image, the
// simulated 40 W hot end of sim/thermal_plant.h, M104 S200 from 25 C, and
// the plant's 100 ms log read for the settling figures. In the run's last
// 10 s every heater::poll() call is timed from its first instruction to
// its return (interrupts included): the calls that ran a PID sample are
// the ones over kSampleFloor cycles (the others only look at the ADC and
// the clock, about 100).
#include <algorithm>
#include <cmath>

#include "bench.h"
#include "board_info.h"
#include "machine.h"
#include "thermal_plant.h"

#include <sim_avr.h>

namespace bench {

namespace {
constexpr uint64_t kSampleFloor = 1000;
constexpr double kTarget = 200, kBand = 0.3;
}  // namespace

HeaterFigures measure_heater(const std::string& dir) {
  HeaterFigures h;
  const std::string elf = dir + "/avrmotion-m32.elf";
  const sim::ElfSymbol poll = sim::find_symbol(elf, "_ZN6heater4pollEv");
  if (!poll.found) return h;
  sim::Machine m(elf);
  sim::ThermalPlant plant(m);
  m.serial().add_line("M104 S200");
  const uint64_t f = m.f_cpu(), timed_from = uint64_t((kHeaterSeconds - 10) * f);
  avr_t* avr = m.avr();
  bool in_poll = false;
  uint64_t entered = 0, total = 0;
  uint16_t sp_in = 0;
  const auto sp = [avr] { return uint16_t(avr->data[R_SPL] | avr->data[R_SPH] << 8); };
  const sim::RunEnd end = m.run(
      [&] {
        if (avr->cycle < timed_from) return false;
        if (!in_poll && avr->pc == poll.value) {
          in_poll = true;
          entered = avr->cycle;
          sp_in = sp();
        } else if (in_poll && sp() > sp_in) {  // its RET popped the return address
          in_poll = false;
          const uint64_t c = avr->cycle - entered;
          if (c > kSampleFloor) {
            ++h.samples;
            total += c;
            h.sample_cycles_max = std::max(h.sample_cycles_max, c);
          }
        }
        return avr->cycle >= uint64_t(kHeaterSeconds * f);
      },
      uint64_t((kHeaterSeconds + 1) * f));
  if (end != sim::RunEnd::done || plant.fault() != sim::ThermalFault::none) return h;
  const std::vector<sim::ThermalSample>& log = plant.log();
  size_t reached = log.size(), settled = log.size();
  for (size_t i = 0; i < log.size(); ++i) {
    if (reached == log.size() && log[i].sensor_c >= kTarget) reached = i;
    if (std::fabs(log[i].sensor_c - kTarget) > kBand) settled = i + 1;
  }
  if (reached == log.size() || settled >= log.size() || h.samples == 0) return h;
  h.to_target_s = log[reached].t_s;
  h.settled_s = log[settled].t_s;
  h.hold_lo_c = h.hold_hi_c = log[settled].sensor_c;
  for (size_t i = reached; i < log.size(); ++i) h.overshoot_c = std::max(h.overshoot_c, log[i].sensor_c - kTarget);
  for (size_t i = settled; i < log.size(); ++i) {
    h.hold_lo_c = std::min(h.hold_lo_c, log[i].sensor_c);
    h.hold_hi_c = std::max(h.hold_hi_c, log[i].sensor_c);
  }
  h.sample_cycles = double(total) / double(h.samples);
  h.ok = true;
  return h;
}

}  // namespace bench
