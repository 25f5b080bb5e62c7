// avrmotion-bench: the step engine's figures, measured by running the real
// firmware images in the (patched) simulator. It prints tables, it asserts
// nothing: tests guard behaviour, this shows performance (docs/step-engine.md).
//
// For every scenario a move is sent with junk lines after it, enough to keep
// the UART receiving and answering for the whole motion, as it would with a
// sender that streams. Every figure covers the whole move, ramps included:
// the steps are compared one by one with the schedule the planner computes
// (the same core code, run here on the host), and the interrupt counters are
// read at the first and the last step.
#include <gelf.h>
#include <libelf.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "machine.h"
#include "schedule.h"

namespace {

struct Scenario {
  const char* image;
  char axis;
  uint32_t rate;
  uint32_t accel;
  uint32_t steps;
  char pulse_port;  // a STEP pin whose pulse widths to measure, or 0
  uint8_t pulse_bit;
};

struct Figures {
  uint32_t clamped_to = 0;     // 0 = not clamped
  size_t steps = 0;
  double cruise_hz = 0;
  double isr_cycles_per_step = 0;
  double cpu_load = 0;
  int64_t spread = 0;          // max - min lateness of the steps against the schedule, whole move
  size_t doubled = 0;          // intervals > 1.5 x their scheduled interval, whole move
  uint64_t pulse_min = 0, pulse_max = 0;  // timer-pulsed STEP width, cycles (0: not measured)
  bool ok = false;
};

std::string image_path(const std::string& dir, const std::string& name) {
  return dir + "/avrmotion-" + name + ".elf";
}

double interrupt_cycles(const std::map<int, sim::IsrStats>& a, const std::map<int, sim::IsrStats>& b) {
  double total = 0;
  for (const auto& kv : b) {
    const auto it = a.find(kv.first);
    const uint64_t count = kv.second.count - (it == a.end() ? 0 : it->second.count);
    const uint64_t cycles = kv.second.total_cycles - (it == a.end() ? 0 : it->second.total_cycles);
    total += double(cycles) + 8.0 * count;  // + response (4) and RETI (4)
  }
  return total;
}

void load_script(sim::Machine& m, const Scenario& s) {
  m.serial().add_line(std::string("MOVE ") + s.axis + std::to_string(s.steps) + " F" + std::to_string(s.rate) +
                      " A" + std::to_string(s.accel));
  // A junk line and its error answer take about 0.5 ms: 2400 cover the
  // longest scenario (1.1 s).
  for (int i = 0; i < 2400; ++i) m.serial().add_line("NOP");
}

bool failed = false;  // a run that did not end as it must: the benchmark fails

Figures measure(const std::string& dir, const Scenario& s) {
  Figures f;
  const uint64_t budget = 16000000ull * 30;
  sim::Machine m(image_path(dir, s.image));
  const std::vector<sim::PinEdge>* pulse = s.pulse_port ? &m.watch_pin(s.pulse_port, s.pulse_bit) : nullptr;
  load_script(m, s);
  const auto& st = m.axis(s.axis)->step_cycles;
  if (m.run([&] { return !st.empty(); }, budget) != sim::RunEnd::done) return f;
  const auto before = m.isr_stats();
  if (m.run([&] { return st.size() >= s.steps; }, budget) != sim::RunEnd::done) return f;
  const auto after = m.isr_stats();
  if (m.run_script(budget) != sim::RunEnd::done) return f;
  for (const std::string& line : m.serial().received()) {
    if (line.rfind("warning: F clamped to ", 0) == 0) f.clamped_to = uint32_t(std::stoul(line.substr(22)));
  }
  const double pos = m.axis(s.axis)->steps();
  f.steps = size_t(pos >= 0 ? pos : -pos);
  f.ok = f.steps == s.steps && st.size() == s.steps;
  if (!f.ok || st.size() < 2) return f;

  // Every step of the whole move against the schedule, ramps included.
  const std::vector<uint32_t> plan =
      sim::planned_schedule(s.steps, am::RampConfig{m.f_cpu(), f.clamped_to ? f.clamped_to : s.rate, s.accel, s.accel});
  const uint32_t fastest = *std::min_element(plan.begin() + 1, plan.end());
  uint64_t due = st[0], cruise_cycles = 0, cruise_steps = 0;
  int64_t lo = 0, hi = 0;
  for (size_t i = 1; i < st.size(); ++i) {
    due += plan[i];
    const int64_t late = int64_t(st[i]) - int64_t(due);
    lo = std::min(lo, late);
    hi = std::max(hi, late);
    const uint64_t interval = st[i] - st[i - 1];
    f.doubled += interval * 2 > uint64_t(plan[i]) * 3;
    if (plan[i] == fastest) {
      cruise_cycles += interval;
      ++cruise_steps;
    }
  }
  f.spread = hi - lo;
  f.cruise_hz = cruise_steps ? double(m.f_cpu()) * cruise_steps / double(cruise_cycles) : 0;
  const double irq = interrupt_cycles(before, after);
  f.isr_cycles_per_step = irq / double(s.steps - 1);
  f.cpu_load = irq / double(st.back() - st.front());
  if (pulse) {
    f.pulse_min = ~0ull;
    for (size_t i = 1; i < pulse->size(); ++i) {
      if ((*pulse)[i - 1].level && !(*pulse)[i].level) {
        const uint64_t w = (*pulse)[i].cycle - (*pulse)[i - 1].cycle;
        f.pulse_min = std::min(f.pulse_min, w);
        f.pulse_max = std::max(f.pulse_max, w);
      }
    }
  }
  return f;
}

struct PartSize {
  const char* mcu;
  unsigned flash, ram;
};
const PartSize kParts[] = {{"atmega328p", 32768, 2048}, {"atmega32", 32768, 2048}, {"atmega16", 16384, 1024}};

void print_sizes(const std::string& dir) {
  std::printf("Image sizes (flash = .text + .data, RAM = .data + .bss; stack measured on the demo-like run)\n");
  std::printf("%-22s %-11s %14s %14s %8s\n", "image", "mcu", "flash", "RAM", "stack");
  for (const char* name : {"uno", "m32", "m32-driver", "m16", "m16-8mhz"}) {
    const std::string path = image_path(dir, name);
    if (elf_version(EV_CURRENT) == EV_NONE) return;
    const int fd = open(path.c_str(), O_RDONLY);
    if (fd < 0) continue;
    Elf* elf = elf_begin(fd, ELF_C_READ, nullptr);
    size_t shstrndx = 0, text = 0, data = 0, bss = 0;
    elf_getshdrstrndx(elf, &shstrndx);
    for (Elf_Scn* scn = elf_nextscn(elf, nullptr); scn; scn = elf_nextscn(elf, scn)) {
      GElf_Shdr sh;
      gelf_getshdr(scn, &sh);
      const char* n = elf_strptr(elf, shstrndx, sh.sh_name);
      if (!n) continue;
      if (!std::strcmp(n, ".text")) text = sh.sh_size;
      if (!std::strcmp(n, ".data")) data = sh.sh_size;
      if (!std::strcmp(n, ".bss")) bss = sh.sh_size;
    }
    elf_end(elf);
    close(fd);
    sim::Machine m(path);
    unsigned stack = 0;
    if (std::string(name) != "m32-driver") {
      m.serial().add_line(std::string("MOVE ") + m.axes().front().name + "200 F2000 A8000");
      m.serial().add_line("POS");
      m.run_script(16000000ull * 10);
      stack = m.stack_bytes();
    }
    const PartSize* part = nullptr;
    for (const PartSize& p : kParts) part = std::strcmp(p.mcu, m.board().mcu) ? part : &p;
    std::printf("%-22s %-11s %6zu (%4.1f%%) %6zu (%4.1f%%) %8s\n", name, m.board().mcu, text + data,
                part ? 100.0 * (text + data) / part->flash : 0, data + bss,
                part ? 100.0 * (data + bss) / part->ram : 0, stack ? std::to_string(stack).c_str() : "-");
  }
  std::printf("\n");
}

void print_engine(const std::string& dir, const char* title, const std::vector<Scenario>& list) {
  std::printf("%s\n", title);
  std::printf("%8s %9s %10s %11s %7s %8s %8s %9s %8s %6s\n", "F asked", "clamped", "cruise Hz", "irq cyc/st",
              "CPU", "spread", "doubled", "pulse", "steps", "exact");
  for (const Scenario& s : list) {
    const Figures f = measure(dir, s);
    const std::string pulse =
        f.pulse_max ? std::to_string(f.pulse_min) + ".." + std::to_string(f.pulse_max) : std::string("-");
    std::printf("%8u %9s %10.0f %11.1f %6.1f%% %8lld %8zu %9s %8zu %6s\n", s.rate,
                f.clamped_to ? std::to_string(f.clamped_to).c_str() : "-", f.cruise_hz, f.isr_cycles_per_step,
                100 * f.cpu_load, (long long)f.spread, f.doubled, pulse.c_str(), f.steps, f.ok ? "yes" : "NO");
    if (!f.ok) failed = true;
  }
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  std::string dir = AVRMOTION_FIRMWARE_DIR;
  if (argc == 3 && std::string(argv[1]) == "--firmware-dir") dir = argv[2];
  else if (argc != 1) {
    std::fprintf(stderr, "usage: avrmotion-bench [--firmware-dir DIR]\n");
    return 2;
  }
  try {
    print_sizes(dir);
    print_engine(dir,
                 "Uno axis Z, hardware-timed STEP (OC1A), ramp planned on the chip, 400000 steps/s^2\n"
                 "(whole move, ramps included: irq cyc/st counts every interrupt from the first step to the\n"
                 " last, response and RETI included, per step; spread is the max - min lateness of the steps\n"
                 " against the planned schedule; doubled counts intervals > 1.5 x their scheduled interval)",
                 {{"uno", 'Z', 50000, 400000, 60000, 'B', 1},
                  {"uno", 'Z', 100000, 400000, 80000, 'B', 1},
                  {"uno", 'Z', 150000, 400000, 100000, 'B', 1},
                  {"uno", 'Z', 160000, 400000, 100000, 'B', 1},
                  {"uno", 'Z', 250000, 400000, 100000, 'B', 1}});
    print_engine(dir, "m32 axis X, software STEP pulse (GPIO in the interrupt), 200000 steps/s^2",
                 {{"m32", 'X', 10000, 200000, 20000, 0, 0},
                  {"m32", 'X', 40000, 200000, 40000, 0, 0},
                  {"m32", 'X', 80000, 200000, 40000, 0, 0}});
    print_engine(dir, "Uno axis X, Motor Shield latch (two-phase), 20000 steps/s^2",
                 {{"uno", 'X', 2000, 20000, 4000, 0, 0}, {"uno", 'X', 20000, 20000, 20000, 0, 0}});
  } catch (const std::exception& e) {
    std::fprintf(stderr, "avrmotion-bench: %s\n", e.what());
    return 2;
  }
  if (failed) std::fprintf(stderr, "avrmotion-bench: a run did not end with every step exact\n");
  return failed ? 1 : 0;
}
