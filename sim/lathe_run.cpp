#include "lathe_run.h"

#include <algorithm>
#include <cstdlib>
#include <memory>

#include "dc_servo.h"
#include "machine.h"

namespace sim {

namespace {

std::string field(const std::string& status, const std::string& key) {
  const size_t at = status.find(" " + key + "=");
  if (at == std::string::npos) return "";
  const size_t from = at + key.size() + 2, to = status.find(' ', from);
  return status.substr(from, to == std::string::npos ? std::string::npos : to - from);
}

// Sends a line as a sender would and runs until it is answered.
bool send(Machine& m, const std::string& line, double budget_s) {
  const size_t k = m.serial().responses().size();
  const std::string bytes = line + "\n";
  m.serial().relay(bytes.data(), bytes.size());
  m.run([&m, k] { return m.serial().responses().size() > k && !m.serial().responses()[k].answer.empty(); },
        uint64_t(budget_s * m.f_cpu()));
  return m.serial().responses().size() > k && m.serial().responses()[k].answer == "ok";
}

}  // namespace

LatheRunFigures run_lathe_pass(const std::string& elf, const SpindleParams& spindle_in, double rpm, double ramp_s,
                               double seconds, const std::string& encoder_line, const std::string& g33_line,
                               const ThreadSpec& thread) {
  LatheRunFigures f;
  Machine m(elf);
  const std::vector<PinEdge>& step = m.watch_pin('C', 0);
  const std::vector<PinEdge>& dir = m.watch_pin('C', 1);
  m.serial().relay_only();
  SpindleParams p = spindle_in;
  const double t0 = 0.2, t1 = t0 + ramp_s, t2 = t1 + seconds, t3 = t2 + ramp_s;
  p.profile = {{t0, 0}, {t1, rpm}, {t2, rpm}, {t3, 0}};
  SpindleEncoder spindle(m, p);
  std::unique_ptr<DcServo> servo;
  if (m.board().servo_pins[0] != am::kNoPin) servo.reset(new DcServo(m));
  m.run([&m] { return m.serial().banner_seen(); }, m.f_cpu());
  if (!send(m, encoder_line, 1) || !send(m, g33_line, 1)) return f;
  const uint64_t armed = m.serial().responses().back().sent_cycle;
  m.run([] { return false; }, uint64_t((t3 + 0.05) * m.f_cpu()) - m.cycles());
  const uint64_t until = m.cycles();
  if (!send(m, "?", 1)) return f;
  const std::vector<std::string>& rx = m.serial().received();
  f.status = rx.size() >= 2 ? rx[rx.size() - 2] : "";
  if (m.axis('Z')) f.pass = check_pass(spindle, *m.axis('Z'), step, thread, 0, armed, until);
  if (servo) {
    f.servo = true;
    f.servo_position = servo->position();
  }
  f.model_counts = spindle.counts();
  f.firmware_counts = std::atoll(field(f.status, "count").c_str());
  const std::string lost = field(f.status, "lost");
  f.firmware_lost = lost.empty() ? -1 : std::atoll(lost.c_str());
  f.edge_rate = rpm / 60 * (p.quadrature ? 4.0 : 1.0) * p.lines;

  f.pulses = pulse_timing(step, dir);
  static const std::vector<uint64_t> kNone;
  const std::vector<uint64_t>& c = m.axis('Z') ? m.axis('Z')->step_cycles : kNone;
  const uint64_t window = m.f_cpu() / 100;
  for (size_t a = 0, b = 0; b < c.size(); ++b) {
    while (c[b] - c[a] >= window) ++a;
    f.step_rate = std::max(f.step_rate, double(b - a + 1) * 100);
  }
  for (const auto& s : m.isr_stats())
    if (s.first == 1 || s.first == 2) f.vector_max = std::max(f.vector_max, s.second.max_cycles);
  f.ran = true;
  return f;
}

}  // namespace sim
