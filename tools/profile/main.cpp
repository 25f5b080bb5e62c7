// avrmotion-profile: a move's speed profile as the firmware would time it,
// and whether a given motor and load can follow it. See docs/ramps.md.
#include <cstdio>
#include <string>
#include <vector>

#include "tools/profile/profile.h"

int main(int argc, char** argv) {
  using namespace am::profile;
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h") {
    std::fputs(usage(), args.empty() ? stderr : stdout);
    return args.empty() ? 2 : 0;
  }
  Options o;
  std::string error = parse_args(args, o);
  if (error.empty()) {
    const std::vector<uint32_t> intervals = plan_intervals(o, error);
    if (error.empty()) {
      std::printf("# %s method: %u steps, %u steps/s, accel %u, decel %u steps/s^2, %u Hz timer, %u steps/rev\n",
                  o.method == Method::seed ? "seed" : "exact", o.steps, o.speed, o.accel, o.decel,
                  o.tick_hz, o.steps_per_rev);
      std::printf("%8s %10s %10s %8s %9s\n", "step", "time_s", "delay_us", "rpm", "steps/s");
      double t = 0;
      for (size_t k = 0; k < intervals.size(); ++k) {
        t += double(intervals[k]) / o.tick_hz;
        if (k % o.every != 0 && k + 1 != intervals.size()) continue;
        const double rate = double(o.tick_hz) / intervals[k];
        std::printf("%8zu %10.5f %10.0f %8.1f %9.1f\n", k, t, intervals[k] * 1e6 / o.tick_hz,
                    rate * 60 / o.steps_per_rev, rate);
      }
      if (!o.torque.empty()) {
        const Motor motor(o.torque, o.load, o.inertia, o.steps_per_rev);
        const StallReport r = check_ramp(intervals, o.tick_hz, motor);
        std::printf("# pull-out rate with this load: %.1f steps/s\n", motor.pull_out_rate());
        if (r.follows) {
          std::printf("# the motor can follow this ramp\n");
        } else {
          std::printf("# STALL at step %u (%.1f steps/s, %.1f rpm): ramp needs %.0f steps/s^2, motor gives %.0f\n",
                      r.step - 1, r.rate, r.rate * 60 / o.steps_per_rev, r.required, r.available);
          return 1;
        }
      }
      return 0;
    }
  }
  std::fprintf(stderr, "avrmotion-profile: %s\n%s", error.c_str(), usage());
  return 2;
}
