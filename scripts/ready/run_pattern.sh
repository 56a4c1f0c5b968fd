#!/bin/bash
# Usage: run_pattern.sh PATTERN.vti OUTDIR
# Writes OUTDIR/start.vti  : the pattern's START state (initial pattern generator applied once, if
#                            apply_when_loading="true"), saved with apply_when_loading="false".
#                            Made with rdy_start because `rdy -n 0 -o X` saves nothing.
#        OUTDIR/ready100.vti: 100 steps of Ready (rdy, OpenCL platform 0 / device 0) from start.vti.
# Prints every command before running it. Exit status non-zero if a step fails or an output is missing.
set -uo pipefail
if [ $# -ne 2 ]; then echo "usage: $0 PATTERN.vti OUTDIR" >&2; exit 2; fi
BIN=${RDY_BUILD:?set RDY_BUILD to the folder of rdy and rdy_start (scripts/ready/CMakeLists.txt)}
PAT=$1; OUT=$2
mkdir -p "$OUT" || exit 1
rm -f "$OUT/start.vti" "$OUT/ready100.vti"
run() { printf '+'; printf ' %q' "$@"; printf '\n'; "$@"; }
run "$BIN/rdy_start" "$PAT" "$OUT/start.vti" || { echo "ERROR: rdy_start failed" >&2; exit 1; }
[ -s "$OUT/start.vti" ] || { echo "ERROR: start.vti not written" >&2; exit 1; }
# rdy exits 0 even when SaveFile throws, so check its output text and the file too
log=$(run "$BIN/rdy" -i "$OUT/start.vti" -n 100 -o "$OUT/ready100.vti" 2>&1); rc=$?
echo "$log"
[ $rc -eq 0 ] || { echo "ERROR: rdy exited $rc" >&2; exit 1; }
if grep -q "Something went wrong" <<<"$log"; then echo "ERROR: rdy could not save" >&2; exit 1; fi
[ -s "$OUT/ready100.vti" ] || { echo "ERROR: ready100.vti not written" >&2; exit 1; }
exit 0
