# Sourced by frames_vs_hole.sh and mda_fps.sh (bash). hole_setup NAME checks
# and fixes what both need before timing HOLE 2 beside vorball. Reads HOLE
# (the hole binary), OUT (the output folder) and here (the script's folder);
# HOLE_RAD, when unset, is $(dirname HOLE)/../rad/simple.rad (the source
# tree's layout), else HOLE's install layout ../share/hole2/rad/simple.rad.
# Makes OUT and turns OUT and HOLE into absolute paths, copies the radius
# file to OUT/hole.rad and writes the same radii for vorball to
# OUT/vorball.radii (hole_compare.py radii). Exits 3 (no radius file, no GNU
# time, no OUT) or 6 (the radii) with NAME in the message.
hole_setup() {
    if [ -z "${HOLE_RAD:-}" ]; then
        HOLE_RAD=$(dirname "$HOLE")/../rad/simple.rad
        [ -r "$HOLE_RAD" ] || HOLE_RAD=$(dirname "$HOLE")/../share/hole2/rad/simple.rad
    fi
    [ -r "$HOLE_RAD" ] || { echo "$1: no radius file $HOLE_RAD (set HOLE_RAD)" >&2; exit 3; }
    [ -x /usr/bin/time ] || { echo "$1: needs GNU time at /usr/bin/time" >&2; exit 3; }
    mkdir -p "$OUT" || exit 3
    OUT=$(cd "$OUT" && pwd)
    HOLE=$(cd "$(dirname "$HOLE")" && pwd)/$(basename "$HOLE")
    cp "$HOLE_RAD" "$OUT/hole.rad" || exit 3
    python3 "$here/../hole_compare.py" radii "$OUT/hole.rad" "$OUT/vorball.radii" || exit 6
}

# time_secs FILE: "wall user system" seconds of a GNU `/usr/bin/time -v` report.
time_secs() {
    python3 - "$1" <<'PY'
import sys
t = {}
for line in open(sys.argv[1]):
    k, _, v = line.strip().rpartition(": ")
    t[k] = v
wall = t["Elapsed (wall clock) time (h:mm:ss or m:ss)"].split(":")
w = sum(float(x) * 60 ** i for i, x in enumerate(reversed(wall)))
print(w, float(t["User time (seconds)"]), float(t["System time (seconds)"]))
PY
}
