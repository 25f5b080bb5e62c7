#!/usr/bin/python3
# Streams a G-code file to a serial port with printrun's printcore (Debian's
# printrun-common, Debian's own python3), as Pronterface prints a file:
# numbered, checksummed lines, one in flight, resends on request.
# tests/sim/test_printcore.cpp runs it against avrmotion-sim --pty.
#
#   printcore_stream.py PORT FILE [--corrupt N] [--guard SECONDS]
#
# --corrupt N changes the checksum of the first sending of line N (the
# printer must ask for it again, printcore then sends its stored copy);
# without it (or N < 0) nothing is changed.
# After the print it sends M400 and waits for every line sent to have its
# `ok`, then closes the port and prints one JSON object on standard output:
#   sent: lines written (M110s and resends included) but M105
#   oks: `ok` lines received but M105's `ok T:...`
#   m105_sent, m105_oks: printcore's M105 while it waits for the printer's
#   `start` (sent at once on the open: the MCU may still be booting, as a
#   real board's bootloader would, and not hear it)
#   errors: the `Error:` lines; resends: the numbers of the `Resend:`
#   lines; corrupted: whether line N was corrupted
# Exit status 0, or 1 when a wait ran past the guard (a hung print).
import argparse
import json
import sys
import threading

from printrun import gcoder
from printrun.printcore import printcore


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("port")
    ap.add_argument("file")
    ap.add_argument("--corrupt", type=int, default=-1)
    ap.add_argument("--guard", type=float, default=120.0)
    args = ap.parse_args()
    with open(args.file) as f:
        lines = [l.rstrip("\r\n") for l in f]

    cond = threading.Condition()
    st = {"sent": 0, "oks": 0, "m105_sent": 0, "m105_oks": 0, "errors": [], "resends": [], "corrupted": False,
          "online": False, "ended": False}

    def received(line):
        line = line.strip()
        with cond:
            if line.startswith("ok T:"):
                st["m105_oks"] += 1
            elif line.startswith("ok"):
                st["oks"] += 1
            elif line.startswith("Resend:"):
                st["resends"].append(int(line.split(":")[1]))
            elif line.startswith("Error:"):
                st["errors"].append(line)
            cond.notify_all()

    def sent(command, gline):
        with cond:
            st["m105_sent" if command.startswith("M105") else "sent"] += 1

    def flag(name):
        def set_it():
            with cond:
                st[name] = True
                cond.notify_all()
        return set_it

    def wait_for(what):
        with cond:
            if not cond.wait_for(what, timeout=args.guard):
                print(json.dumps(dict(st, hung=True)))
                sys.exit(1)

    p = printcore()
    p.recvcb = received
    p.sendcb = sent
    p.onlinecb = flag("online")
    p.endcb = flag("ended")
    p.connect(args.port, 115200)
    write = p.printer.write

    def corrupting_write(data):
        text = data.decode("ascii")
        if args.corrupt >= 0 and not st["corrupted"] and text.startswith("N%d " % args.corrupt):
            star = text.rindex("*")
            text = text[: star + 1] + str((int(text[star + 1 :]) + 1) % 256) + "\n"
            st["corrupted"] = True
        return write(text.encode("ascii"))

    p.printer.write = corrupting_write
    wait_for(lambda: st["online"])
    p.startprint(gcoder.LightGCode(lines))
    wait_for(lambda: st["ended"])
    with cond:
        before = st["sent"]
    p.send_now("M400")
    wait_for(lambda: st["sent"] > before and st["oks"] >= st["sent"])
    p.disconnect()
    del st["online"], st["ended"]
    print(json.dumps(st))


main()
