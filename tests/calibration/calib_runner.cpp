// Calibration runner: runs one calibration program (an AVR ELF) in libsimavr
// and checks the pin-edge timings it produces against the expectations
// written in the program's source.
//
//   calib_runner --mcu atmega328p --freq 16000000 prog.elf prog.S
//
// Expectation lines in the source (anywhere, usually in // comments):
//   EXPECT <name>: <pin><edge>#<k> -> <pin><edge>#<m> = <cycles>
//       cycles from the k-th to the m-th matching edge (0-based, signed)
//   EXPECT <name>: count <pin><edge> = <n>
//       number of matching edges in the whole run
//   BUDGET <cycles>
//       the program must reach its end (cli; sleep) within this many cycles
// <pin> is a port pin (B1, D6, ...), an output-compare name (OC1A, ...) or
// MARK (the marker pin), mapped per MCU; <edge> is ^ (rising), v (falling) or * (either).
//
// Edge timestamps are avr->cycle when the pin IRQ fires: the first cycle of
// the instruction that writes the port, or, for timer outputs, the cycle at
// which simavr processes the compare match. Pin IRQs fire on every port
// write, so edges are detected here by comparing with the last level.
//
// A run in which simavr logs an error fails too: that is how it reports an
// event it dropped ("CYCLE: avr_cycle_timer_insert: ran out of timers").
#include <simavr/sim_avr.h>
#include <simavr/sim_elf.h>
#include <simavr/avr_ioport.h>

#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <string>
#include <vector>

namespace {

struct Edge {
  uint64_t cycle;
  char port;
  int pin;
  int level;  // level after the edge
};

struct PinWatch {
  std::vector<Edge>* edges;
  avr_t* avr;
  char port;
  int pin;
  int level = 0;
};

struct PinRef {
  char port = 0;
  int pin = 0;
  char edge = '*';
};

struct Expectation {
  std::string name;
  bool is_count = false;
  PinRef a, b;
  int ka = 0, kb = 0;
  int64_t expected = 0;
};

void pin_changed(avr_irq_t*, uint32_t value, void* param) {
  auto* w = static_cast<PinWatch*>(param);
  int level = value & 1;  // timer outputs carry AVR_IOPORT_OUTPUT in upper bits
  if (level == w->level) return;
  w->level = level;
  w->edges->push_back({w->avr->cycle, w->port, w->pin, level});
}

void no_sleep(avr_t*, avr_cycle_count_t) {}  // default syncs to wall-clock time

// simavr's own logger (same filter, same streams), counting its errors.
int simavr_errors = 0;
void counting_logger(avr_t* avr, const int level, const char* format, va_list args) {
  if (level == LOG_ERROR) ++simavr_errors;
  if (!avr || avr->log >= level) std::vfprintf(level > LOG_ERROR ? stdout : stderr, format, args);
}

// Output-compare pins of the supported parts, and the marker pin the
// programs use (calib.h MARK_*: a port with no timer output in use).
std::optional<std::pair<char, int>> oc_pin(const std::string& mcu, const std::string& oc) {
  static const std::map<std::string, std::map<std::string, std::pair<char, int>>> table = {
      {"atmega328p", {{"MARK", {'D', 0}}, {"OC0A", {'D', 6}}, {"OC0B", {'D', 5}}, {"OC1A", {'B', 1}},
                      {"OC1B", {'B', 2}}, {"OC2A", {'B', 3}}, {"OC2B", {'D', 3}}}},
      {"atmega32", {{"MARK", {'B', 0}}, {"OC0", {'B', 3}}, {"OC1A", {'D', 5}}, {"OC1B", {'D', 4}}, {"OC2", {'D', 7}}}},
      {"atmega1284p", {{"MARK", {'B', 0}}, {"OC0A", {'B', 3}}, {"OC0B", {'B', 4}}, {"OC1A", {'D', 5}}, {"OC1B", {'D', 4}},
                       {"OC2A", {'D', 7}}, {"OC2B", {'D', 6}}}},
      {"atmega16", {{"MARK", {'B', 0}}, {"OC0", {'B', 3}}, {"OC1A", {'D', 5}}, {"OC1B", {'D', 4}}, {"OC2", {'D', 7}}}},
  };
  auto m = table.find(mcu);
  if (m == table.end()) return std::nullopt;
  auto p = m->second.find(oc);
  if (p == m->second.end()) return std::nullopt;
  return p->second;
}

PinRef parse_pin(const std::string& mcu, const std::string& name, char edge) {
  PinRef r;
  r.edge = edge;
  if (name.size() == 2 && name[0] >= 'A' && name[0] <= 'D' && name[1] >= '0' && name[1] <= '7') {
    r.port = name[0];
    r.pin = name[1] - '0';
  } else if (auto p = oc_pin(mcu, name)) {
    r.port = p->first;
    r.pin = p->second;
  } else {
    std::fprintf(stderr, "unknown pin '%s' for %s\n", name.c_str(), mcu.c_str());
    std::exit(2);
  }
  return r;
}

bool matches(const Edge& e, const PinRef& p) {
  return e.port == p.port && e.pin == p.pin &&
         (p.edge == '*' || (p.edge == '^') == (e.level == 1));
}

std::optional<uint64_t> nth_edge(const std::vector<Edge>& edges, const PinRef& p, int k) {
  for (const auto& e : edges)
    if (matches(e, p) && k-- == 0) return e.cycle;
  return std::nullopt;
}

}  // namespace

