// The text protocol on the UART (docs/protocol.md): one command per line,
// answered by "ok" or "error: <reason>" once it has been accepted or refused.
//
// Contract
//   poll() is called from the main loop. It reads received bytes into the line
//   buffer only while no command is waiting, so a command that must wait (a
//   move while the previous one is still being queued, POS/WAIT/RELEASE until
//   motion ends) holds back the next line instead of losing it. The sender
//   keeps one line in flight and sends the next after the answer.
#pragma once

namespace protocol {

void banner();
void poll();

}  // namespace protocol
