// avrmotion-bench: the step engine's figures, measured by running the real
// firmware images in the (patched) simulator. It prints tables, it asserts
// nothing about them: tests guard behaviour, this shows performance
// (docs/step-engine.md, docs/benchmarks.md). It fails only when a run is
// broken: a scenario that did not finish, or whose step count is not exact.
//
// For every scenario a move is sent with junk lines after it, enough to keep
// the UART receiving and answering for the whole motion, as it would with a
// sender that streams. Every figure covers the whole move, ramps included:
// the steps are compared one by one with the schedule the planner computes
// (the same core code, run here on the host), and the interrupt counters are
// read at the first and the last step.
//
// Every scenario and every image-size row is a job of its own, on a machine
// of its own. The jobs run in parallel, each in a child process (fork), and
// send their figures back through a pipe: the harness keeps process-wide
// state (simavr's one logger, and sim::Machine's table of machines for it)
// that concurrent machines in one process would share, a process shares
// nothing. With --jobs 1 everything runs in this process, one job after the
// other. The tables are printed in their fixed order once every job has
// ended, so the output does not depend on the number of workers; progress
// (a line as each job starts and ends) goes to standard error.
#include <fcntl.h>
#include <limits.h>
#include <gelf.h>
#include <libelf.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include "machine.h"
#include "schedule.h"

