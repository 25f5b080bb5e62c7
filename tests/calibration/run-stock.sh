#!/bin/sh
# Run every calibration program against Debian's stock libsimavr and the
# patched one, and print the measurements side by side (the table in
# docs/simulator.md comes from this). Needs a configured and built tree:
#   cmake -S . -B build && cmake --build build && tests/calibration/run-stock.sh build
# Exit status is 0 when the patched runner passes everything (the stock
# failures are the point of the exercise).
set -eu
build=${1:-build}
src=$(cd "$(dirname "$0")" && pwd)/programs
bin=$build/tests   # the runners (the programs are in $build/calibration-avr)
[ -x "$bin/calib_runner_stock" ] || { echo "no $bin/calib_runner_stock (libsimavr-dev missing?)" >&2; exit 2; }
status=0
echo "| program | mcu | expectation | expected | stock 1.6 | patched |"
echo "|---|---|---|---|---|---|"
for elf in "$build"/calibration-avr/*.elf; do
  base=$(basename "$elf" .elf)
  name=${base%-*}
  mcu=${base##*-}
  "$bin/calib_runner_stock" --mcu "$mcu" "$elf" "$src/$name.S" 2>/dev/null > "$build/.stock.out" || true
  "$bin/calib_runner" --mcu "$mcu" "$elf" "$src/$name.S" 2>/dev/null > "$build/.patched.out" || status=1
  # result lines: "<ok|FAIL> <name> expected <n> measured <n|none ...>"
  awk -v prog="$name" -v mcu="$mcu" '
    FNR == NR && $1 ~ /^(ok|FAIL)$/ { stock[$2] = $6; next }
    $1 ~ /^(ok|FAIL)$/ {
      s = ($2 in stock) ? stock[$2] : "did not finish"
      printf "| %s | %s | %s | %s | %s%s | %s |\n", prog, mcu, $2, $4, s, (s == $4 ? "" : " **x**"), $6
    }' "$build/.stock.out" "$build/.patched.out"
done
rm -f "$build/.stock.out" "$build/.patched.out"
exit $status
