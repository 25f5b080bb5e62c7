// avrmotion-sim --pty: a board image run as a serial port (docs/simulator.md,
// "The simulator as a serial port").
//
// Contract of run_pty()
//   - The MCU is held in reset until a client first opens the port, so a
//     client that opens it after start-up gets the banner, and the budget
//     counts from that open.
//   - Every later open resets the MCU, as opening an Arduino's port does
//     (DTR pulses RESET): the new client gets a fresh banner and firmware
//     state. Motor positions (the decoders) carry on; the motors do not move
//     on a reset.
//   - Client -> AVR: the client's bytes are handed to the UART one per byte
//     time (10 bits at the board's baud rate, in simulated cycles), never
//     faster. At most kBacklog of them wait in the simulator; the rest stay
//     in the pty, so a client that writes faster than the line blocks, as on
//     a real port. Bytes a client wrote just before it closed still go.
//   - AVR -> client: written as they come; what the firmware prints while
//     no client has the port open is counted and dropped (it never blocks
//     the simulation).
//   - Pacing: simulated time follows wall-clock time times `speed` while a
//     client is there (speed 0: as fast as it goes), and real time while
//     none is. A run that falls more than 0.1 s behind starts its pacing
//     again from there instead of racing to catch up (max_lag_s says by how
//     much it fell behind at worst).
//   - End: `done` once the client has closed and no client opened the port
//     again within `linger_s` (simulated, so real-time) seconds;
//     `budget_spent` after `budget` cycles from the first open (if set);
//     `cpu_stopped`; `interrupted` on SIGINT or SIGTERM (installed here).
//     A simavr error throws SimulatorFault, as every run does (machine.h).
#pragma once
#include <cstdint>
#include <ostream>

#include "machine.h"
#include "pty_port.h"

namespace sim {

struct PtyOptions {
  double speed = 1;       // simulated seconds per wall-clock second; 0: no pacing
  double linger_s = 2;    // how long after a close a client may reopen
  uint64_t budget = 0;    // cycles from the first open; 0: none
  std::ostream* progress = nullptr;  // progress_line() about once a second
};

struct PtyStats {
  unsigned sessions = 0;            // client opens seen
  uint64_t bytes_to_avr = 0;        // client bytes handed to the UART
  uint64_t bytes_from_avr = 0;      // firmware bytes written to a client
  uint64_t bytes_discarded = 0;     // firmware bytes while no client had it open
  uint64_t bytes_dropped_at_reset = 0;  // client bytes still queued when a new client reset the MCU
  uint64_t min_byte_interval = 0;   // shortest cycles between two client bytes at the UART
  double wall_seconds = 0;          // first open to the end
  double simulated_seconds = 0;     // the same span in simulated time
  double max_lag_s = 0;             // worst lag behind the pace (paced stretches)
};

RunEnd run_pty(Machine& m, PtyPort& port, const PtyOptions& options, PtyStats& stats);

}  // namespace sim
