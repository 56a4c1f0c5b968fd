#!/bin/bash
# Makes the fixtures of tests/sim/test_ready_numbers.cpp: for each case, a
# start written by figgen (start.vti, 64 x 32 cells, 128 in 1-D, 16^3 in 3-D;
# --format vti at step 0)
# and what GollyGang/Ready's own command-line tool computed from it in 100
# steps (ready100.vti), with the commands in commands.txt.
#
#   RDY=/path/to/rdy FIGGEN=build/figgen tests/sim/ready/make_fixtures.sh PATTERNS_DIR
#
# rdy is Ready's src/cmd built against its readybase library (libvtk9-dev,
# an OpenCL on the CPU: pocl-opencl-icd); docs/formulas.md says how.
# PATTERNS_DIR is Ready's Patterns/ folder.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
rdy=${RDY:?set RDY to Ready\'s rdy}
figgen=${FIGGEN:-build/figgen}
patterns=${1:?give Ready\'s Patterns folder}
small=(--set steps=0 --set "figure.panels=[0]" --format png,vti)
plane=(--set width=64 --set height=32)
log="$here/commands.txt"
: > "$log"
make_case() {  # NAME SOURCE [figgen options...]
  local name=$1 source=$2; shift 2
  local dir="$here/$name" tmp
  tmp=$(mktemp -d)
  mkdir -p "$dir"
  local cmd=("$figgen" render "$source" "${small[@]}" --set id=start "$@" --out "$tmp")
  echo "${cmd[*]}" | sed "s|$tmp|OUT|; s|$patterns|Patterns|" >> "$log"
  "${cmd[@]}" > /dev/null
  cp "$tmp/start.vti" "$dir/start.vti"
  echo "rdy -i $name/start.vti -n 100 -o $name/ready100.vti" >> "$log"
  "$rdy" -i "$dir/start.vti" -n 100 -o "$dir/ready100.vti" > /dev/null
  rm -rf "$tmp"
}
make_case brusselator figures/fx-brusselator.toml "${plane[@]}"
make_case fhn-labyrinth figures/fx-fhn-labyrinth.toml "${plane[@]}"
make_case cgl-spirals figures/fx-cgl-spirals.toml "${plane[@]}" --set "animation.steps=[0,0]"
make_case ks-high "$patterns/KuramotoSivashinsky1978/Kuramoto-Sivashinsky.vti" "${plane[@]}" --set accuracy=high
make_case sobel-waves "$patterns/Experiments/TihaVonGhyczy/sobel_waves.vti" "${plane[@]}"
make_case gs-map-low "$patterns/GrayScott1984/parameter-map.vti" "${plane[@]}" --set accuracy=low
make_case splats-double "$patterns/Experiments/CornusAmmonis/splats.vti" "${plane[@]}" --set data_type=double
make_case tunnelling-1d figures/fx-tunnelling.toml --set width=128 --set "animation.steps=[0,0]"
make_case glider-3d figures/fx-glider-3d.toml --set width=16 --set height=16 --set depth=16 --set "animation.steps=[0,0]"
rdy_version=$(cd "$(dirname "$rdy")" && git -C "${READY_SRC:-.}" describe --tags 2>/dev/null || true)
echo "# rdy: GollyGang/Ready ${rdy_version:-0.11.0-95-g46ca0b83}, OpenCL: $(clinfo -l 2>/dev/null | tr '\n' ' ' | tr -s ' ')" >> "$log"
