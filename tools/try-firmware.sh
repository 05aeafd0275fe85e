#!/usr/bin/env bash
# Prints the bundled strip (examples/strip) through a GT2560 simulated in gt2560-avr running
# FIRMWARE (an ATmega2560 .elf or .hex: the project's test firmware, or your own build of stock
# Marlin 1.1.9, docs/board-simulator.md), with the robot simulated in the service at time scale 1,
# then checks from the board's step pulses and cutter pin that every path got its planned feed
# and every cut was made (tools/board-check). About four minutes.
#
#   tools/try-firmware.sh [--invert-e-dir] FIRMWARE [BUILD_DIR]     BUILD_DIR: default build/release
#
#   --invert-e-dir   the firmware was built with INVERT_E0_DIR / INVERT_E1_DIR true (the E direction
#                    pin low for forward), as the Geeetech GT2560 example configuration of stock
#                    Marlin 1.1.9 is: gt2560-avr and board-check then count low as forward
#
# Everything lands in out/try-firmware/: the cell YAML, the service's and the board's logs, the
# pin edges (edges.log), the job's plan under state/jobs/1/plan. Exit status: board-check's.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
usage="usage: tools/try-firmware.sh [--invert-e-dir] FIRMWARE [BUILD_DIR]"
direction=()
while [ $# -gt 0 ]; do
    case "$1" in
        --invert-e-dir) direction=(--invert-e-dir); shift ;;
        -h|--help) echo "$usage"; exit 0 ;;
        -*) echo "try-firmware: unknown option $1" >&2; echo "$usage" >&2; exit 2 ;;
        *) break ;;
    esac
done
[ $# -ge 1 ] && [ $# -le 2 ] || { echo "$usage" >&2; exit 2; }
[ -f "$1" ] || { echo "try-firmware: no firmware file $1" >&2; exit 2; }
firmware=$(realpath "$1")
build=$(realpath "${2:-$root/build/release}")
for program in tools/gt2560-avr tools/board-check tools/fibrecell daemon/fibrecelld; do
    [ -x "$build/$program" ] || { echo "try-firmware: no $build/$program (build first)" >&2; exit 2; }
done

out="$root/out/try-firmware"
rm -rf "$out"
mkdir -p "$out"
cat >"$out/cell.yaml" <<YAML
# Written by tools/try-firmware.sh: the simulated robot in the service, the board outside it.
name: try-firmware
state_dir: $out/state
simulated: true
simulation: {time_scale: 1, board: external}
extruder: {link: {port: $out/ttyGT2560}}
api: {socket: $out/api.sock}
YAML

# The board, its control commands through a fifo (kept open here for the script's life).
mkfifo "$out/board.ctl"
exec 3<>"$out/board.ctl"
"$build/tools/gt2560-avr" "$firmware" --link "$out/ttyGT2560" --cell "$out/cell.yaml" \
    --edge-log "$out/edges.log" "${direction[@]}" <&3 >"$out/board.out" 2>"$out/board.err" &
board=$!
fibrecelld=""
# shellcheck disable=SC2317  # run by the trap
stop() {
    [ -n "$fibrecelld" ] && kill "$fibrecelld" 2>/dev/null && wait "$fibrecelld" 2>/dev/null
    echo quit >&3
    wait "$board" 2>/dev/null || true
}
trap stop EXIT
for _ in $(seq 200); do
    grep -q '^port ' "$out/board.out" 2>/dev/null && break
    kill -0 "$board" 2>/dev/null || { cat "$out/board.err" >&2; echo "try-firmware: gt2560-avr did not start" >&2; exit 1; }
    sleep 0.1
done
echo "try-firmware: $(basename "$firmware") runs on the simulated GT2560 at $out/ttyGT2560${direction:+ (E direction inverted)}"

"$build/daemon/fibrecelld" --config "$out/cell.yaml" >"$out/fibrecelld.log" 2>&1 &
fibrecelld=$!
for _ in $(seq 200); do
    [ -S "$out/api.sock" ] && break
    kill -0 "$fibrecelld" 2>/dev/null || { cat "$out/fibrecelld.log" >&2; echo "try-firmware: fibrecelld did not start" >&2; exit 1; }
    sleep 0.1
done
export FIBRECELL_SOCKET="$out/api.sock"
outcome=0
# A pause (the firmware halted, the link lost) ends it too: nobody is here to resume it.
"$build/tools/fibrecell" submit "$root/examples/strip/strip.job.yaml" --start --watch --until-paused ||
    outcome=$?

echo status >&3
for _ in $(seq 100); do grep -q '^status ' "$out/board.out" && break; sleep 0.1; done
echo "try-firmware: the board's own figures: $(grep '^status ' "$out/board.out" | tail -1 | cut -c8-)"
check=0
"$build/tools/board-check" "${direction[@]}" "$out/state/jobs/1/plan" "$out/edges.log" || check=$?
[ "$outcome" -eq 0 ] || echo "try-firmware: the print ended with status $outcome (see $out/fibrecelld.log)"
exit $(( check != 0 ? check : outcome ))
