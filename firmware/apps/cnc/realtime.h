// grbl's realtime commands (board::kRealtime): single bytes a sender may put
// anywhere in the stream, mid-line and with the receive ring full. The
// receive interrupt takes them out before they reach a line
// (hal::uart::take_realtime) and never queues them.
//
// Contract
//   `?`   poll() prints one status report as soon as the main loop comes
//         round: <State|MPos:x,y,z|FS:feed,0>, State Idle, Run, Hold:1
//         (slowing down), Hold:0 (held), Alarm; MPos in mm with 3 decimals, where
//         the motors are at that instant (the odometer's count), for every
//         axis of the board; FS the feed of the newest G-code line (mm/min)
//         while anything moves, 0 at rest. Several `?` before the report print one.
//   `!`   feed hold: the path slows down to rest at the blocks' own
//         acceleration (path::hold()); queued lines stay queued.
//   `~`   resume after a hold (path::resume()); nothing while not held.
//   0x18  soft reset (Ctrl-X): in the interrupt, the step clock stops and
//         the chip restarts through the watchdog 15 ms later; no step is made
//         after the byte is received. What was queued is gone. A reset that
//         stopped steps leaves the position lost: after the banner boot()
//         prints grbl's `ALARM:3` (reply::alarm()), and motion is refused
//         (error:9) until `$X` (or M999).
#pragma once

namespace realtime {

// After the banner; by_watchdog: hal::watchdog::after_reset()'s answer.
void boot(bool by_watchdog);
void poll();

}  // namespace realtime
