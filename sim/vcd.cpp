#include "vcd.h"

#include <avr_ioport.h>
#include <avr_timer.h>
#include <sim_avr.h>
#include <sim_interrupts.h>
#include <sim_irq.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace sim {

namespace {

// Vector numbers from the datasheets (and avr-libc's <avr/iom*.h> *_vect_num).
const char* const kVectors328p[] = {
    "RESET",        "INT0",         "INT1",        "PCINT0",      "PCINT1",       "PCINT2",       "WDT",
    "TIMER2_COMPA", "TIMER2_COMPB", "TIMER2_OVF",  "TIMER1_CAPT", "TIMER1_COMPA", "TIMER1_COMPB", "TIMER1_OVF",
    "TIMER0_COMPA", "TIMER0_COMPB", "TIMER0_OVF",  "SPI_STC",     "USART_RX",     "USART_UDRE",   "USART_TX",
    "ADC",          "EE_READY",     "ANALOG_COMP", "TWI",         "SPM_READY"};
const char* const kVectors32[] = {
    "RESET",        "INT0",         "INT1",       "INT2",        "TIMER2_COMP", "TIMER2_OVF", "TIMER1_CAPT",
    "TIMER1_COMPA", "TIMER1_COMPB", "TIMER1_OVF", "TIMER0_COMP", "TIMER0_OVF",  "SPI_STC",    "USART_RXC",
    "USART_UDRE",   "USART_TXC",    "ADC",        "EE_RDY",      "ANA_COMP",    "TWI",        "SPM_RDY"};
const char* const kVectors16[] = {
    "RESET",        "INT0",       "INT1",       "TIMER2_COMP", "TIMER2_OVF", "TIMER1_CAPT", "TIMER1_COMPA",
    "TIMER1_COMPB", "TIMER1_OVF", "TIMER0_OVF", "SPI_STC",     "USART_RXC",  "USART_UDRE",  "USART_TXC",
    "ADC",          "EE_RDY",     "ANA_COMP",   "TWI",         "INT2",       "TIMER0_COMP", "SPM_RDY"};
const char* const kVectors1284p[] = {
    "RESET",        "INT0",         "INT1",         "INT2",         "PCINT0",      "PCINT1",       "PCINT2",
    "PCINT3",       "WDT",          "TIMER2_COMPA", "TIMER2_COMPB", "TIMER2_OVF",  "TIMER1_CAPT",  "TIMER1_COMPA",
    "TIMER1_COMPB", "TIMER1_OVF",   "TIMER0_COMPA", "TIMER0_COMPB", "TIMER0_OVF",  "SPI_STC",      "USART0_RX",
    "USART0_UDRE",  "USART0_TX",    "ANALOG_COMP",  "ADC",          "EE_READY",    "TWI",          "SPM_READY",
    "USART1_RX",    "USART1_UDRE",  "USART1_TX",    "TIMER3_CAPT",  "TIMER3_COMPA", "TIMER3_COMPB", "TIMER3_OVF"};

// Identifiers: printable ASCII without '$' (which starts VCD keywords).
std::string vcd_id(size_t index) {
  static const std::string alphabet = [] {
    std::string a;
    for (char c = 33; c < 127; ++c) {
      if (c != '$') a += c;
    }
    return a;
  }();
  std::string id;
  do {
    id += alphabet[index % alphabet.size()];
    index /= alphabet.size();
  } while (index > 0);
  return id;
}

// A VCD identifier-safe name: letters, digits and '_'.
std::string safe(const std::string& s) {
  std::string out;
  for (const char c : s) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return out.empty() ? "_" : out;
}

std::string pin_text(uint8_t code) { return std::string("P") + am::pin_port(code) + char('0' + am::pin_bit(code)); }

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t") - a + 1);
}

uint64_t stamp_ps(uint64_t cycle, uint32_t f) {
  if (1000000000000ull % f == 0) return cycle * (1000000000000ull / f);
  const unsigned __int128 ps = (static_cast<unsigned __int128>(cycle) * 1000000000000ull + f / 2) / f;
  return uint64_t(ps);
}

void write_value(std::FILE* out, int bits, uint32_t v, const std::string& id) {
  if (bits == 1) {
    std::fprintf(out, "%c%s\n", v ? '1' : '0', id.c_str());
    return;
  }
  char buf[40];
  int n = 0;
  for (int i = bits - 1; i >= 0; --i) {
    if (n == 0 && i > 0 && !((v >> i) & 1)) continue;  // no leading zeros
    buf[n++] = ((v >> i) & 1) ? '1' : '0';
  }
  buf[n] = 0;
  std::fprintf(out, "b%s %s\n", buf, id.c_str());
}

}  // namespace

