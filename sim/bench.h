// avrmotion-bench's scenarios, figures and pages (sim/bench.cpp runs them).
//
//   bench_scenarios.cpp  the engine tables, the images whose sizes are
//                        measured, the parts' flash and RAM
//   bench_page.cpp       the tables on standard output and the Markdown page
//                        (docs/benchmarks.md), both from the same figures
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace bench {

struct Scenario {
  const char* image;
  char axis;
  uint32_t rate;
  uint32_t accel;
  uint32_t steps;
  char pulse_port;  // a STEP pin whose pulse widths to measure, or 0
  uint8_t pulse_bit;
  const char* also = "";  // axes moving the same steps with `axis` (a coordinated diagonal)
  // The board's kMaxStepRate, for the smoothing level of a coordinated
  // diagonal (sim/schedule.h); unused for one axis.
  uint32_t max_step_rate = 0;
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

// The m32's hot end (sim/bench_heater.cpp): M104 S200 from 25 C with
// Marlin's default gains on the simulated 40 W plant, kHeaterSeconds long.
struct HeaterFigures {
  bool ok = false;             // the run finished, no fault, the target reached
  double to_target_s = 0;      // first reading at or above 200 C
  double overshoot_c = 0;      // the highest reading above 200 C
  double settled_s = 0;        // from then on within +-0.3 C
  double hold_lo_c = 0, hold_hi_c = 0;  // the readings from settled_s to the end
  size_t samples = 0;          // PID samples timed (the last 10 s)
  double sample_cycles = 0;    // heater::poll() calls that ran a sample: mean cycles
  uint64_t sample_cycles_max = 0;
};
constexpr double kHeaterSeconds = 200;
HeaterFigures measure_heater(const std::string& firmware_dir);

// Slicer's files printed start to finish on the m32 (sim/bench_print.cpp):
// sim/slicer_file.h's prints, their estimates from the limits measured from
// the image (sim/print_limits.h), sent one line in flight at 115200 baud to
// the image with its hot end and its switches. The print time is the
// simulator's from the first step after M109's answer to the last step
// before the M400 after the park: the moves the estimate times (no
// heat-up, no homing).
struct PrintScenario {
  const char* label;   // one word
  int layers;
  int segments;        // chords of a perimeter (radius 10 mm)
  double initial_c;    // the hot end at the start
  const char* board = "m32";  // the image: avrmotion-<board>.elf
  bool i3_limits = false;     // the file's machine-limits block (sim/slicer_file.h, i3_file_limits())
  int flow_percent = 0;       // > 0: the file's M221 S<flow_percent>
};
const std::vector<PrintScenario>& print_scenarios();
struct PrintFigures {
  bool ran = false;            // the run finished (no fault, no budget spent)
  bool exact = false;          // every axis on its expected steps
  size_t lines = 0, answered = 0, errors = 0;
  int starvations = -1;
  double print_s = 0;          // simulated, the timed moves
  double estimate_s = 0;       // the estimator's for the same moves
  double total_s = 0;          // simulated, the whole run (heat-up and homing included)
  double wall_s = 0;           // the host's time for the run (varies: standard error only)
  double c_at_first_extrusion = 0;
  double accel_mm_s2 = 0, rate_mm_s = 0;  // X's, as probed
  char enabled_at_end[8] = {};
  unsigned switch_closes = 0;  // X, Y, Z together
  size_t held = 0;             // `held within the board's limit` lines (a file's limits the firmware clamped)
  int progress = -1;           // the last M73 percent the firmware echoed (sim/print_watch.h)
  char message[32] = {};       // the last M117 text it echoed
};
PrintFigures measure_print(const std::string& firmware_dir, const PrintScenario& s);
void print_print(const std::vector<PrintFigures>& p);
// The host's time per simulated second of each print, on standard error
// (it varies from run to run, so it is on neither the tables nor the page).
void print_host_time(const std::vector<PrintFigures>& p);
std::string print_markdown(const std::vector<PrintFigures>& p);

// The lathe (sim/bench_lathe.cpp): one locked pass on the m16-lathe image
// at a steady spindle speed (sim/lathe_run.h).
struct LatheScenario {
  const char* label;   // the encoder: "x4" (600-line quadrature) or "x1" (600 lines, one channel)
  bool quadrature;
  double rpm;
  double ramp_s;       // from rest to rpm (and back)
  const char* pitch;   // G33's pitch word
  int64_t pitch_num, pitch_den;  // um
};
struct LatheFigures {
  bool ran = false;
  double edge_rate = 0;        // counts/s at rpm
  int64_t counts = 0;          // the model's
  int64_t firmware_counts = 0;
  int64_t lost = 0;            // the firmware's doubtful counts
  bool exact = false;          // locked, every count exact after, no count lost
  uint64_t latency_max = 0;    // cycles: a count's edge to its first step's rise
  uint64_t vector_max = 0;     // INT0/INT1 entry to RETI
  double step_rate = 0;        // steps/s, the busiest 10 ms
  uint64_t pulse_min = 0;      // the shortest step pulse, cycles
};
const std::vector<LatheScenario>& lathe_scenarios();
LatheFigures measure_lathe(const std::string& firmware_dir, const LatheScenario& s);
void print_lathe(const std::vector<LatheFigures>& figures);

// One image's row of the size table.
struct SizeRow {
  bool found = false;  // the image exists (a missing one has no row)
  char mcu[24] = {};
  uint32_t f_cpu = 0;
  size_t flash = 0, ram = 0;  // .text + .data, .data + .bss
  unsigned stack = 0;         // 0: not measured
};

struct Table {
  const char* title;    // printed above the table (standard output)
  const char* heading;  // its Markdown heading, after the image, part and clock
  const char* name;     // a short name, for the anchors
  std::vector<Scenario> list;
};

const std::vector<Table>& engine_tables();
std::string move_line(const Scenario& s);

// The images of the size table, in its order.
extern const char* const kSizeImages[13];

// Each part's flash and RAM, bytes.
struct PartSize {
  const char* mcu;
  unsigned flash, ram;
};
extern const PartSize kParts[4];
const PartSize* part_of(const char* mcu);

void print_sizes(const std::vector<SizeRow>& rows);
void print_engine(const Table& t, const Figures* figures);
void print_heater(const HeaterFigures& h);
// The Markdown page: the same figures as the tables on standard output,
// formatted alike, and nothing that changes from run to run.
std::string markdown(const std::vector<SizeRow>& sizes, const std::vector<std::vector<Figures>>& engine,
                     const HeaterFigures& heater, const std::vector<PrintFigures>& print,
                     const std::vector<LatheFigures>& lathe);

}  // namespace bench
