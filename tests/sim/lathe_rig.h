// The m16-lathe image (LatheRig) or the m16-servo image (ServoRig) with a
// simulated spindle, for the lathe tests: lines
// go out as a sender's (relay mode: no WAIT of the host's own between them),
// one at a time, each run until its answer.
#pragma once
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "dc_servo.h"
#include "lathe_check.h"
#include "sim_fixture.h"
#include "spindle_encoder.h"

namespace simtest {

// What both lathe rigs share: a lathe image relayed line by line over its
// UART, its spindle simulated (the rig adds the leadscrew's side).
struct LatheUart {
  LatheUart(const char* name, const sim::SpindleParams& p) : m(new sim::Machine(image(name))) {
    m->serial().relay_only();
    spindle.reset(new sim::SpindleEncoder(*m, p));
  }
  void wait_banner() {
    m->run([this] { return m->serial().banner_seen(); }, m->f_cpu());
  }

  // Sends `line`, runs until it is answered; returns the answer ("" if the
  // budget ran out).
  std::string send(const std::string& line, double budget_s = 1) {
    const size_t k = m->serial().responses().size();
    m->serial().relay(line.data(), line.size());
    m->serial().relay("\n", 1);
    m->run([this, k] { return m->serial().responses().size() > k && !m->serial().responses()[k].answer.empty(); },
           uint64_t(budget_s * m->f_cpu()));
    if (m->serial().responses().size() <= k) return "";
    last = m->serial().responses()[k];
    return last.answer;
  }

  // The status line ("state=... z=..."), "" if none came.
  std::string status() {
    if (send("?") != "ok") return "";
    const auto& r = m->serial().received();
    return r.size() >= 2 ? r[r.size() - 2] : "";
  }

  // Runs until the leadscrew is idle (WAIT), at most budget_s.
  bool wait_idle(double budget_s) { return send("WAIT", budget_s) == "ok"; }

  std::unique_ptr<sim::Machine> m;
  std::unique_ptr<sim::SpindleEncoder> spindle;
  sim::Response last;
};

struct LatheRig : LatheUart {
  explicit LatheRig(const sim::SpindleParams& p)
      : LatheUart("m16-lathe", p), step(&m->watch_pin('C', 0)), dir(&m->watch_pin('C', 1)) {
    wait_banner();
  }

  void run_for(double s) {
    m->run([] { return false; }, uint64_t(s * m->f_cpu()));
  }
  // The cycle a pass's line was received whole: it was armed after it.
  uint64_t armed_after() const { return last.sent_cycle; }

  const sim::AxisTrace& z() const { return *m->axis('Z'); }

  const std::vector<sim::PinEdge>* step;
  const std::vector<sim::PinEdge>* dir;
};

// A status line's field ("z", "err", "state", ...), "" when absent.
inline std::string field(const std::string& status, const std::string& key) {
  const std::string k = key + "=";
  size_t at = status.find(" " + k);
  at = at == std::string::npos ? (status.rfind(k, 0) == 0 ? 0 : std::string::npos) : at + 1;
  if (at == std::string::npos) return "";
  const size_t from = at + k.size(), to = status.find(' ', from);
  return status.substr(from, to == std::string::npos ? std::string::npos : to - from);
}

}  // namespace simtest

namespace simtest {

// The m16-servo image with a simulated spindle and the seed's DC servo
// (sim/dc_servo.h) on its leadscrew; lines as LatheRig sends them.
struct ServoRig : LatheUart {
  explicit ServoRig(const sim::SpindleParams& p, const sim::ServoParams& s = sim::ServoParams())
      : LatheUart("m16-servo", p), enable(&m->watch_pin('D', 5)), in1(&m->watch_pin('C', 0)),
        in2(&m->watch_pin('C', 1)) {
    servo.reset(new sim::DcServo(*m, s));
    wait_banner();
  }

  void run_until(double t_s) {
    const uint64_t until = uint64_t(t_s * m->f_cpu());
    if (until > m->cycles()) m->run([] { return false; }, until - m->cycles());
  }

  std::unique_ptr<sim::DcServo> servo;
  const std::vector<sim::PinEdge>* enable;  // PD5, the L298's ENABLE
  const std::vector<sim::PinEdge>* in1;     // PC0, IN1
  const std::vector<sim::PinEdge>* in2;     // PC1, IN2
};

}  // namespace simtest