namespace {

using Clock = std::chrono::steady_clock;

struct Scenario {
  const char* image;
  char axis;
  uint32_t rate;
  uint32_t accel;
  uint32_t steps;
  char pulse_port;  // a STEP pin whose pulse widths to measure, or 0
  uint8_t pulse_bit;
  const char* also = "";  // axes moving the same steps with `axis` (a coordinated diagonal)
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
  char mcu[24] = {};  // the image's part and clock, for the Markdown headings
  uint32_t f_cpu = 0;
};

// One image's row of the size table.
struct SizeRow {
  bool found = false;  // the image exists (a missing one has no row)
  char mcu[24] = {};
  uint32_t f_cpu = 0;
  size_t flash = 0, ram = 0;  // .text + .data, .data + .bss
  unsigned stack = 0;         // 0: not measured
};

// What a job sends back. Plain bytes, so that a child process can write it
// into a pipe as it is.
struct Result {
  bool done = false;  // the job ran to its end (no exception, no crash)
  char error[480] = {};
  Figures figures;
  SizeRow size;
};
static_assert(std::is_trivially_copyable<Result>::value, "a Result crosses a pipe as bytes");
static_assert(sizeof(Result) <= PIPE_BUF, "a Result fits the pipe in one write");

struct Table {
  const char* title;    // printed above the table (standard output)
  const char* heading;  // its Markdown heading, after the image, part and clock
  const char* name;     // a short name, for the anchors
  std::vector<Scenario> list;
};

const std::vector<Table>& engine_tables() {
  static const std::vector<Table> tables = {
      {"Uno axis Z, hardware-timed STEP (OC1A), ramp planned on the chip, 300000 steps/s^2\n"
       "(whole move, ramps included: irq cyc/st counts every interrupt from the first step to the\n"
       " last, response and RETI included, per step; spread is the max - min lateness of the steps\n"
       " against the planned schedule; doubled counts intervals > 1.5 x their scheduled interval)",
       "axis Z, hardware-timed STEP on OC1A (D9), 300000 steps/s^2", "uno Z, timer-pulsed STEP",
       {{"uno", 'Z', 50000, 300000, 60000, 'B', 1},
        {"uno", 'Z', 100000, 300000, 80000, 'B', 1},
        {"uno", 'Z', 150000, 300000, 100000, 'B', 1},
        {"uno", 'Z', 160000, 300000, 100000, 'B', 1},
        {"uno", 'Z', 250000, 300000, 100000, 'B', 1}}},
      {"m32 axis X, software STEP pulse (GPIO in the interrupt), 200000 steps/s^2",
       "axis X, software STEP pulse (GPIO in the interrupt), 200000 steps/s^2", "m32 X, software STEP pulse",
       {{"m32", 'X', 10000, 200000, 20000, 0, 0},
        {"m32", 'X', 40000, 200000, 40000, 0, 0},
        {"m32", 'X', 80000, 200000, 40000, 0, 0}}},
      {"m32 axes X Y Z (and E), one coordinated diagonal block, software STEP pulses, 200000 steps/s^2\n"
       "(figures per event of the dominant axis X; every axis steps at every event)",
       "axes X Y Z (E), one coordinated diagonal block, software STEP pulses, 200000 steps/s^2",
       "m32 XYZ(E), coordinated",
       {{"m32", 'X', 10000, 200000, 20000, 0, 0, "YZ"},
        {"m32", 'X', 40000, 200000, 40000, 0, 0, "YZ"},
        {"m32", 'X', 40000, 200000, 40000, 0, 0, "YZE"}}},
      {"Uno axis X, Motor Shield latch (two-phase), 20000 steps/s^2",
       "axis X, Adafruit Motor Shield v1 latch (74HC595, two-phase), 20000 steps/s^2", "uno X, shield latch",
       {{"uno", 'X', 2000, 20000, 4000, 0, 0}, {"uno", 'X', 20000, 20000, 20000, 0, 0}}},
  };
  return tables;
}

const char* const kSizeImages[] = {"uno", "m32", "m32-driver", "m16", "m16-8mhz"};

struct PartSize {
  const char* mcu;
  unsigned flash, ram;
};
const PartSize kParts[] = {{"atmega328p", 32768, 2048}, {"atmega32", 32768, 2048}, {"atmega16", 16384, 1024}};

const PartSize* part_of(const char* mcu) {
  for (const PartSize& p : kParts) {
    if (!std::strcmp(p.mcu, mcu)) return &p;
  }
  return nullptr;
}

// Other firmware, as docs/step-engine.md quotes it from the measurements of
// issue 4: not run here (their images are not part of this repository).
struct Anchor {
  const char* firmware;
  const char* rate;
  const char* cycles_per_step;
};
const Anchor kAnchors[] = {
    {"grbl 1.1h", "32 kHz", "362"},
    {"FastAccelStepper", "80 kHz", "149"},
    {"AccelStepper 1.64", "4.45 kHz", "-"},
};

std::string image_path(const std::string& dir, const std::string& name) {
  return dir + "/avrmotion-" + name + ".elf";
}

std::string move_line(const Scenario& s) {
  std::string line = std::string("MOVE ") + s.axis + std::to_string(s.steps);
  for (const char* a = s.also; *a; ++a) line += std::string(" ") + *a + std::to_string(s.steps);
  return line + " F" + std::to_string(s.rate) + " A" + std::to_string(s.accel);
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
  m.serial().add_line(move_line(s));
  // A junk line and its error answer take about 0.5 ms: 2400 cover the
  // longest scenario (1.1 s).
  for (int i = 0; i < 2400; ++i) m.serial().add_line("NOP");
}

Figures measure(const std::string& dir, const Scenario& s) {
  Figures f;
  const uint64_t budget = 16000000ull * 30;
  sim::Machine m(image_path(dir, s.image));
  std::snprintf(f.mcu, sizeof f.mcu, "%s", m.board().mcu);
  f.f_cpu = m.f_cpu();
  const std::vector<sim::PinEdge>* pulse = s.pulse_port ? &m.watch_pin(s.pulse_port, s.pulse_bit) : nullptr;
  load_script(m, s);
  if (!m.axis(s.axis)) throw std::runtime_error(std::string("the ") + s.image + " image has no axis " + s.axis);
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
  for (const char* a = s.also; *a; ++a)
    f.ok = f.ok && m.axis(*a) && m.axis(*a)->step_cycles.size() == s.steps && m.axis(*a)->steps() == double(s.steps);
  if (!f.ok || st.size() < 2) return f;

  // Every step of the whole move against the schedule, ramps included.
  const std::vector<uint32_t> plan =
      sim::planned_schedule(s.steps, sim::Ramp{m.f_cpu(), f.clamped_to ? f.clamped_to : s.rate, s.accel});
  const uint32_t fastest = *std::min_element(plan.begin() + 1, plan.end());
  uint64_t cruise_cycles = 0, cruise_steps = 0;
  for (size_t i = 1; i < st.size(); ++i) {
    const uint64_t interval = st[i] - st[i - 1];
    f.doubled += interval * 2 > uint64_t(plan[i]) * 3;
    if (plan[i] == fastest) {
      cruise_cycles += interval;
      ++cruise_steps;
    }
  }
  f.spread = sim::lateness(st, 0, st.size(), plan).spread();
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

// Flash and RAM from the ELF's sections, the stack from a demo-like run.
SizeRow measure_size(const std::string& dir, const char* name) {
  SizeRow r;
  const std::string path = image_path(dir, name);
  if (elf_version(EV_CURRENT) == EV_NONE) throw std::runtime_error("libelf is out of date");
  const int fd = open(path.c_str(), O_RDONLY);
  if (fd < 0) return r;
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
  if (std::string(name) != "m32-driver") {
    m.serial().add_line(std::string("MOVE ") + m.axes().front().name + "200 F2000 A8000");
    m.serial().add_line("POS");
    m.run_script(16000000ull * 10);
    r.stack = m.stack_bytes();
  }
  r.found = true;
  std::snprintf(r.mcu, sizeof r.mcu, "%s", m.board().mcu);
  r.f_cpu = m.f_cpu();
  r.flash = text + data;
  r.ram = data + bss;
  return r;
}

// --- running the jobs ---------------------------------------------------------

struct Job {
  std::string name;  // for the progress lines
  std::function<void(Result&)> run;
};

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

Result run_here(const Job& job) {
  Result r;
  try {
    job.run(r);
    r.done = true;
  } catch (const std::exception& e) {
    std::snprintf(r.error, sizeof r.error, "%s", e.what());
  } catch (...) {
    std::snprintf(r.error, sizeof r.error, "unknown exception");
  }
  return r;
}

class Progress {
 public:
  explicit Progress(size_t total) : total_(total), start_(Clock::now()) {}
  void started(size_t i, const Job& job) {
    std::fprintf(stderr, "avrmotion-bench: [%zu/%zu] start %s\n", i + 1, total_, job.name.c_str());
  }
  void ended(size_t i, const Job& job, const Result& r, double seconds) {
    ++ended_;
    const bool inexact = r.done && job.name.rfind("size ", 0) != 0 && !r.figures.ok;
    std::fprintf(stderr, "avrmotion-bench: [%zu/%zu] %s %s in %.1f s (%zu of %zu ended, %.1f s since the start)%s%s\n",
                 i + 1, total_, r.done ? "done" : "BROKEN", job.name.c_str(), seconds, ended_, total_,
                 seconds_since(start_), r.done ? "" : ": ", r.done ? (inexact ? ": NOT EXACT" : "") : r.error);
  }
  double elapsed() const { return seconds_since(start_); }

 private:
  size_t total_, ended_ = 0;
  Clock::time_point start_;
};

// Runs every job, `workers` at a time, and returns their results in the
// jobs' order.
std::vector<Result> run_jobs(const std::vector<Job>& jobs, unsigned workers) {
  std::vector<Result> results(jobs.size());
  Progress progress(jobs.size());
  if (workers <= 1) {
    for (size_t i = 0; i < jobs.size(); ++i) {
      progress.started(i, jobs[i]);
      const Clock::time_point t = Clock::now();
      results[i] = run_here(jobs[i]);
      progress.ended(i, jobs[i], results[i], seconds_since(t));
    }
  } else {
    struct Child {
      pid_t pid;
      int fd;
      size_t job;
      Clock::time_point start;
    };
    std::vector<Child> running;
    size_t next = 0;
    while (next < jobs.size() || !running.empty()) {
      while (running.size() < workers && next < jobs.size()) {
        int p[2];
        if (pipe(p) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
        std::fflush(stdout);
        std::fflush(stderr);
        progress.started(next, jobs[next]);
        const pid_t pid = fork();
        if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
        if (pid == 0) {
          close(p[0]);
          const Result r = run_here(jobs[next]);
          // A Result is at most PIPE_BUF bytes: one write, never partial, and
          // it fits the pipe's buffer, so the child ends before it is read.
          const bool sent = write(p[1], &r, sizeof r) == ssize_t(sizeof r);
          _exit(sent ? 0 : 3);
        }
        close(p[1]);
        running.push_back({pid, p[0], next, Clock::now()});
        ++next;
      }
      int status = 0;
      const pid_t pid = waitpid(-1, &status, 0);
      if (pid < 0) {
        if (errno == EINTR) continue;
        throw std::runtime_error(std::string("waitpid: ") + std::strerror(errno));
      }
      const auto it = std::find_if(running.begin(), running.end(), [&](const Child& c) { return c.pid == pid; });
      if (it == running.end()) continue;
      Result& r = results[it->job];
      ssize_t got;
      do got = read(it->fd, &r, sizeof r);
      while (got < 0 && errno == EINTR);
      close(it->fd);
      if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || got != ssize_t(sizeof r)) {
        r = Result();
        if (WIFSIGNALED(status))
          std::snprintf(r.error, sizeof r.error, "its process died of signal %d (%s)", WTERMSIG(status),
                        strsignal(WTERMSIG(status)));
        else
          std::snprintf(r.error, sizeof r.error, "its process ended with status %d without its figures",
                        WIFEXITED(status) ? WEXITSTATUS(status) : -1);
      }
      progress.ended(it->job, jobs[it->job], r, seconds_since(it->start));
      running.erase(it);
    }
  }
  std::fprintf(stderr, "avrmotion-bench: %zu jobs on %u worker%s in %.1f s\n", jobs.size(), std::max(workers, 1u),
               workers > 1 ? "s" : "", progress.elapsed());
  return results;
}

// --- output -------------------------------------------------------------------

std::string clamped_text(const Figures& f) { return f.clamped_to ? std::to_string(f.clamped_to) : "-"; }

std::string pulse_text(const Figures& f) {
  return f.pulse_max ? std::to_string(f.pulse_min) + ".." + std::to_string(f.pulse_max) : std::string("-");
}

std::string format(const char* fmt, double v) {
  char b[64];
  std::snprintf(b, sizeof b, fmt, v);
  return b;
}

void print_sizes(const std::vector<SizeRow>& rows) {
  std::printf("Image sizes (flash = .text + .data, RAM = .data + .bss; stack measured on the demo-like run)\n");
  std::printf("%-22s %-11s %14s %14s %8s\n", "image", "mcu", "flash", "RAM", "stack");
  for (size_t i = 0; i < rows.size(); ++i) {
    const SizeRow& r = rows[i];
    if (!r.found) continue;
    const PartSize* part = part_of(r.mcu);
    std::printf("%-22s %-11s %6zu (%4.1f%%) %6zu (%4.1f%%) %8s\n", kSizeImages[i], r.mcu, r.flash,
                part ? 100.0 * r.flash / part->flash : 0, r.ram, part ? 100.0 * r.ram / part->ram : 0,
                r.stack ? std::to_string(r.stack).c_str() : "-");
  }
  std::printf("\n");
}

void print_engine(const Table& t, const Figures* figures) {
  std::printf("%s\n", t.title);
  std::printf("%8s %9s %10s %11s %7s %8s %8s %9s %8s %6s\n", "F asked", "clamped", "cruise Hz", "irq cyc/st",
              "CPU", "spread", "doubled", "pulse", "steps", "exact");
  for (size_t i = 0; i < t.list.size(); ++i) {
    const Scenario& s = t.list[i];
    const Figures& f = figures[i];
    std::printf("%8u %9s %10.0f %11.1f %6.1f%% %8lld %8zu %9s %8zu %6s\n", s.rate, clamped_text(f).c_str(),
                f.cruise_hz, f.isr_cycles_per_step, 100 * f.cpu_load, (long long)f.spread, f.doubled,
                pulse_text(f).c_str(), f.steps, f.ok ? "yes" : "NO");
  }
  std::printf("\n");
}

// The Markdown page (docs/benchmarks.md): the same figures as the tables on
// standard output, formatted alike, and nothing that changes from run to run
// (no date, no wall time), so the page only changes when a figure does.
std::string markdown(const std::vector<SizeRow>& sizes, const std::vector<std::vector<Figures>>& engine) {
  std::string o;
  auto add = [&](const std::string& s) { o += s; };
  add("# Benchmarks\n\n"
      "Every figure on this page is printed by `avrmotion-bench`; the page is its output\n"
      "(`./build/sim/avrmotion-bench --markdown docs/benchmarks.md`), not edited by hand.\n"
      "The simulation is deterministic: the same images give the same page, whatever the\n"
      "machine and the number of workers (`--jobs`). How the step engine works and what\n"
      "limits it: [step-engine.md](step-engine.md).\n\n"
      "## How it is measured\n\n"
      "- **Simulator.** The real firmware images (`avrmotion-<board>.elf`, built with\n"
      "  avr-gcc) run cycle by cycle on libsimavr 1.6 with the project's timing patches\n"
      "  ([simulator.md](simulator.md): stock simavr 1.6 mis-times timer events and\n"
      "  pin edges). Each image runs at its board's clock.\n"
      "- **Traffic.** Each scenario sends one `MOVE` and then 2400 junk lines (`NOP`),\n"
      "  so the UART receives a line and transmits its error answer during the whole\n"
      "  motion, as with a sender that streams.\n"
      "- **Whole move.** Every figure covers the move from its first step to its last,\n"
      "  ramps included, not only the cruise:\n"
      "  - *cruise*: the mean rate over the steps planned at the fastest interval;\n"
      "  - *irq cycles/step*: every interrupt (step and UART) between the first and the\n"
      "    last step, each with its 4-cycle response and RETI's 4 cycles, divided by\n"
      "    the intervals between the steps; *CPU* is the same cycles as a share of the\n"
      "    time from the first step to the last;\n"
      "  - *spread*: max - min lateness of the steps against the schedule the planner\n"
      "    computes (the same core code run on the host, `sim/schedule.h`), in cycles;\n"
      "  - *doubled*: intervals longer than 1.5 times their scheduled interval;\n"
      "  - *pulse*: shortest..longest STEP high time of the timer-pulsed axis, cycles;\n"
      "  - *clamped*: the rate the firmware clamped F to (`warning: F clamped to N`);\n"
      "  - *exact*: the decoded position equals the steps commanded, and as many step\n"
      "    edges were seen. A run that is not exact, or that did not finish, is a\n"
      "    broken run and makes the benchmark fail; no figure has a target to meet.\n\n"
      "## Step engine\n\n");
  const std::vector<Table>& tables = engine_tables();
  for (size_t t = 0; t < tables.size(); ++t) {
    const Figures& first = engine[t].front();
    add(std::string("### ") + tables[t].list.front().image + " (" + first.mcu + ", " +
        format("%g MHz", first.f_cpu / 1e6) + "), " + tables[t].heading + "\n\n");
    add("| command | F asked (Hz) | clamped to (Hz) | cruise (Hz) | irq cycles/step | CPU | spread (cycles) | "
        "doubled | pulse (cycles) | steps | exact |\n");
    add("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
    for (size_t i = 0; i < tables[t].list.size(); ++i) {
      const Scenario& s = tables[t].list[i];
      const Figures& f = engine[t][i];
      add("| `" + move_line(s) + "` | " + std::to_string(s.rate) + " | " + clamped_text(f) + " | " +
          format("%.0f", f.cruise_hz) + " | " + format("%.1f", f.isr_cycles_per_step) + " | " +
          format("%.1f %%", 100 * f.cpu_load) + " | " + std::to_string(f.spread) + " | " +
          std::to_string(f.doubled) + " | " + pulse_text(f) + " | " + std::to_string(f.steps) + " | " +
          (f.ok ? "yes" : "NO") + " |\n");
    }
    add("\n");
  }

  add("## Image sizes\n\n"
      "Flash is `.text + .data`, RAM is `.data + .bss` (static data), both read from the\n"
      "ELF. Stack is the deepest byte the image wrote below its static data, found by\n"
      "painting the free RAM before reset, on a demo-like run (`MOVE <first axis>200\n"
      "F2000 A8000`, then `POS`); the driver board takes no commands, so its stack is\n"
      "not measured. Percentages are of the part's flash and RAM.\n\n"
      "| image | MCU | clock | flash (B) | of flash | RAM (B) | of RAM | stack (B) | of RAM | RAM + stack |\n"
      "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (size_t i = 0; i < sizes.size(); ++i) {
    const SizeRow& r = sizes[i];
    if (!r.found) continue;
    const PartSize* p = part_of(r.mcu);
    auto pct = [&](size_t v, unsigned of) { return p ? format("%.1f %%", 100.0 * v / of) : std::string("?"); };
    add(std::string("| ") + kSizeImages[i] + " | " + r.mcu + " | " + format("%g MHz", r.f_cpu / 1e6) + " | " +
        std::to_string(r.flash) + " | " + pct(r.flash, p ? p->flash : 1) + " | " + std::to_string(r.ram) + " | " +
        pct(r.ram, p ? p->ram : 1) + " | " + (r.stack ? std::to_string(r.stack) : "-") + " | " +
        (r.stack ? pct(r.stack, p ? p->ram : 1) : "-") + " | " +
        (r.stack ? pct(r.ram + r.stack, p ? p->ram : 1) : "-") + " |\n");
  }
  add("\nParts: ");
  for (size_t i = 0; i < sizeof kParts / sizeof kParts[0]; ++i) {
    add(std::string(i ? ", " : "") + kParts[i].mcu + " " + std::to_string(kParts[i].flash) + " B flash / " +
        std::to_string(kParts[i].ram) + " B RAM");
  }
  add(".\n\n");

  add("## Anchors\n\n"
      "Figures for other AVR step generators, quoted from earlier measurement in the\n"
      "simulator (issue 4, as [step-engine.md](step-engine.md) states them). They are\n"
      "not re-measured here: those firmwares are not part of this repository. How\n"
      "they were measured (UART traffic or not, whole move or cruise only) is not\n"
      "recorded with them, so compare orders of magnitude, not digits.\n\n"
      "| firmware | top step rate | cycles per step | source |\n"
      "|---|---:|---:|---|\n");
  for (const Anchor& a : kAnchors) {
    add(std::string("| ") + a.firmware + " | " + a.rate + " | " + a.cycles_per_step +
        " | quoted, not re-measured |\n");
  }
  add("\nThis run's avrmotion figures at the top rate of each table above (the fastest\n"
      "exact cruise, and its irq cycles/step, UART traffic included):\n\n"
      "| avrmotion axis | top step rate (Hz) | irq cycles/step | source |\n"
      "|---|---:|---:|---|\n");
  for (size_t t = 0; t < tables.size(); ++t) {
    const Figures* best = nullptr;
    for (const Figures& f : engine[t]) {
      if (f.ok && (!best || f.cruise_hz > best->cruise_hz)) best = &f;
    }
    add(std::string("| ") + tables[t].name + " | " + (best ? format("%.0f", best->cruise_hz) : "-") + " | " +
        (best ? format("%.1f", best->isr_cycles_per_step) : "-") + " | measured above |\n");
  }
  return o;
}

const char kUsage[] =
    "usage: avrmotion-bench [--firmware-dir DIR] [--jobs N] [--markdown FILE]\n"
    "  --firmware-dir DIR  the avrmotion-<board>.elf images (default: this build's)\n"
    "  --jobs N            run N jobs at a time, each in a process of its own (default: the\n"
    "                      number of cores); 1 runs every job in this process, in turn\n"
    "  --markdown FILE     also write the figures as a Markdown page (docs/benchmarks.md)\n"
    "Exit status: 0, 1 when a run is not exact, 2 when a run did not finish (or bad usage).\n";

}  // namespace

int main(int argc, char** argv) {
  std::string dir = AVRMOTION_FIRMWARE_DIR, markdown_path;
  unsigned workers = std::max(1u, std::thread::hardware_concurrency());
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--firmware-dir" && has_value) {
      dir = argv[++i];
    } else if (a == "--markdown" && has_value) {
      markdown_path = argv[++i];
    } else if (a == "--jobs" && has_value) {
      char* end = nullptr;
      const unsigned long n = std::strtoul(argv[++i], &end, 10);
      if (*end || n < 1 || n > 256) {
        std::fprintf(stderr, "avrmotion-bench: --jobs wants a number from 1 to 256\n%s", kUsage);
        return 2;
      }
      workers = unsigned(n);
    } else if (a == "--help" || a == "-h") {
      std::printf("%s", kUsage);
      return 0;
    } else {
      std::fprintf(stderr, "%s", kUsage);
      return 2;
    }
  }

