#!/usr/bin/env bash
# Makes sure every Debian 12 package figgen builds with is installed.
# Installs the missing ones with apt-get (through sudo when not root);
# when that is impossible, names the first missing package and the command
# that installs it, and fails.
#   scripts/deps.sh         what the build, `make figures` and `make test` need
#   scripts/deps.sh bench   also the book's route that `make bench` times
#                           (Debian's python3 with numpy, scipy, matplotlib)
#   scripts/deps.sh fuzz    also clang with libFuzzer, for `make fuzz`
set -eu

packages=(
  g++ make cmake pkg-config
  python3-glad libglm-dev  # glad generates the GL loader
  # GL: the headers of OSMesa and EGL to build; at run time figgen opens one
  # (--gl): EGL (libglvnd's libEGL, Mesa's EGL and its llvmpipe driver) or OSMesa
  libosmesa6-dev libegl-dev libosmesa6 libegl1 libegl-mesa0 libgl1-mesa-dri
  libpng-dev zlib1g-dev
  libssl-dev  # SHA-256 of states (libcrypto)
  libavcodec-dev libavformat-dev libavutil-dev libswscale-dev
  libwebp-dev  # films' animated previews
  libcairo2-dev poppler-utils librsvg2-bin  # PDF and SVG through cairo; the tests rasterise them back
  libfreetype-dev fonts-dejavu-core
  # text: shaping (libraqm over HarfBuzz and FriBidi), line breaks (libunibreak),
  # fallback fonts through fontconfig, and the documents' own scripts (Noto Sans CJK)
  libraqm-dev libharfbuzz-dev libfribidi-dev libunibreak-dev libfontconfig-dev fonts-noto-cjk
  libcli11-dev libtomlplusplus-dev nlohmann-json3-dev
  libxbyak-dev  # formula chains as machine code (x86-64)
  libtinyxml2-dev libglib2.0-dev  # Ready's pattern files: XML, and base64 (GLib); zlib as above
  python3-vtk9 python3-numpy  # the tests read figgen's VTI files back with VTK (its numpy_support)
  libopenmpi-dev openmpi-bin  # MPI: its headers and mpirun; figgen opens libmpi only under mpirun
  catch2 libbenchmark-dev
  python3-dev python3-pybind11  # the Python module (python/), built with the project
  python3-pytest jupyter-nbconvert python3-ipykernel  # its tests, and the example notebook run headless
  chromium chromium-driver python3-selenium  # the gallery's browser test
)
if [ "${1:-}" = bench ]; then
  packages+=(python3 python3-numpy python3-scipy python3-matplotlib ffmpeg)  # ffmpeg: matplotlib's FFMpegWriter
fi
if [ "${1:-}" = fuzz ]; then
  packages+=(clang libclang-rt-14-dev libomp-14-dev)  # libFuzzer and clang's OpenMP
fi

missing=()
for p in "${packages[@]}"; do
  # dpkg-query prints "install ok installed" only for a fully installed package.
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [ "$status" = "install ok installed" ] || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

source "$(dirname "$0")/as-root.sh"
if ! as_root_prefix; then
  echo "figgen: missing Debian package ${missing[0]} (all missing: ${missing[*]}); install with: sudo apt-get install -y ${missing[*]}" >&2
  exit 1
fi

echo "figgen: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -q >/dev/null
"${sudo[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}" >/dev/null
