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

#include "bench.h"
#include "machine.h"
#include "schedule.h"

namespace {

using Clock = std::chrono::steady_clock;
using namespace bench;

// What a job sends back. Plain bytes, so that a child process can write it
// into a pipe as it is.
struct Result {
  bool done = false;  // the job ran to its end (no exception, no crash)
  char error[480] = {};
  Figures figures;
  SizeRow size;
  HeaterFigures heater;
  LatheFigures lathe;
  PrintFigures print;
};
static_assert(std::is_trivially_copyable<Result>::value, "a Result crosses a pipe as bytes");
static_assert(sizeof(Result) <= PIPE_BUF, "a Result fits the pipe in one write");

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
  m.serial().add_line(move_line(s));
  // A junk line and its refusal (`[MSG:unknown command]`, `error:20`: 35
  // bytes both ways) take about 3 ms at 115200 baud: 1000 keep the UART busy
  // for the longest scenario (2.1 s).
  for (int i = 0; i < 1000; ++i) m.serial().add_line("NOP");
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
    if (line.rfind("[MSG:F clamped to ", 0) == 0) f.clamped_to = uint32_t(std::stoul(line.substr(18)));
  }
  const double pos = m.axis(s.axis)->steps();
  f.steps = size_t(pos >= 0 ? pos : -pos);
  f.ok = f.steps == s.steps && st.size() == s.steps;
  for (const char* a = s.also; *a; ++a)
    f.ok = f.ok && m.axis(*a) && m.axis(*a)->step_cycles.size() == s.steps && m.axis(*a)->steps() == double(s.steps);
  if (!f.ok || st.size() < 2) return f;

  // Every step of the whole move against the schedule, ramps included.
  const sim::Ramp ramp{m.f_cpu(), f.clamped_to ? f.clamped_to : s.rate, s.accel};
  const std::vector<uint32_t> plan =
      *s.also ? sim::smoothed_schedule(s.steps, ramp, sim::smoothing_level(s.steps, ramp.rate, s.max_step_rate))
              : sim::planned_schedule(s.steps, ramp);
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
  if (std::string(name) == "m16-lathe" || std::string(name) == "m16-servo") {
    // The lathe's deepest line: a three-start thread's ratio and phase.
    for (const char* line : {"ENCODER C600 E4", "G33 Z-10 P13 D3 E2", "STOP", "?", "G0 Z0.1"})
      m.serial().add_line(line);
    m.run_script(16000000ull * 10);
    r.stack = m.stack_bytes();
  } else if (std::string(name) != "m32-driver") {
    const std::string axis(1, m.axes().front().name);
    if (!(m.board().program & am::kProgramCommands)) {  // G-code only: the printer, the mill
      m.serial().add_line("G91");
      m.serial().add_line("G1 " + axis + "0.2 F120");
      m.serial().add_line("M114");
    } else {
      m.serial().add_line("MOVE " + axis + "200 F2000 A8000");
      m.serial().add_line("POS");
    }
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
    const bool heater = job.name.rfind("heater ", 0) == 0, lathe = job.name.rfind("lathe ", 0) == 0;
    const bool print = job.name.rfind("print ", 0) == 0;
    const bool inexact = r.done && job.name.rfind("size ", 0) != 0 &&
                         (heater  ? !r.heater.ok
                          : print ? !r.print.ran || !r.print.exact
                          : lathe ? !r.lathe.ran
                                  : !r.figures.ok);
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
  // The hot end's run is the longest: first.
  jobs.insert(jobs.begin(), Job{"heater m32 M104 S200", [&dir](Result& r) { r.heater = measure_heater(dir); }});
  // The prints next: the next longest.
  const std::vector<PrintScenario>& prints = print_scenarios();
  for (size_t i = 0; i < prints.size(); ++i) {
    const PrintScenario s = prints[i];
    jobs.insert(jobs.begin() + long(1 + i), Job{std::string("print ") + s.board + " " + s.label,
                                                [&dir, s](Result& r) { r.print = measure_print(dir, s); }});
  }
  const size_t first_lathe_job = jobs.size();
  for (const LatheScenario& s : lathe_scenarios()) {
    jobs.push_back({std::string("lathe ") + s.label + " " + s.pitch + " " + std::to_string(int(s.rpm)) + " rpm",
                    [&dir, s](Result& r) { r.lathe = measure_lathe(dir, s); }});
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
    } else if (i == 0   ? !results[i].heater.ok
               : i <= prints.size() ? !results[i].print.ran || !results[i].print.exact
               : i < first_lathe_job ? !results[i].figures.ok
                                            : i < first_size_job && !results[i].lathe.ran) {
      inexact = true;
    }
  }
  const HeaterFigures heater = results.front().heater;
  std::vector<PrintFigures> print;
  for (size_t i = 0; i < prints.size(); ++i) print.push_back(results[1 + i].print);
  print_host_time(print);

  std::vector<SizeRow> sizes;
  for (size_t i = first_size_job; i < results.size(); ++i) sizes.push_back(results[i].size);
  std::vector<LatheFigures> lathe;
  for (size_t i = first_lathe_job; i < first_size_job; ++i) lathe.push_back(results[i].lathe);
  std::vector<std::vector<Figures>> engine;
  size_t k = 1 + prints.size();  // after the heater's and the prints' jobs
  for (const Table& t : tables) {
    engine.emplace_back();
    for (size_t i = 0; i < t.list.size(); ++i) engine.back().push_back(results[k++].figures);
  }
  print_sizes(sizes);
  for (size_t t = 0; t < tables.size(); ++t) print_engine(tables[t], engine[t].data());
  print_heater(heater);
  print_print(print);
  print_lathe(lathe);
  std::fflush(stdout);

  if (unfinished || inexact) {
    std::fprintf(stderr, "avrmotion-bench: %s\n",
                 unfinished ? "a run did not finish: the figures are not valid"
                            : "a run did not end with every step exact (or the hot end did not settle)");
    if (!markdown_path.empty()) std::fprintf(stderr, "avrmotion-bench: %s not written\n", markdown_path.c_str());
    return unfinished ? 2 : 1;
  }
  if (!markdown_path.empty()) {
    const std::string page = markdown(sizes, engine, heater, print, lathe);
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
