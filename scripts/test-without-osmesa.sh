#!/usr/bin/env bash
# `make test-without-osmesa`: figgen where OSMesa is gone (Mesa removed it
# upstream in 25.1). REMOVES Debian's libosmesa6 from this machine, so it is
# meant for a throwaway one (../shared/tools/fresh-debian-check
# test-without-osmesa); `make` installs it again (scripts/deps.sh).
# Then: --gl osmesa is refused in one line naming the package, every
# catalog figure renders (auto: EGL), and the golden tests run under EGL.
#   scripts/test-without-osmesa.sh BUILD_DIR JOBS
set -eu
build=${1:-build}
jobs=${2:-2}
source "$(dirname "$0")/as-root.sh"
if ! as_root_prefix; then
  echo "test-without-osmesa: needs root (or sudo) to remove libosmesa6" >&2
  exit 1
fi
echo "test-without-osmesa: removing Debian's libosmesa6 (and libosmesa6-dev) from this machine" >&2
DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get remove -y -q libosmesa6 >/dev/null
if /sbin/ldconfig -p | grep -q 'libOSMesa\.so\.8 '; then
  echo "test-without-osmesa: libOSMesa.so.8 is still installed" >&2
  exit 1
fi

out="$build/without-osmesa"
rm -rf "$out"
status=0
said=$("$build/figgen" render tc7-7 --format png --gl osmesa --out "$out" 2>&1) || status=$?
if [ "$status" -ne 1 ] || [ "$(printf '%s\n' "$said" | wc -l)" -ne 1 ] ||
   ! printf '%s' "$said" | grep -q "install Debian's libosmesa6"; then
  echo "test-without-osmesa: --gl osmesa should fail in one line naming libosmesa6; it said (status $status):" >&2
  printf '%s\n' "$said" >&2
  exit 1
fi
echo "test-without-osmesa: --gl osmesa refused: $said" >&2

start=$(date +%s)
"$build/figgen" render figures/*.toml --out "$out"
if grep -L '"platform": "egl"' "$out"/*.json | grep -q .; then
  echo "test-without-osmesa: figures not drawn through EGL: $(grep -L '"platform": "egl"' "$out"/*.json)" >&2
  exit 1
fi
echo "test-without-osmesa: $(ls "$out"/*.png | wc -l) figures rendered through EGL in $(( $(date +%s) - start )) s" >&2

ctest --test-dir "$build" --output-on-failure -j "$jobs" -R '\(egl\)$'