const char* vector_name(const std::string& mcu, int vector) {
  const auto pick = [vector](const char* const* table, int n) -> const char* {
    return vector >= 0 && vector < n ? table[vector] : "";
  };
  if (mcu == "atmega328p" || mcu == "atmega328" || mcu == "atmega168" || mcu == "atmega88" || mcu == "atmega48") {
    return pick(kVectors328p, int(sizeof kVectors328p / sizeof *kVectors328p));
  }
  if (mcu == "atmega32") return pick(kVectors32, int(sizeof kVectors32 / sizeof *kVectors32));
  if (mcu == "atmega16") return pick(kVectors16, int(sizeof kVectors16 / sizeof *kVectors16));
  if (mcu == "atmega1284p") return pick(kVectors1284p, int(sizeof kVectors1284p / sizeof *kVectors1284p));
  return "";
}

struct VcdRecorder::Signal {
  VcdRecorder* rec;
  std::string scope, name, id;
  int bits;
  avr_irq_t* irq;
  bool always;       // declared even if it never changes
  uint32_t mask;     // 0: a level (nonzero low byte = 1); else the value's bits
  uint32_t initial;  // at the start of the recording
  uint32_t committed;
  uint32_t pending_value = 0;
  bool pending = false;
  bool changed = false;
};

void VcdRecorder::add(const std::string& scope, const std::string& name, int bits, avr_irq_t* irq, bool always,
                      uint32_t mask) {
  for (auto& s : signals_) {
    if (s->irq == irq) {  // named twice (board and X, say): once is enough
      s->always = s->always || always;
      return;
    }
  }
  std::unique_ptr<Signal> s(new Signal);
  s->rec = this;
  s->scope = scope;
  s->name = name;
  s->id = vcd_id(signals_.size());
  s->bits = bits;
  s->irq = irq;
  s->always = always;
  s->mask = mask;
  const uint32_t v = irq->value;
  s->initial = s->committed = mask ? (v & mask) : ((v & 0xff) != 0);
  avr_irq_register_notify(irq, &VcdRecorder::on_irq, s.get());
  signals_.push_back(std::move(s));
}

