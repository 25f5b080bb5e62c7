// The lathe's UART front end (115200 at 16 MHz; docs/lathe.md, "Over the
// UART"): one line in, one answer out (`ok`, `error: <reason>`, the status
// line), so a sender can cut threads too.
#pragma once

namespace protocol {

void banner();
void poll();

}  // namespace protocol
