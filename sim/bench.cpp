// avrmotion-bench: the step engine's figures, measured by running the real
// firmware images in the (patched) simulator. It prints tables, it asserts
// nothing: tests guard behaviour, this shows performance (docs/step-engine.md).
//
// For every scenario a move is sent with 20 junk lines after it, so the UART
// receives and answers during the motion, as it would with a sender that
// streams. The cruise window is the stretch of steps at the move's top speed
// (found in a first run); an identical second run (the simulation is
// deterministic) snapshots the interrupt counters at the window's edges.
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

namespace {

struct Scenario {
  const char* image;
  char axis;
  uint32_t rate;
  uint32_t accel;
  uint32_t steps;
};

struct Figures {
  uint32_t clamped_to = 0;     // 0 = not clamped
  size_t steps = 0;
  double cruise_hz = 0;
  double isr_cycles_per_step = 0;
  double cpu_load = 0;
  uint64_t jitter = 0;         // max - min cruise interval
  size_t doubled = 0;          // intervals > 1.5 x the cruise interval inside the window
  bool ok = false;
};

std::string image_path(const std::string& dir, const std::string& name) {
  return dir + "/avrmotion-" + name + ".elf";
}

std::map<int, sim::IsrStats> snapshot(const sim::Machine& m) { return m.isr_stats(); }

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
  for (int i = 0; i < 20; ++i) m.serial().add_line("NOP");
}

Figures measure(const std::string& dir, const Scenario& s) {
  Figures f;
  const uint64_t budget = 16000000ull * 30;
  std::vector<uint64_t> stamps;
  {
    sim::Machine m(image_path(dir, s.image));
    load_script(m, s);
    if (m.run_script(budget) != sim::RunEnd::done) return f;
    stamps = m.axis(s.axis)->step_cycles;
    for (const std::string& line : m.serial().received()) {
      if (line.rfind("warning: F clamped to ", 0) == 0) f.clamped_to = uint32_t(std::stoul(line.substr(22)));
    }
    f.steps = size_t(m.axis(s.axis)->steps() >= 0 ? m.axis(s.axis)->steps() : -m.axis(s.axis)->steps());
  }
  if (stamps.size() < 4) return f;
  std::vector<uint64_t> iv;
  for (size_t i = 1; i < stamps.size(); ++i) iv.push_back(stamps[i] - stamps[i - 1]);
  const uint64_t fastest = *std::min_element(iv.begin(), iv.end());
  // The cruise: the steps within 1 % of the fastest interval; measure the
  // middle 80 % of that stretch, away from the ramps' ends.
  size_t first = iv.size(), last = 0;
  for (size_t i = 0; i < iv.size(); ++i) {
    if (iv[i] <= fastest + fastest / 100 + 4) {
      first = std::min(first, i);
      last = i;
    }
  }
  const size_t span = last - first;
  const size_t a = first + span / 10, b = last - span / 10;
  if (b <= a) return f;
  uint64_t lo = ~0ull, hi = 0, sum = 0;
  for (size_t i = a; i < b; ++i) {
    lo = std::min(lo, iv[i]);
    hi = std::max(hi, iv[i]);
    sum += iv[i];
  }
  f.cruise_hz = 16e6 / (double(sum) / (b - a));
  f.jitter = hi - lo;
  for (size_t i = a; i < b; ++i) f.doubled += iv[i] * 2 > lo * 3;

  // Second run: interrupt time between the window's first and last step.
  sim::Machine m(image_path(dir, s.image));
  load_script(m, s);
  const auto& st = m.axis(s.axis)->step_cycles;
  m.run([&] { return st.size() > a + 1; }, budget);
  const auto before = snapshot(m);
  const uint64_t c0 = m.cycles();
  m.run([&] { return st.size() > b + 1; }, budget);
  const auto after = snapshot(m);
  const uint64_t c1 = m.cycles();
  const double irq = interrupt_cycles(before, after);
  f.isr_cycles_per_step = irq / double(b - a);
  f.cpu_load = irq / double(c1 - c0);
  f.ok = f.steps == s.steps;
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
  std::printf("%8s %9s %10s %11s %9s %7s %8s %8s %6s\n", "F asked", "clamped", "cruise Hz", "irq cyc/st",
              "CPU", "jitter", "doubled", "steps", "exact");
  for (const Scenario& s : list) {
    const Figures f = measure(dir, s);
    std::printf("%8u %9s %10.0f %11.1f %8.1f%% %7llu %8zu %8zu %6s\n", s.rate,
                f.clamped_to ? std::to_string(f.clamped_to).c_str() : "-", f.cruise_hz, f.isr_cycles_per_step,
                100 * f.cpu_load, (unsigned long long)f.jitter, f.doubled, f.steps, f.ok ? "yes" : "NO");
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
                 "(irq cyc/st: every interrupt in the cruise window, response and RETI included, per step)",
                 {{"uno", 'Z', 50000, 400000, 60000},
                  {"uno", 'Z', 100000, 400000, 80000},
                  {"uno", 'Z', 150000, 400000, 100000},
                  {"uno", 'Z', 160000, 400000, 100000},
                  {"uno", 'Z', 250000, 400000, 100000}});
    print_engine(dir, "m32 axis X, software STEP pulse (GPIO in the interrupt), 200000 steps/s^2",
                 {{"m32", 'X', 10000, 200000, 20000},
                  {"m32", 'X', 40000, 200000, 40000},
                  {"m32", 'X', 80000, 200000, 40000}});
    print_engine(dir, "Uno axis X, Motor Shield latch (two-phase), 20000 steps/s^2",
                 {{"uno", 'X', 2000, 20000, 4000}, {"uno", 'X', 20000, 20000, 20000}});
  } catch (const std::exception& e) {
    std::fprintf(stderr, "avrmotion-bench: %s\n", e.what());
    return 2;
  }
  return 0;
}