VcdRecorder::VcdRecorder(Machine& m, const std::string& path, const std::string& spec_in) : m_(m), path_(path) {
  avr_t* avr = m.avr();
  const am::BoardDescriptor& b = m.board();
  {  // fail now, not after the run, if the file cannot be written
    std::FILE* probe = std::fopen(path.c_str(), "w");
    if (!probe) throw std::runtime_error("cannot write " + path);
    std::fclose(probe);
  }
  body_ = std::tmpfile();
  if (!body_) throw std::runtime_error("cannot create a temporary file for " + path);
  cycle_ = m.cycles();
  start_stamp_ = last_stamp_ = stamp_ps(cycle_, m.f_cpu());

  const auto pin_irq = [&](uint8_t code) -> avr_irq_t* {
    return avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ(am::pin_port(code)), am::pin_bit(code));
  };
  const auto add_axis = [&](int i) {
    static const char* const roles[4][4] = {{"", "", "", ""},
                                            {"step", "dir", "enable", ""},
                                            {"latch", "clock", "data", "oe"},
                                            {"in1", "in2", "in3", "in4"}};
    const am::AxisDescriptor& d = b.axes[i];
    const int kind = int(d.kind) <= 3 ? int(d.kind) : 0;
    const std::string scope = d.kind == am::AxisKind::shield_latch ? "shield" : safe(std::string(1, d.name));
    for (int k = 0; k < 4; ++k) {
      if (d.pins[k] == am::kNoPin || !*roles[kind][k]) continue;
      avr_irq_t* irq = pin_irq(d.pins[k]);
      if (irq) add(scope, std::string(roles[kind][k]) + "_" + pin_text(d.pins[k]), 1, irq, true, 0);
    }
  };
  const auto add_vector = [&](avr_int_vector_t* v, bool always) {
    const char* vn = vector_name(b.mcu, v->vector);
    add("isr", "v" + std::to_string(v->vector) + (*vn ? std::string("_") + vn : ""), 1, v->irq + AVR_INT_IRQ_RUNNING,
        always, 0);
  };
  const auto add_pwm = [&](char timer, int ch, bool always) -> bool {
    avr_irq_t* irq = avr_io_getirq(avr, AVR_IOCTL_TIMER_GETIRQ(timer), TIMER_IRQ_OUT_PWM0 + ch);
    if (!irq) return false;
    const int bits = (timer == '1' || timer >= '3') ? 16 : 8;
    add("pwm", std::string("OC") + timer + char('A' + ch) + "_duty", bits, irq, always, (1u << bits) - 1);
    return true;
  };

  std::string spec = trim(spec_in).empty() ? "board,isr,pwm" : spec_in;
  size_t start = 0;
  while (start <= spec.size()) {
    const size_t comma = std::min(spec.find(',', start), spec.size());
    const std::string tok = trim(spec.substr(start, comma - start));
    start = comma + 1;
    if (tok.empty()) continue;
    std::string low = tok;
    for (char& c : low) c = char(std::tolower(static_cast<unsigned char>(c)));
    bool ok = false;
    if (low == "board") {
      for (int i = 0; i < b.axis_count; ++i) add_axis(i);
      ok = true;
    } else if (low == "isr") {
      std::vector<avr_int_vector_t*> vectors(avr->interrupts.vector,
                                             avr->interrupts.vector + avr->interrupts.vector_count);
      std::sort(vectors.begin(), vectors.end(),
                [](const avr_int_vector_t* x, const avr_int_vector_t* y) { return x->vector < y->vector; });
      for (avr_int_vector_t* v : vectors) add_vector(v, false);
      ok = true;
    } else if (low == "pwm") {
      for (char t = '0'; t <= '5'; ++t) {
        for (int ch = 0; ch < 2; ++ch) add_pwm(t, ch, false);
      }
      ok = true;
    } else if (low.size() > 3 && low.compare(0, 3, "isr") == 0 &&
               low.find_first_not_of("0123456789", 3) == std::string::npos) {
      const int n = std::atoi(low.c_str() + 3);
      for (int i = 0; i < avr->interrupts.vector_count; ++i) {
        if (avr->interrupts.vector[i]->vector == n) {
          add_vector(avr->interrupts.vector[i], true);
          ok = true;
        }
      }
    } else if (low.size() == 5 && low.compare(0, 3, "pwm") == 0 && std::isdigit(static_cast<unsigned char>(low[3]))) {
      const int ch = low[4] == 'a' || low[4] == '0' ? 0 : low[4] == 'b' || low[4] == '1' ? 1 : -1;
      ok = ch >= 0 && add_pwm(low[3], ch, true);
    } else if (low.size() == 3 && low[0] == 'p' && low[1] >= 'a' && low[1] <= 'd' && low[2] >= '0' && low[2] <= '7') {
      const uint8_t code = am::pin_code(char(std::toupper(static_cast<unsigned char>(low[1]))), uint8_t(low[2] - '0'));
      avr_irq_t* irq = pin_irq(code);
      if (irq) {
        add("pins", pin_text(code), 1, irq, true, 0);
        ok = true;
      }
    } else if (tok.size() == 1) {
      for (int i = 0; i < b.axis_count; ++i) {
        if (b.axes[i].name == tok[0]) {
          add_axis(i);
          ok = true;
        }
      }
    }
    if (!ok) {
      abandon();
      throw std::runtime_error("unknown VCD signal '" + tok + "' on " + b.board +
                               " (board, isr, pwm, an axis letter, a pin like PB3, isr<N>, pwm<timer><A|B>)");
    }
  }
}

VcdRecorder::~VcdRecorder() {
  try {
    finish();
  } catch (...) {
  }
}

void VcdRecorder::on_irq(avr_irq_t*, uint32_t value, void* param) {
  auto* s = static_cast<Signal*>(param);
  s->rec->change(*s, value);
}

// Changes come in cycle order, except timed events (a compare match, an OC
// pin) that fall inside an interrupt's response: simavr charges those 4 (or 5)
// cycles at once and raises the vector's running IRQ at their end, then runs
// the events with their own, earlier cycles (patch J). So the changes of the
// last kReorder cycles are held back and written sorted by cycle.
constexpr uint64_t kReorder = 16;

void VcdRecorder::change(Signal& s, uint32_t value) {
  const uint32_t v = s.mask ? (value & s.mask) : ((value & 0xff) != 0);
  const uint64_t now = m_.cycles();
  held_.push_back({now, &s, v});
  if (now > kReorder) release(now - kReorder);
}

void VcdRecorder::release(uint64_t through) {
  std::stable_sort(held_.begin(), held_.end(), [](const Held& a, const Held& b) { return a.cycle < b.cycle; });
  size_t n = 0;
  for (; n < held_.size() && held_[n].cycle <= through; ++n) stage(*held_[n].signal, held_[n].value, held_[n].cycle);
  held_.erase(held_.begin(), held_.begin() + long(n));
}