  // The scenarios first, the short image-size runs last, so the last worker
  // to end is not left with a long job.
  std::vector<Job> jobs;
  const std::vector<Table>& tables = engine_tables();
  for (const Table& t : tables) {
    for (const Scenario& s : t.list) {
      jobs.push_back({std::string(s.image) + " " + move_line(s),
                      [&dir, s](Result& r) { r.figures = measure(dir, s); }});
    }
  }
  const size_t first_size_job = jobs.size();
  for (const char* name : kSizeImages) {
    jobs.push_back({std::string("size ") + name, [&dir, name](Result& r) { r.size = measure_size(dir, name); }});
  }

  std::vector<Result> results;
  try {
    results = run_jobs(jobs, workers);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "avrmotion-bench: %s\n", e.what());
    return 2;
  }

  bool unfinished = false, inexact = false;
  for (size_t i = 0; i < results.size(); ++i) {
    if (!results[i].done) {
      unfinished = true;
      std::fprintf(stderr, "avrmotion-bench: %s: %s\n", jobs[i].name.c_str(), results[i].error);
    } else if (i < first_size_job && !results[i].figures.ok) {
      inexact = true;
    }
  }

  std::vector<SizeRow> sizes;
  for (size_t i = first_size_job; i < results.size(); ++i) sizes.push_back(results[i].size);
  std::vector<std::vector<Figures>> engine;
  size_t k = 0;
  for (const Table& t : tables) {
    engine.emplace_back();
    for (size_t i = 0; i < t.list.size(); ++i) engine.back().push_back(results[k++].figures);
  }
  print_sizes(sizes);
  for (size_t t = 0; t < tables.size(); ++t) print_engine(tables[t], engine[t].data());
  std::fflush(stdout);

  if (unfinished || inexact) {
    std::fprintf(stderr, "avrmotion-bench: %s\n",
                 unfinished ? "a run did not finish: the figures are not valid"
                            : "a run did not end with every step exact");
    if (!markdown_path.empty()) std::fprintf(stderr, "avrmotion-bench: %s not written\n", markdown_path.c_str());
    return unfinished ? 2 : 1;
  }
  if (!markdown_path.empty()) {
    const std::string page = markdown(sizes, engine);
    FILE* out = std::fopen(markdown_path.c_str(), "w");
    const bool written = out && std::fwrite(page.data(), 1, page.size(), out) == page.size();
    if (!out || std::fclose(out) != 0 || !written) {
      std::fprintf(stderr, "avrmotion-bench: cannot write %s: %s\n", markdown_path.c_str(), std::strerror(errno));
      return 2;
    }
    std::fprintf(stderr, "avrmotion-bench: wrote %s\n", markdown_path.c_str());
  }
  return 0;
}