int main(int argc, char** argv) {
  std::string mcu = "atmega328p";
  uint32_t freq = 16000000;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--mcu" && i + 1 < argc) mcu = argv[++i];
    else if (a == "--freq" && i + 1 < argc) freq = std::strtoul(argv[++i], nullptr, 0);
    else files.push_back(a);
  }
  if (files.size() != 2) {
    std::fprintf(stderr, "usage: %s [--mcu M] [--freq HZ] prog.elf prog.S\n", argv[0]);
    return 2;
  }

  // --- expectations from the program source ---
  std::ifstream src(files[1]);
  if (!src) { std::fprintf(stderr, "cannot read %s\n", files[1].c_str()); return 2; }
  const std::string pin = R"(([A-D][0-7]|OC[0-2][AB]?|MARK)([\^v*]))";
  const std::regex re_interval(R"(EXPECT\s+(\S+):\s*)" + pin + R"(#(\d+)\s*->\s*)" + pin +
                               R"(#(\d+)\s*=\s*(-?\d+))");
  const std::regex re_count(R"(EXPECT\s+(\S+):\s*count\s+)" + pin + R"(\s*=\s*(\d+))");
  const std::regex re_budget(R"(BUDGET\s+(\d+))");
  std::vector<Expectation> expect;
  uint64_t budget = 100000;
  for (std::string line; std::getline(src, line);) {
    std::smatch m;
    if (std::regex_search(line, m, re_interval)) {
      Expectation e;
      e.name = m[1];
      e.a = parse_pin(mcu, m[2], m[3].str()[0]);
      e.ka = std::stoi(m[4]);
      e.b = parse_pin(mcu, m[5], m[6].str()[0]);
      e.kb = std::stoi(m[7]);
      e.expected = std::stoll(m[8]);
      expect.push_back(e);
    } else if (std::regex_search(line, m, re_count)) {
      Expectation e;
      e.name = m[1];
      e.is_count = true;
      e.a = parse_pin(mcu, m[2], m[3].str()[0]);
      e.expected = std::stoll(m[4]);
      expect.push_back(e);
    } else if (std::regex_search(line, m, re_budget)) {
      budget = std::stoull(m[1]);
    } else if (line.find("EXPECT") != std::string::npos &&
               line.find("EXPECT") == line.find_first_not_of(" \t/;*")) {
      std::fprintf(stderr, "malformed expectation: %s\n", line.c_str());
      return 2;
    }
  }
  if (expect.empty()) { std::fprintf(stderr, "no EXPECT lines in %s\n", files[1].c_str()); return 2; }

  // --- simulator ---
  avr_global_logger_set(counting_logger);
  elf_firmware_t fw;
  std::memset(&fw, 0, sizeof fw);
  if (elf_read_firmware(files[0].c_str(), &fw) != 0) {
    std::fprintf(stderr, "cannot load %s\n", files[0].c_str());
    return 2;
  }
  std::snprintf(fw.mmcu, sizeof fw.mmcu, "%s", mcu.c_str());
  fw.frequency = freq;
  avr_t* avr = avr_make_mcu_by_name(mcu.c_str());
  if (!avr) { std::fprintf(stderr, "unknown mcu %s\n", mcu.c_str()); return 2; }
  avr_init(avr);
  avr_load_firmware(avr, &fw);
  avr->frequency = freq;
  avr->sleep = no_sleep;
  avr->log = LOG_ERROR;  // "mode 0 UNSUPPORTED" on OCR writes before WGM is set is harmless

  std::vector<Edge> edges;
  std::vector<PinWatch> watches;
  watches.reserve(32);
  for (char port = 'A'; port <= 'D'; ++port)
    for (int n = 0; n < 8; ++n) {
      avr_irq_t* irq = avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ(port), n);
      if (!irq) continue;
      watches.push_back({&edges, avr, port, n});
      avr_irq_register_notify(irq, pin_changed, &watches.back());
    }

  int state = avr->state;
  while (state != cpu_Done && state != cpu_Crashed && avr->cycle <= budget)
    state = avr_run(avr);
  if (state != cpu_Done) {
    std::printf("FAIL: program did not finish (%s) after %llu cycles (budget %llu)\n",
                state == cpu_Crashed ? "crashed" : "still running",
                (unsigned long long)avr->cycle, (unsigned long long)budget);
    return 1;
  }

  // --- compare ---
  int failures = 0;
  for (const auto& e : expect) {
    std::optional<int64_t> got;
    if (e.is_count) {
      int64_t n = 0;
      for (const auto& ed : edges) n += matches(ed, e.a);
      got = n;
    } else {
      auto ta = nth_edge(edges, e.a, e.ka), tb = nth_edge(edges, e.b, e.kb);
      if (ta && tb) got = (int64_t)*tb - (int64_t)*ta;
    }
    bool ok = got && *got == e.expected;
    failures += !ok;
    if (got)
      std::printf("%-4s %-28s expected %6lld  measured %6lld\n", ok ? "ok" : "FAIL",
                  e.name.c_str(), (long long)e.expected, (long long)*got);
    else
      std::printf("FAIL %-28s expected %6lld  measured   none (edge missing)\n",
                  e.name.c_str(), (long long)e.expected);
  }
  if (simavr_errors) {
    std::printf("FAIL: simavr logged %d error(s), see standard error (a dropped event invalidates the run)\n",
                simavr_errors);
    ++failures;
  }
  if (failures && std::getenv("CALIB_TRACE"))
    for (const auto& ed : edges)
      std::printf("  %10llu P%c%d %s\n", (unsigned long long)ed.cycle, ed.port, ed.pin,
                  ed.level ? "rise" : "fall");
  avr_terminate(avr);
  return failures ? 1 : 0;
}