void VcdRecorder::stage(Signal& s, uint32_t v, uint64_t cycle) {
  // Never before what is written already (an event later than kReorder).
  if (cycle > cycle_) {
    flush_cycle();
    cycle_ = cycle;
  }
  if (!s.pending) {
    if (v == s.committed) return;
    s.pending = true;
    pending_.push_back(&s);
  }
  s.pending_value = v;
}

void VcdRecorder::flush_cycle() {
  bool stamped = false;
  for (Signal* s : pending_) {
    s->pending = false;
    if (s->pending_value == s->committed) continue;  // back where it was within the cycle
    if (!stamped) {
      const uint64_t t = stamp_ps(cycle_, m_.f_cpu());
      if (t != last_stamp_) std::fprintf(body_, "#%llu\n", static_cast<unsigned long long>(t));
      last_stamp_ = t;
      stamped = true;
    }
    s->committed = s->pending_value;
    s->changed = true;
    ++changes_;
    write_value(body_, s->bits, s->committed, s->id);
  }
  pending_.clear();
}

void VcdRecorder::abandon() {
  finished_ = true;
  for (auto& s : signals_) avr_irq_unregister_notify(s->irq, &VcdRecorder::on_irq, s.get());
  if (body_) std::fclose(body_);
  body_ = nullptr;
  std::remove(path_.c_str());
}

void VcdRecorder::finish() {
  if (finished_) return;
  finished_ = true;
  for (auto& s : signals_) avr_irq_unregister_notify(s->irq, &VcdRecorder::on_irq, s.get());
  if (!body_) return;
  release(UINT64_MAX);
  flush_cycle();

  const am::BoardDescriptor& b = m_.board();
  std::FILE* out = std::fopen(path_.c_str(), "w");
  if (!out) {
    std::fclose(body_);
    body_ = nullptr;
    throw std::runtime_error("cannot write " + path_);
  }
  const uint32_t f = m_.f_cpu();
  char cycle_ps[64];
  if (1000000000000ull % f == 0) {
    std::snprintf(cycle_ps, sizeof cycle_ps, "%llu ps", static_cast<unsigned long long>(1000000000000ull / f));
  } else {
    std::snprintf(cycle_ps, sizeof cycle_ps, "%.3f ps (stamps rounded to 1 ps)", 1e12 / f);
  }
  std::fprintf(out,
               "$version avrmotion-sim $end\n"
               "$comment %s (%s) at %u Hz: one CPU cycle is %s; cycle = round(time * f_cpu); "
               "time 0 is reset $end\n"
               "$timescale 1ps $end\n"
               "$scope module %s $end\n",
               b.board, b.mcu, unsigned(f), cycle_ps, safe(b.board).c_str());
  // Scopes in the order their first signal was added.
  std::vector<std::string> scopes;
  for (const auto& s : signals_) {
    if ((s->always || s->changed) && std::find(scopes.begin(), scopes.end(), s->scope) == scopes.end()) {
      scopes.push_back(s->scope);
    }
  }
  declared_.clear();
  for (const std::string& scope : scopes) {
    std::fprintf(out, "$scope module %s $end\n", scope.c_str());
    for (const auto& s : signals_) {
      if (s->scope != scope || !(s->always || s->changed)) continue;
      std::fprintf(out, "$var wire %d %s %s $end\n", s->bits, s->id.c_str(), s->name.c_str());
      declared_.push_back(scope + "." + s->name);
    }
    std::fprintf(out, "$upscope $end\n");
  }
  std::fprintf(out, "$upscope $end\n$enddefinitions $end\n");
  // The initial values, at the time the recording began.
  std::fprintf(out, "#%llu\n$dumpvars\n", static_cast<unsigned long long>(start_stamp_));
  for (const auto& s : signals_) {
    if (s->always || s->changed) write_value(out, s->bits, s->initial, s->id);
  }
  std::fprintf(out, "$end\n");
  std::rewind(body_);
  char buf[1 << 16];
  for (size_t n; (n = std::fread(buf, 1, sizeof buf, body_)) > 0;) std::fwrite(buf, 1, n, out);
  std::fclose(body_);
  body_ = nullptr;
  const uint64_t end = stamp_ps(m_.cycles(), f);
  if (end > last_stamp_) std::fprintf(out, "#%llu\n", static_cast<unsigned long long>(end));
  const bool ok = std::ferror(out) == 0;
  if (std::fclose(out) != 0 || !ok) throw std::runtime_error("cannot write " + path_);
}

}  // namespace sim
