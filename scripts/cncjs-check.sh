#!/usr/bin/env bash
# A manual check, not in CI (it downloads cncjs and its dependencies from the
# npm registry, about 150 MB): cncjs, a grbl sender, streams a G-code file in
# its Grbl mode to the m32-cnc image (or BOARD's) through avrmotion-sim
# --pty, and the simulator's report must end on the file's last target.
#
#   ./scripts/cncjs-check.sh [FILE]     (default: a generated square, 200 lines)
#   BOARD=m1284 ./scripts/cncjs-check.sh   the m1284, in grbl's style by a
#                                          stored `$200=0` (--save-eeprom)
#
# Installs cncjs, socket.io-client and jsonwebtoken into build/cncjs (npm,
# Node.js 20), starts the simulator on a pty linked at build/cncjs/port,
# starts the cncjs server on 127.0.0.1:8123 with a throw-away secret, and
# drives it as its pendants do: a token signed with that secret, `open` the
# port as Grbl at 115200, `gcode:load` and `gcode:start`, then waits for the
# workflow to go idle with every line received, closes the port and prints
# the report's axes.
#
# Status (run 2026-12-02, cncjs 1.11.5 on Node.js 20, npm's install scripts
# not run): cncjs connects in Grbl mode and reads the banner; its `$$` gets
# error:3 (`[MSG:not in this image]`: no settings listing on the m32-cnc
# yet); it polls with `?` and streams counting against grbl's 128 bytes into
# the 128-byte receive ring: 204 of 204 lines acknowledged, no error, and the
# report ends on the square's last target, X 1.234 Y 5.678 mm. The check
# fails when a line is not acknowledged or, for the default file, the
# report's X and Y are not that target.
# With BOARD=m1284 (run 2026-12-02, the same cncjs): the banner in grbl's
# style from the stored `$200=0`; `$$` answers the 43 settings, which
# cncjs annotates ($3, $5, $100.. with its own names); 204 of 204 lines
# acknowledged, no error, the report ends on X 1.234 Y 5.678 mm.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
work=build/cncjs
mkdir -p "$work"
if [ ! -d "$work/node_modules/cncjs" ]; then
  echo "cncjs-check: npm install cncjs (into $work)" >&2
  (cd "$work" && npm install --no-audit --no-fund cncjs@1 socket.io-client@2 jsonwebtoken@9 >&2)
fi

file=${1:-}
if [ -z "$file" ]; then
  file=$work/square.gcode
  {
    echo "G21"; echo "G90"
    for i in $(seq 1 50); do
      echo "G1 X$((i % 10)).$((i % 7))00 Y0.000 F3000"
      echo "G1 X10.000 Y$((i % 10)).$((i % 3))00"
      echo "G1 X0.000 Y10.000"
      echo "G1 X0.000 Y0.000"
    done
    echo "G1 X1.234 Y5.678 F3000"
  } >"$file"
fi

secret=$(head -c 16 /dev/urandom | od -An -tx1 | tr -d ' \n')
printf '{"secret":"%s","allowRemoteAccess":false}\n' "$secret" >"$work/cncrc"
board=${BOARD:-m32-cnc}
eeprom=()
if [ "$board" = m1284 ]; then  # Marlin's style by default: grbl's stored first
  printf '$200=0\n' | ./build/sim/avrmotion-sim --board m1284 --save-eeprom "$work/m1284.eeprom" >/dev/null
  eeprom=(--eeprom "$work/m1284.eeprom")
fi
./build/sim/avrmotion-sim --board "$board" "${eeprom[@]}" --pty --link "$work/port" --speed max --linger 0 \
  --max-seconds 600 --report "$work/report.json" &
sim=$!
node "$work/node_modules/cncjs/bin/cncjs" --host 127.0.0.1 --port 8123 --config "$PWD/$work/cncrc" >"$work/cncjs.log" 2>&1 &
server=$!
trap 'kill $server $sim 2>/dev/null || true' EXIT
for _ in $(seq 1 100); do [ -e "$work/port" ] && grep -q "Started the server" "$work/cncjs.log" && break; sleep 0.2; done

CNCJS_SECRET=$secret CNCJS_PORT=$(readlink -f "$work/port") CNCJS_FILE=$file \
  NODE_PATH=$work/node_modules node <<'EOF'
const fs = require('fs');
const io = require('socket.io-client');
const jwt = require('jsonwebtoken');
const token = jwt.sign({ id: '', name: 'avrmotion-check' }, process.env.CNCJS_SECRET, { expiresIn: '1h' });
const port = process.env.CNCJS_PORT;
const gcode = fs.readFileSync(process.env.CNCJS_FILE, 'utf8');
const socket = io.connect('ws://127.0.0.1:8123', { query: 'token=' + token });
let started = false;
const fail = (why) => { console.error('cncjs-check: ' + why); process.exit(1); };
setTimeout(() => fail('no end within 5 minutes'), 300000);
socket.on('connect', () => socket.emit('open', port, { baudrate: 115200, controllerType: 'Grbl' }));
socket.on('serialport:error', (e) => fail('port: ' + JSON.stringify(e)));
socket.on('serialport:read', (line) => console.error('< ' + line));
socket.on('serialport:open', () => {
  socket.emit('command', port, 'gcode:load', 'check.gcode', gcode, (err) => {
    if (err) fail('load: ' + err);
    socket.emit('command', port, 'gcode:start');
    started = true;
  });
});
socket.on('sender:status', (s) => {
  if (started && s.total > 0 && s.received >= s.total) {
    console.error(`cncjs-check: ${s.received} of ${s.total} lines acknowledged`);
    socket.emit('close', port, () => process.exit(0));
  }
});
EOF
wait $sim
grep -A6 '"axes"' "$work/report.json"
if [ -z "${1:-}" ]; then
  grep -q '"X": {"steps": 1234, "mm": 1.234,' "$work/report.json" &&
    grep -q '"Y": {"steps": 5678, "mm": 5.678,' "$work/report.json" ||
    { echo "cncjs-check: FAILED, the report does not end on X1.234 Y5.678" >&2; exit 1; }
  echo "cncjs-check: ends on X1.234 Y5.678"
fi
