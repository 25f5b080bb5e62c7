// The print's measurements (print_watch.h).
#include "print_watch.h"

#include <avr_ioport.h>
#include <sim_avr.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>

namespace sim {

namespace {

// The line the firmware printed just before the `ok` of response `r`: the
// first `ok` after r's first byte went out (one line in flight; not r's
// answer_cycle, which a host's line lost at a reset shifts by one in a
// --pty run: the simulator pairs answers with lines in order).
bool line_before_ok(const SerialHost& serial, const Response& r, std::string& line) {
  const std::vector<std::string>& got = serial.received();
  const std::vector<uint64_t>& cycles = serial.received_cycles();
  for (size_t k = 1; k < got.size() && k < cycles.size(); ++k) {
    if (cycles[k] <= r.sent_cycle || !SerialHost::is_ok(got[k])) continue;
    line = got[k - 1];
    return true;
  }
  return false;
}

// The echo line of the last answered line with `code` ("M73"; a host's
// `N<n> ` before it as well) that `accept` takes.
template <typename Accept>
bool last_echo(const SerialHost& serial, const char* code, Accept accept) {
  const std::vector<Response>& rs = serial.responses();
  for (size_t i = rs.size(); i-- > 0;) {
    std::string line = rs[i].line, echo;
    if (line.size() > 1 && line[0] == 'N') line.erase(0, std::min(line.size(), line.find(' ') + 1));
    const size_t n = std::char_traits<char>::length(code);
    if (line.compare(0, n, code) != 0 || (line.size() > n && line[n] != ' '))
      continue;
    if (line_before_ok(serial, rs[i], echo) && echo.rfind("echo:", 0) == 0 && accept(echo.substr(5))) return true;
  }
  return false;
}

}  // namespace

int last_progress(const SerialHost& serial) {
  int percent = -1;
  last_echo(serial, "M73", [&](const std::string& text) {
    const std::string prefix = "Progress: ";
    if (text.rfind(prefix, 0) != 0) return false;
    size_t k = prefix.size(), digits = 0;
    int p = 0;
    while (k < text.size() && std::isdigit(static_cast<unsigned char>(text[k])) && digits < 4)
      p = p * 10 + (text[k++] - '0'), ++digits;
    if (!digits || k >= text.size() || text[k] != '%') return false;  // M73 R5's: an earlier one's
    percent = p;
    return true;
  });
  return percent;
}

bool last_message(const SerialHost& serial, std::string& text) {
  return last_echo(serial, "M117", [&](const std::string& echo) {
    text = echo;
    return true;
  });
}

PrintWatch::PrintWatch(Machine& m, const ThermalPlant* plant, const Endstops* switches)
    : m_(m), plant_(plant), switches_(switches) {
  const am::BoardDescriptor& b = m.board();
  const AxisTrace* e = m.axis('E');
  uint8_t step_pin = am::kNoPin;
  for (uint8_t i = 0; i < b.axis_count; ++i)
    if (b.axes[i].name == 'E' && b.axes[i].kind == am::AxisKind::step_dir) step_pin = b.axes[i].pins[0];
  if (!e || step_pin == am::kNoPin) throw std::runtime_error("PrintWatch: the board has no step/dir axis E");
  most_e_ = e->steps();
  m.listen_pin(am::pin_port(step_pin), am::pin_bit(step_pin), [this, e](bool, uint64_t cycle) {
    if (first_extrusion_ || e->steps() <= most_e_) {
      if (e->steps() > most_e_) most_e_ = e->steps();
      return;
    }
    first_extrusion_ = cycle ? cycle : 1;
    if (plant_) {
      sensor_c_ = plant_->sensor_c();
      block_c_ = plant_->block_c();
    }
  });
}

std::string PrintWatch::enabled_now() const {
  const am::BoardDescriptor& b = m_.board();
  std::string out;
  for (uint8_t i = 0; i < b.axis_count; ++i) {
    const am::AxisDescriptor& a = b.axes[i];
    if (a.kind != am::AxisKind::step_dir || a.pins[2] == am::kNoPin) continue;
    avr_ioport_state_t st;
    if (avr_ioctl(m_.avr(), AVR_IOCTL_IOPORT_GETSTATE(am::pin_port(a.pins[2])), &st) != 0) continue;
    const unsigned bit = 1u << am::pin_bit(a.pins[2]);
    const bool output = st.ddr & bit, high = st.port & bit, active_low = a.option & 1;
    if (output && high != active_low) out += a.name;
  }
  return out;
}

unsigned PrintWatch::switch_closes(char name) const {
  if (!switches_ || !switches_->has(name)) return 0;
  const size_t n = switches_->contact_changes(name).size();
  if (n == 0) return 0;
  // The changes alternate; the first is the contact at the start.
  const bool first_closed = switches_->closed(name) == ((n - 1) % 2 == 0);
  return unsigned(first_closed ? (n + 1) / 2 : n / 2);
}

bool PrintWatch::heater_pin_now() const {
  if (!plant_) return false;
  const std::vector<PinEdge>& edges = plant_->heater_pin();
  return !edges.empty() && edges.back().level;
}

double PrintWatch::heater_duty_last() const {
  return plant_ && !plant_->log().empty() ? plant_->log().back().duty : -1;
}

double PrintWatch::target_c_last() const {
  if (!plant_ || plant_->log().empty() || std::isnan(plant_->log().back().target_c)) return -1;
  return plant_->log().back().target_c;
}

}  // namespace sim
