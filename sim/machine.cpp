#include "machine.h"

#include <avr_adc.h>
#include <avr_eeprom.h>
#include <avr_ioport.h>
#include <avr_timer.h>
#include <sim_avr.h>
#include <sim_elf.h>
#include <sim_interrupts.h>
#include <sim_irq.h>

#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "../core/motor/shield_wiring.h"
#include "board_info.h"
#include "thermal_plant.h"

namespace sim {

namespace {

constexpr uint8_t kPaint = 0xA5;

// simavr's default sleep handler waits in wall-clock time; simulated time is
// all we want.
void no_sleep(avr_t*, avr_cycle_count_t) {}

// The machines by core, for the logger: simavr has one logger per process.
// (A constructor that throws leaves its core, and its entry, behind; that
// core never runs, so the entry is never looked up.)
std::map<const avr_t*, Machine*>& machines_by_core() {
  static std::map<const avr_t*, Machine*> machines;
  return machines;
}

}  // namespace

// What gets printed is what simavr's own logger prints (messages up to the
// core's log level, and errors always), except that it all goes to standard
// error, since the report owns standard output, and that messages without a
// core (its ELF loading, at debug level) are left out. Machines set the level
// to LOG_ERROR: its warnings are notes such as an OCR write before a timer's
// clock and mode are set, which the datasheet allows. Errors are counted for
// their machine, and fail its run (SimulatorFault).
void Machine::on_simavr_log(avr_t* avr, const int level, const char* format, va_list args) {
  if (level <= LOG_ERROR || (avr && avr->log >= level)) {
    va_list copy;
    va_copy(copy, args);
    std::vfprintf(stderr, format, copy);
    va_end(copy);
  }
  if (level != LOG_ERROR || !avr) return;
  const auto it = machines_by_core().find(avr);
  if (it == machines_by_core().end()) return;
  Machine* m = it->second;
  if (m->simavr_errors_++ == 0) {
    char text[256];
    std::vsnprintf(text, sizeof text, format, args);
    m->first_simavr_error_ = text;
    while (!m->first_simavr_error_.empty() && m->first_simavr_error_.back() == '\n')
      m->first_simavr_error_.pop_back();
  }
}

void Machine::throw_simavr_fault() const {
  throw SimulatorFault("simavr reported " + std::to_string(simavr_errors_) + " error(s) by cycle " +
                       std::to_string(avr_->cycle) + ", the first: \"" + first_simavr_error_ +
                       "\" (a lost event or an access it cannot simulate: the run is not valid)");
}

struct Machine::PinHook {
  Machine* machine;
  uint8_t code;
  bool level = false;
  bool known = false;
  std::vector<std::function<void(bool, uint64_t)>> listeners;
};

Machine::Machine(const std::string& elf_path)
    : board_(read_board_descriptor(elf_path)),
      starvations_(find_symbol(elf_path, "_ZN4path12_GLOBAL__N_111starvationsE")),
      elf_path_(elf_path) {
  avr_global_logger_set(&Machine::on_simavr_log);
  elf_firmware_t fw;
  std::memset(&fw, 0, sizeof fw);
  if (elf_read_firmware(elf_path.c_str(), &fw) != 0) throw std::runtime_error("cannot load " + elf_path);
  std::snprintf(fw.mmcu, sizeof fw.mmcu, "%s", board_.mcu);
  fw.frequency = board_.f_cpu;
  avr_ = avr_make_mcu_by_name(board_.mcu);
  if (!avr_) throw std::runtime_error(std::string("simavr has no core for ") + board_.mcu);
  machines_by_core()[avr_] = this;
  avr_init(avr_);
  avr_->log = LOG_ERROR;
  avr_->sleep = no_sleep;
  avr_load_firmware(avr_, &fw);
  std::free(fw.flash);
  std::free(fw.eeprom);
  std::free(fw.fuse);
  std::free(fw.lockbits);
  avr_->frequency = board_.f_cpu;

  const uint16_t ram_start = uint16_t(avr_->ioend + 1);
  paint_start_ = uint16_t(ram_start + fw.datasize + fw.bsssize);
  // .noinit (a soft reset's mark, firmware/apps/cnc/realtime.cpp) lies after
  // .bss: static data too, up to the linker's _end.
  const ElfSymbol end = find_symbol(elf_path, "_end");
  if (end.found && uint16_t(end.value) > paint_start_) paint_start_ = uint16_t(end.value);
  for (uint32_t a = ram_start; a <= avr_->ramend; ++a) avr_->data[a] = kPaint;

  serial_.reset(new SerialHost(avr_, board_.baud));
  if (!(board_.program & am::kProgramCommands)) serial_->set_wait_line("M400");
  attach_axes();
  attach_isr_profiler();
  // A board with a heater has its thermistor plugged in, at room temperature
  // until a ThermalPlant drives it.
  if (board_.heater_pin != am::kNoPin) set_adc_millivolts(board_.heater_adc, thermistor_input_mv(ThermalParams(), 25));
  for (uint8_t i = 0; i < board_.axis_count; ++i) {
    const am::AxisDescriptor& d = board_.axes[i];
    if (d.endstop != am::kNoPin)
      hold_input(am::pin_port(d.endstop), am::pin_bit(d.endstop), (d.option & am::kEndstopClosedHigh) == 0);
  }
}

Machine::~Machine() {
  if (avr_) avr_terminate(avr_);
  machines_by_core().erase(avr_);
}

uint64_t Machine::cycles() const { return avr_->cycle; }

size_t Machine::reset() {
  avr_reset(avr_);
  reapply_held();
  for (const auto& again : after_reset_) again();
  return serial_->on_reset();
}

const AxisTrace* Machine::axis(char name) const {
  for (const AxisTrace& a : axes_) {
    if (a.name == name) return &a;
  }
  return nullptr;
}

void Machine::on_pin_irq(avr_irq_t*, uint32_t value, void* param) {
  auto* hook = static_cast<PinHook*>(param);
  const bool level = value != 0;
  // simavr raises the pin IRQ on every port write: keep changes only.
  if (hook->known && level == hook->level) return;
  hook->known = true;
  hook->level = level;
  const uint64_t cycle = hook->machine->avr_->cycle;
  for (auto& f : hook->listeners) f(level, cycle);
}

void Machine::hook_pin(uint8_t code, std::function<void(bool, uint64_t)> on_change) {
  for (auto& h : pin_hooks_) {
    if (h->code == code) {
      h->listeners.push_back(std::move(on_change));
      return;
    }
  }
  pin_hooks_.emplace_back(new PinHook{this, code, false, false, {std::move(on_change)}});
  avr_irq_t* irq = avr_io_getirq(avr_, AVR_IOCTL_IOPORT_GETIRQ(am::pin_port(code)), am::pin_bit(code));
  if (!irq) throw std::runtime_error(std::string("no port ") + am::pin_port(code) + " on " + board_.mcu);
  avr_irq_register_notify(irq, &Machine::on_pin_irq, pin_hooks_.back().get());
}

void Machine::attach_axes() {
  axes_.resize(board_.axis_count);
  step_dir_.reserve(board_.axis_count);
  coils_.reserve(board_.axis_count);
  for (uint8_t i = 0; i < board_.axis_count; ++i) {
    const am::AxisDescriptor& d = board_.axes[i];
    AxisTrace& t = axes_[i];
    t.name = d.name;
    t.kind = int(d.kind);
    t.steps_per_mm = d.steps_per_m / 1000.0;
    switch (d.kind) {
      case am::AxisKind::step_dir: {
        step_dir_.emplace_back(&t);
        StepDirDecoder* dec = &step_dir_.back();
        hook_pin(d.pins[1], [dec](bool level, uint64_t) { dec->on_dir(level); });
        hook_pin(d.pins[0], [dec](bool level, uint64_t cycle) { dec->on_step(level, cycle); });
        break;
      }
      case am::AxisKind::shield_latch: {
        t.units_per_step = 2;
        coils_.emplace_back(&t);
        CoilDecoder* dec = &coils_.back();
        const am::ShieldStepperWiring wiring = am::shield_wiring(d.option);
        if (!latch_) {
          latch_.reset(new Latch595Model);
          const uint8_t data_pin = d.pins[2];
          hook_pin(data_pin, [](bool, uint64_t) {});  // track its level
          hook_pin(d.pins[1], [this, data_pin](bool level, uint64_t) {
            latch_->on_clock(level, pin_hooks_level(data_pin));
          });
          hook_pin(d.pins[0], [this](bool level, uint64_t cycle) {
            latch_->on_latch(level, cycle);
          });
          hook_pin(d.pins[3], [this](bool level, uint64_t) { latch_->on_enable(level); });
        }
        // Registered after the latch model's own listener, so it sees the
        // outputs the latch edge just produced.
        hook_pin(d.pins[0], [this, dec, wiring](bool level, uint64_t cycle) {
          if (level) dec->on_pattern(wiring.pattern(latch_->outputs()), cycle);
        });
        hook_pin(d.pins[3], [this, dec, wiring](bool, uint64_t cycle) {
          dec->on_pattern(wiring.pattern(latch_->outputs()), cycle);
        });
        break;
      }
      case am::AxisKind::unipolar4: {
        t.units_per_step = 2;
        coils_.emplace_back(&t);
        CoilDecoder* dec = &coils_.back();
        const uint8_t* pins = d.pins;
        const bool one_port = am::pin_port(pins[0]) == am::pin_port(pins[1]) &&
                              am::pin_port(pins[0]) == am::pin_port(pins[2]) &&
                              am::pin_port(pins[0]) == am::pin_port(pins[3]);
        if (one_port) {
          // One port write moves several pins at once, but simavr reports
          // them pin by pin; the port-wide IRQ shows the write as a whole.
          uint8_t bits[4];
          for (int k = 0; k < 4; ++k) bits[k] = am::pin_bit(pins[k]);
          hook_port(am::pin_port(pins[0]), [dec, bits](uint8_t value, uint64_t cycle) {
            uint8_t pattern = 0;
            for (int k = 0; k < 4; ++k) pattern |= uint8_t(((value >> bits[k]) & 1) << k);
            dec->on_pattern(pattern, cycle);
          });
        } else {
          auto pattern = std::make_shared<uint8_t>(0);
          for (uint8_t k = 0; k < 4; ++k) {
            hook_pin(pins[k], [dec, pattern, k](bool level, uint64_t cycle) {
              *pattern = uint8_t(level ? (*pattern | (1u << k)) : (*pattern & ~(1u << k)));
              dec->on_pattern(*pattern, cycle);
            });
          }
        }
        break;
      }
      default:
        break;
    }
  }
}

struct Machine::PortHook {
  avr_t* avr;
  std::function<void(uint8_t, uint64_t)> listener;
};

void Machine::on_port_irq(avr_irq_t*, uint32_t value, void* param) {
  auto* hook = static_cast<PortHook*>(param);
  hook->listener(uint8_t(value), hook->avr->cycle);
}

void Machine::hook_port(char port, std::function<void(uint8_t, uint64_t)> on_write) {
  port_hooks_.emplace_back(new PortHook{avr_, std::move(on_write)});
  avr_irq_t* irq = avr_io_getirq(avr_, AVR_IOCTL_IOPORT_GETIRQ(port), IOPORT_IRQ_PIN_ALL);
  if (!irq) throw std::runtime_error(std::string("no port ") + port + " on " + board_.mcu);
  avr_irq_register_notify(irq, &Machine::on_port_irq, port_hooks_.back().get());
}

bool Machine::pin_hooks_level(uint8_t code) const {
  for (const auto& h : pin_hooks_) {
    if (h->code == code) return h->level;
  }
  return false;
}

void Machine::on_isr_irq(avr_irq_t*, uint32_t value, void* param) {
  auto* hook = static_cast<std::pair<Machine*, int>*>(param);
  Machine* m = hook->first;
  const uint64_t now = m->avr_->cycle;
  if (value) {
    m->isr_entry_[hook->second] = now;
    return;
  }
  auto it = m->isr_entry_.find(hook->second);
  if (it == m->isr_entry_.end()) return;
  IsrStats& s = m->isr_[hook->second];
  const uint64_t spent = now - it->second;
  ++s.count;
  s.total_cycles += spent;
  if (spent > s.max_cycles) s.max_cycles = spent;
  m->isr_entry_.erase(it);
}

void Machine::attach_isr_profiler() {
  for (int i = 0; i < avr_->interrupts.vector_count; ++i) {
    avr_int_vector_t* v = avr_->interrupts.vector[i];
    isr_hooks_.emplace_back(new std::pair<Machine*, int>(this, v->vector));
    avr_irq_register_notify(v->irq + AVR_INT_IRQ_RUNNING, &Machine::on_isr_irq, isr_hooks_.back().get());
  }
}

unsigned Machine::free_ram() const { return unsigned(avr_->ramend - paint_start_ + 1); }

unsigned Machine::stack_bytes() const {
  for (uint32_t a = paint_start_; a <= avr_->ramend; ++a) {
    if (avr_->data[a] != kPaint) return unsigned(avr_->ramend - a + 1);
  }
  return 0;
}

int Machine::starvations() const {
  if (!starvations_.found) return -1;
  const uint16_t at = uint16_t(starvations_.value & 0xFFFF);  // the data-space offset off
  return avr_->data[at] | avr_->data[at + 1] << 8;
}

const std::vector<PinEdge>& Machine::watch_pin(char port, uint8_t bit) {
  const uint8_t code = am::pin_code(port, bit);
  std::vector<PinEdge>& log = watched_[code];
  hook_pin(code, [&log](bool level, uint64_t cycle) { log.push_back({cycle, level}); });
  return log;
}

void Machine::set_input(char port, uint8_t bit, bool level) {
  avr_raise_irq(avr_io_getirq(avr_, AVR_IOCTL_IOPORT_GETIRQ(port), bit), level ? 1 : 0);
}

// (simavr's EEPROM ioctls answer -1 whether they worked or not.)
std::vector<uint8_t> Machine::eeprom(uint32_t bytes) {
  avr_eeprom_desc_t d{nullptr, 0, bytes ? bytes : uint32_t(avr_->e2end + 1)};
  avr_ioctl(avr_, AVR_IOCTL_EEPROM_GET, &d);
  return d.ee ? std::vector<uint8_t>(d.ee, d.ee + d.size) : std::vector<uint8_t>();
}

void Machine::set_eeprom(std::vector<uint8_t> bytes) {
  avr_eeprom_desc_t d{bytes.data(), 0, uint32_t(bytes.size())};
  avr_ioctl(avr_, AVR_IOCTL_EEPROM_SET, &d);
}

void Machine::hold_input(char port, uint8_t bit, bool level) {
  auto& h = held_[port];
  const uint8_t mask = uint8_t(1u << bit);
  h.first = uint8_t(h.first | mask);
  h.second = uint8_t(level ? h.second | mask : h.second & ~mask);
  apply_held(port);
  set_input(port, bit, level);
}

void Machine::apply_held(char port) {
  const auto& h = held_.at(port);
  avr_ioport_external_t e;
  e.name = uint8_t(port);
  e.mask = h.first;
  e.value = h.second;
  avr_ioctl(avr_, AVR_IOCTL_IOPORT_SET_EXTERNAL(port), &e);
}

void Machine::reapply_held() {
  // A reset cleared the PIN registers but not the pins' last levels, and
  // simavr filters a level raised again unchanged: raised as a change (the
  // reset left every edge detector off).
  for (const auto& h : held_) {
    for (uint8_t bit = 0; bit < 8; ++bit) {
      if (!(h.second.first & (1u << bit))) continue;
      const uint32_t level = (h.second.second >> bit) & 1u;
      avr_irq_t* irq = avr_io_getirq(avr_, AVR_IOCTL_IOPORT_GETIRQ(h.first), bit);
      irq->value = level ^ 1u;
      avr_raise_irq(irq, level);
    }
  }
}

void Machine::set_adc_millivolts(uint8_t channel, uint32_t mv) {
  if (channel > 7) throw std::runtime_error("ADC channel out of range");
  if (!avr_->avcc) avr_->avcc = 5000;
  if (!avr_->vcc) avr_->vcc = 5000;
  if (!avr_->aref) avr_->aref = 5000;
  avr_irq_t* irq = avr_io_getirq(avr_, AVR_IOCTL_ADC_GETIRQ, ADC_IRQ_ADC0 + channel);
  if (!irq) throw std::runtime_error(std::string("no ADC on ") + board_.mcu);
  avr_raise_irq(irq, mv);
}

struct Machine::PwmHook {
  avr_t* avr;
  std::vector<PwmSample> log;
};

void Machine::on_pwm_irq(avr_irq_t*, uint32_t value, void* param) {
  auto* hook = static_cast<PwmHook*>(param);
  hook->log.push_back({hook->avr->cycle, uint16_t(value)});
}

const std::vector<PwmSample>& Machine::watch_pwm(char timer, uint8_t channel) {
  if (channel > 1) throw std::runtime_error("PWM channel is 0 (A) or 1 (B)");
  const int key = (timer << 1) | channel;
  auto it = pwm_hooks_.find(key);
  if (it != pwm_hooks_.end()) return it->second->log;
  avr_irq_t* irq = avr_io_getirq(avr_, AVR_IOCTL_TIMER_GETIRQ(timer), TIMER_IRQ_OUT_PWM0 + channel);
  if (!irq) throw std::runtime_error(std::string("no timer ") + timer + " on " + board_.mcu);
  PwmHook* hook = new PwmHook{avr_, {}};
  pwm_hooks_[key].reset(hook);
  avr_irq_register_notify(irq, &Machine::on_pwm_irq, hook);
  return hook->log;
}

uint16_t Machine::pwm_duty_at(const std::vector<PwmSample>& log, uint64_t cycle) {
  uint16_t duty = 0;  // the OCR reset value
  for (const PwmSample& s : log) {
    if (s.cycle > cycle) break;
    duty = s.duty;
  }
  return duty;
}

RunEnd Machine::run(const std::function<bool()>& stop, uint64_t budget) {
  const uint64_t end = avr_->cycle + budget;
  if (simavr_errors_) throw_simavr_fault();
  while (!stop()) {
    if (avr_->cycle >= end) return RunEnd::budget_spent;
    const int state = avr_run(avr_);
    if (simavr_errors_) throw_simavr_fault();
    if (state == cpu_Done || state == cpu_Crashed) return RunEnd::cpu_stopped;
  }
  return RunEnd::done;
}

}  // namespace sim
