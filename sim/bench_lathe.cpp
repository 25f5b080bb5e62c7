// The benchmark's lathe rows (bench.h, LatheScenario): one locked pass of
// the m16-lathe image per row (sim/lathe_run.h): the spindle from rest to
// the row's rpm, 0.5 s there, back to rest; the firmware's count and its
// doubtful counts against the encoder model's; every count after the lock
// against floor(lambda s). Sweeps of the edge rate for the 600-line encoder
// counted x4 (quadrature) and x1 (one channel) on a 0.5 mm pitch (few
// steps: the counting is what is measured), engaged on a fast spindle (0.3
// s ramp: the catch-up runs at the row's rate) and locked while slow (3 s
// ramp: locked counts at the row's rate, also 1 and 2 mm at 3000 rpm x4),
// and one coarse thread (4 TPI) brought up slowly, for the step rate.
#include <cstdio>
#include <string>

#include "bench.h"
#include "lathe_run.h"

namespace bench {

const std::vector<LatheScenario>& lathe_scenarios() {
  static const std::vector<LatheScenario> list = {
      {"x4", true, 800, 0.3, "K0.5", 500, 1},    {"x4", true, 1000, 0.3, "K0.5", 500, 1},
      {"x4", true, 1100, 0.3, "K0.5", 500, 1},   {"x4", true, 1200, 0.3, "K0.5", 500, 1},
      {"x4", true, 1300, 0.3, "K0.5", 500, 1},   {"x4", true, 1400, 0.3, "K0.5", 500, 1},
      {"x4", true, 1500, 0.3, "K0.5", 500, 1},   {"x4", true, 3000, 0.3, "K0.5", 500, 1},
      {"x4", true, 2000, 3.0, "K0.5", 500, 1},   {"x4", true, 2500, 3.0, "K0.5", 500, 1},
      {"x4", true, 3000, 3.0, "K0.5", 500, 1},   {"x4", true, 3000, 3.0, "K1", 1000, 1},
      {"x4", true, 3000, 3.0, "K2", 2000, 1},
      {"x1", false, 3000, 0.3, "K0.5", 500, 1},  {"x1", false, 4000, 0.3, "K0.5", 500, 1},
      {"x1", false, 5000, 0.3, "K0.5", 500, 1},  {"x1", false, 6000, 0.3, "K0.5", 500, 1},
      {"x1", false, 7000, 0.3, "K0.5", 500, 1},  {"x1", false, 12000, 0.3, "K0.5", 500, 1},
      {"x1", false, 8000, 3.0, "K0.5", 500, 1},  {"x1", false, 12000, 3.0, "K0.5", 500, 1},
      {"x4", true, 1000, 3.0, "P4", 25400, 4},
  };
  return list;
}

LatheFigures measure_lathe(const std::string& dir, const LatheScenario& s) {
  LatheFigures f;
  sim::SpindleParams p;
  p.lines = 600;
  p.quadrature = s.quadrature;
  sim::ThreadSpec t{s.pitch_num, s.pitch_den};
  t.counts_per_turn = s.quadrature ? 2400 : 600;
  const sim::LatheRunFigures r =
      sim::run_lathe_pass(dir + "/avrmotion-m16-lathe.elf", p, s.rpm, s.ramp_s, 0.5,
                          s.quadrature ? "ENCODER C600 E4" : "ENCODER C600 E1", std::string("G33 Z-900 ") + s.pitch, t);
  f.ran = r.ran;
  f.edge_rate = r.edge_rate;
  f.counts = r.model_counts;
  f.firmware_counts = r.firmware_counts;
  f.lost = r.firmware_lost;
  f.exact = r.ran && r.pass.locked && r.pass.mismatches == 0 && r.pass.position == r.pass.expected &&
            r.firmware_counts == r.model_counts && r.firmware_lost == 0;
  f.latency_max = r.pass.max_latency;
  f.vector_max = r.vector_max;
  f.step_rate = r.step_rate;
  f.pulse_min = r.pulses.min_high;
  return f;
}

void print_lathe(const std::vector<LatheFigures>& figures) {
  const std::vector<LatheScenario>& list = lathe_scenarios();
  std::printf("Lathe, m16-lathe: a 600-line encoder, one locked G33 pass at a steady rpm\n");
  std::printf("%4s %6s %6s %5s %9s %9s %9s %6s %6s %8s %8s %8s %6s\n", "enc", "pitch", "rpm", "ramp", "counts/s",
              "counts", "firmware", "lost", "exact", "latency", "vector", "steps/s", "pulse");
  double best[2][2] = {{0, 0}, {0, 0}};
  for (size_t i = 0; i < list.size(); ++i) {
    const LatheScenario& s = list[i];
    const LatheFigures& f = figures[i];
    std::printf("%4s %6s %6.0f %5.1f %9.0f %9lld %9lld %6lld %6s %8llu %8llu %8.0f %6llu\n", s.label, s.pitch, s.rpm,
                s.ramp_s, f.edge_rate, (long long)f.counts, (long long)f.firmware_counts, (long long)f.lost,
                f.exact ? "yes" : "NO", (unsigned long long)f.latency_max, (unsigned long long)f.vector_max,
                f.step_rate, (unsigned long long)f.pulse_min);
    double& b = best[s.ramp_s < 1 ? 0 : 1][s.quadrature ? 0 : 1];
    if (f.exact && f.edge_rate > b) b = f.edge_rate;
  }
  std::printf("  highest exact rate, 0.3 s ramp: x4 %.0f counts/s, x1 %.0f counts/s; 3 s ramp: x4 %.0f, x1 %.0f\n\n",
              best[0][0], best[0][1], best[1][0], best[1][1]);
}

}  // namespace bench
