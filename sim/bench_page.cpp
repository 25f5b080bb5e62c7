#include <cstdio>
#include <string>

#include "bench.h"

namespace bench {

namespace {

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

std::string clamped_text(const Figures& f) { return f.clamped_to ? std::to_string(f.clamped_to) : "-"; }

std::string pulse_text(const Figures& f) {
  return f.pulse_max ? std::to_string(f.pulse_min) + ".." + std::to_string(f.pulse_max) : std::string("-");
}

std::string format(const char* fmt, double v) {
  char b[64];
  std::snprintf(b, sizeof b, fmt, v);
  return b;
}

}  // namespace

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

void print_heater(const HeaterFigures& h) {
  std::printf("Hot end, m32: M104 S200 from 25 C, Marlin's default gains, the simulated 40 W plant, %.0f s\n",
              kHeaterSeconds);
  std::printf("  to 200 C   overshoot   settled (+-0.3 C)   hold from then    PID sample, cycles\n");
  std::printf("  %6.1f s   %6.2f C    %7.1f s           %.2f..%.2f C   mean %.0f, max %llu, of %zu\n\n",
              h.to_target_s, h.overshoot_c, h.settled_s, h.hold_lo_c, h.hold_hi_c, h.sample_cycles,
              (unsigned long long)h.sample_cycles_max, h.samples);
}

// The Markdown page (docs/benchmarks.md): the same figures as the tables on
// standard output, formatted alike, and nothing that changes from run to run
// (no date, no wall time), so the page only changes when a figure does.
std::string markdown(const std::vector<SizeRow>& sizes, const std::vector<std::vector<Figures>>& engine,
                     const HeaterFigures& heater, const std::vector<PrintFigures>& print,
                     const std::vector<LatheFigures>& lathe) {
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
      "  - *clamped*: the rate the firmware clamped F to (`[MSG:F clamped to N]`);\n"
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

  add(format("## Hot end (m32)\n\n"
             "`M104 S200` from 25 C with Marlin's default gains, on the simulated 40 W hot end\n"
             "(`sim/thermal_plant.h`, [heater.md](heater.md)), %.0f s. The temperatures are the\n"
             "thermistor's as the plant logs them every 100 ms; *settled* is the time from which\n"
             "every reading stays within +-0.3 C of 200 C, *hold* their range from then to the end.\n"
             "*PID sample*: the `heater::poll()` calls of the last 10 s that ran a 125 ms sample\n"
             "(conversion, PID, safety, PWM; those over 1000 cycles), from their first instruction\n"
             "to their return, interrupts included.\n\n",
             kHeaterSeconds));
  add("| to 200 C (s) | overshoot (C) | settled (s) | hold (C) | PID sample, mean (cycles) | max | samples |\n"
      "|---:|---:|---:|---:|---:|---:|---:|\n");
  char row[160];
  std::snprintf(row, sizeof row, "| %.1f | %.2f | %.1f | %.2f..%.2f | %.0f | %llu | %zu |\n\n", heater.to_target_s,
                heater.overshoot_c, heater.settled_s, heater.hold_lo_c, heater.hold_hi_c, heater.sample_cycles,
                (unsigned long long)heater.sample_cycles_max, heater.samples);
  add(row);
  add(print_markdown(print));

  add("## Lathe (m16-lathe)\n\n"
      "One locked `G33 Z-900 <pitch>` pass per row on the simulated spindle (`sim/spindle_encoder.h`,\n"
      "[lathe.md](lathe.md)): a 600-line encoder counted x4 (quadrature, 2400 counts a turn) or x1\n"
      "(one channel, 600), from rest to the row's rpm over the row's *ramp* (s), 0.5 s there, back\n"
      "to rest over the same time. *counts*: the\n"
      "encoder model's; *firmware*: the image's count; *lost*: counts its decoder could not be\n"
      "sure of; *exact*: locked, every count after the lock on floor(lambda s), no count lost.\n"
      "*latency*: cycles from the count's edge to its first step's rise (16 per us), the most\n"
      "over the run's stepping counts; *vector*: the longest INT0/INT1 run, entry to RETI;\n"
      "*steps/s*: the busiest 10 ms; *pulse*: the shortest step pulse, cycles. A 0.3 s ramp\n"
      "engages the pass while the spindle is already fast, so the catch-up's counts (the C vector,\n"
      "the pace) run at the row's rate; a 3 s ramp locks the carriage while the target is still\n"
      "slow, so the row's rate is a locked count's (the assembly's).\n\n"
      "| encoder | pitch | rpm | ramp | counts/s | counts | firmware | lost | exact | latency | vector | steps/s | pulse |\n"
      "|---|---|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|\n");
  double best[2][2] = {{0, 0}, {0, 0}};
  for (size_t i = 0; i < lathe.size(); ++i) {
    const LatheScenario& s = lathe_scenarios()[i];
    const LatheFigures& f = lathe[i];
    add(std::string("| ") + s.label + " | " + s.pitch + " | " + format("%.0f", s.rpm) + " | " +
        format("%.1f", s.ramp_s) + " | " + format("%.0f", f.edge_rate) + " | " + std::to_string(f.counts) + " | " + std::to_string(f.firmware_counts) +
        " | " + std::to_string(f.lost) + " | " + (f.exact ? "yes" : "NO") + " | " + std::to_string(f.latency_max) +
        " | " + std::to_string(f.vector_max) + " | " + format("%.0f", f.step_rate) + " | " +
        std::to_string(f.pulse_min) + " |\n");
    double& b = best[s.ramp_s < 1 ? 0 : 1][s.quadrature ? 0 : 1];
    if (f.exact && f.edge_rate > b) b = f.edge_rate;
  }
  add(format("\nHighest exact rate, 0.3 s ramp: x4 %.0f counts/s, ", best[0][0]) +
      format("x1 %.0f counts/s; 3 s ramp: ", best[0][1]) + format("x4 %.0f counts/s, ", best[1][0]) +
      format("x1 %.0f counts/s.\n\n", best[1][1]));

  add("## Image sizes\n\n"
      "Flash is `.text + .data`, RAM is `.data + .bss` (static data), both read from the\n"
      "ELF. Stack is the deepest byte the image wrote below its static data, found by\n"
      "painting the free RAM before reset, on a demo-like run (`MOVE <first axis>200\n"
      "F2000 A8000`, then `POS`; the lathe: `ENCODER C600 E4`, `G33 Z-10 P13 D3 E2`, `STOP`,\n"
      "`?`, `G0 Z0.1`); the driver board takes no commands, so its stack is\n"
      "not measured. Percentages are of the flash an image may fill (on the Uno the\n"
      "bootloader keeps 512 bytes) and of the part's RAM.\n\n"
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

}  // namespace bench
