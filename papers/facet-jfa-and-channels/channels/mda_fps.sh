#!/bin/bash
# Frames per second of `vorball channels` over a large MD trajectory, end to end
# with the reading included, with the frames in flight (VORBALL_FRAMES_AHEAD=2, a
# reader thread; VORBALL_FRAMES_IN_FLIGHT frames analysed at once) and without
# (0:1, the sequential loop), beside HOLE 2 on the same frames in the same
# session (issue 33, benchmark item 4).
#
# usage: mda_fps.sh HOLEBIN VORBALL TOPOLOGY TRAJ GRID DEVICE OUTDIR
#   HOLEBIN   the hole binary (built apart; radius file HOLE_RAD as in
#             frames_vs_hole.sh: $(dirname HOLEBIN)/../rad/simple.rad by default)
#   VORBALL   the vorball binary
#   TOPOLOGY  the trajectory's topology (GRO, PDB; .gz too), TRAJ its XTC/TRR/DCD,
#             e.g. MDAnalysis' test files adk_oplsaa.gro + adk_oplsaa.xtc (47,681
#             atoms, 10 frames) or YiiP_lipids.gro.gz + YiiP_lipids.xtc (43,480
#             atoms); GPL-2+, keep them out of the repository
#   GRID      vorball's --grid;  DEVICE its --device (ref, cpu, gpu, auto)
#   OUTDIR    gets fps.tsv (one row per run: tool, variant, frames, wall, user,
#             system seconds, frames/s on the wall clock, CPU s per frame),
#             stages.tsv (vorball's mean ms per frame of each --json clock, per
#             variant), the tables, and HOLE's per-frame inputs and outputs
# The atoms: vorball drops water and the membrane (its defaults) and is told
# --ignore for the ions (IGNORE, default NA+,CL-,NA,CL,K,SOD,CLA,POT); HOLE gets one
# PDB per frame holding the same atoms, written beforehand (untimed) by
# MDAnalysis (PYTHON: a python with MDAnalysis; PYTHONDONTWRITEBYTECODE is set).
# Both tools get HOLE's simple.rad radii (vorball through hole_compare.py radii).
# HOLE reads one structure per process, so it runs once per frame, as a HOLE user
# runs a trajectory: "coord, radius, ignore, raseed 1" (frames_vs_hole.sh's plain).
# Times by GNU /usr/bin/time -v over each whole run. REPEATS (default 1) repeats.
# VARIANTS (default "0:1 2:1 2:2 2:4 2:8"): vorball's runs, each AHEAD:IN_FLIGHT
# (VORBALL_FRAMES_AHEAD, VORBALL_FRAMES_IN_FLIGHT). NOHOLE=1 skips HOLE and its
# frames (no MDAnalysis needed then). A long trajectory: repeat the XTC's frames
# (an XTC is its frames one after another), e.g. 11 copies of adk_oplsaa.xtc
# make 110 frames: for k in $(seq 11); do cat adk_oplsaa.xtc; done > adk110.xtc
# YiiP's zinc sites are dummy atoms (residue ZNM) without a HOLE radius: pass
# IGNORE=NA+,CL-,ZNM for it.
set -u
if [ $# -lt 7 ]; then
    sed -n '2,/^set -u/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'
    exit 2
fi
HOLE=$1 VORBALL=$2 TOP=$3 TRAJ=$4 GRID=$5 DEVICE=$6 OUT=$7
PYTHON=${PYTHON:-python3} REPEATS=${REPEATS:-1} VARIANTS=${VARIANTS:-0:1 2:1 2:2 2:4 2:8}
NOHOLE=${NOHOLE:-0}
IGNORE=${IGNORE:-NA+,CL-,NA,CL,K,SOD,CLA,POT}
export PYTHONDONTWRITEBYTECODE=1
here=$(cd "$(dirname "$0")" && pwd)
. "$here/hole_setup.sh"
if [ "$NOHOLE" = 1 ] && [ -z "${HOLE_RAD:-}" ] && [ ! -r "$(dirname "$HOLE")/../rad/simple.rad" ] &&
    [ ! -r "$(dirname "$HOLE")/../share/hole2/rad/simple.rad" ]; then
    # No HOLE here (a GPU host): the repository's copy of its simple.rad radii.
    mkdir -p "$OUT" && OUT=$(cd "$OUT" && pwd) && cp "$here/hole_simple.radii" "$OUT/vorball.radii" || exit 3
else
    hole_setup mda_fps
    mkdir -p "$OUT/frames" && cp "$OUT/hole.rad" "$OUT/frames/hole.rad" || exit 3
fi

# The membrane names vorball leaves out by default, for HOLE's frames.
if [ "$NOHOLE" = 1 ]; then
    frames=  # from the first run's JSON
else
membrane=$("$VORBALL" channels --help | tr -d ' \n' | grep -o '(defaultDUM,POPC[A-Z0-9,]*' |
    sed 's/^(default//' | head -1)
[ -n "$membrane" ] || { echo "mda_fps: no membrane list in vorball's --help" >&2; exit 6; }
frames=$("$PYTHON" - "$TOP" "$TRAJ" "$OUT/frames" "$IGNORE,$membrane" <<'EOF' || exit 6
import sys, warnings
warnings.filterwarnings("ignore")
import MDAnalysis as mda
top, traj, dst, drop = sys.argv[1:5]
water = "SOL HOH WAT TIP3 TIP4 TIP5 SPC T3P T4P H2O DOD"
names = " ".join(n for n in drop.replace(",", " ").split() if n) + " " + water
u = mda.Universe(top, traj)
sel = u.select_atoms("not resname " + names)
for k, ts in enumerate(u.trajectory):
    sel.write("%s/f%04d.pdb" % (dst, k))
print(len(u.trajectory))
EOF
)
[ "$NOHOLE" = 1 ] || [ "${frames:-0}" -gt 0 ] || { echo "mda_fps: no frames read" >&2; exit 6; }
for f in "$OUT"/frames/f*.pdb; do
    b=$(basename "$f" .pdb)
    printf '%s\n' "coord $b.pdb" "radius hole.rad" "ignore hoh tip wat" "raseed 1" > "$OUT/frames/$b.inp"
done
fi

tsv=$OUT/fps.tsv
printf 'tool\tvariant\trepeat\tframes\twall_s\tuser_s\tsys_s\tframes_per_s\tcpu_s_per_frame\n' > "$tsv"
row() { # tool variant repeat timefile
    read -r w u s < <(time_secs "$4")
    awk -v w="$w" -v u="$u" -v s="$s" -v n="$frames" -v head="$1\t$2\t$3\t$frames" 'BEGIN {
        printf "%s\t%.3f\t%.3f\t%.3f\t%.2f\t%.4f\n", head, w, u, s, n / w, (u + s) / n }' >> "$tsv"
}

for rep in $(seq 1 "$REPEATS"); do
    for v in $VARIANTS; do
        ahead=${v%%:*} w=${v##*:} name=vorball_a${v%%:*}w${v##*:}
        echo "mda_fps: vorball channels --device $DEVICE --grid $GRID, ahead $ahead, in flight $w, repeat $rep" >&2
        VORBALL_FRAMES_AHEAD=$ahead VORBALL_FRAMES_IN_FLIGHT=$w /usr/bin/time -v -o "$OUT/$name.$rep.time" \
            "$VORBALL" --quiet channels --device "$DEVICE" --grid "$GRID" --radii "$OUT/vorball.radii" \
            --ignore "$IGNORE" --json -o "$OUT/$name.json" "$TOP" --traj "$TRAJ" \
            2> "$OUT/$name.$rep.err" || echo "mda_fps: vorball failed (see $OUT)" >&2
        [ -n "$frames" ] || frames=$(python3 -c 'import json, sys; print(len(json.load(open(sys.argv[1]))["frames"]))' \
            "$OUT/$name.json") || exit 6
        row vorball "$DEVICE grid $GRID ahead $ahead in_flight $w" "$rep" "$OUT/$name.$rep.time"
        cmp -s "$OUT/vorball_a0w1.json" "$OUT/$name.json" 2> /dev/null ||
            [ "$(grep -v '"ms"\|"clock"\|"device"' "$OUT/vorball_a0w1.json" 2> /dev/null | md5sum)" = \
              "$(grep -v '"ms"\|"clock"\|"device"' "$OUT/$name.json" | md5sum)" ] ||
            echo "mda_fps: $name.json differs from vorball_a0w1.json (less clocks)" >&2
    done
    [ "$NOHOLE" = 1 ] && continue
    echo "mda_fps: HOLE, one process per frame ($frames frames), repeat $rep" >&2
    /usr/bin/time -v -o "$OUT/hole.$rep.time" sh -c '
        cd "$1" || exit 3
        for inp in f*.inp; do
            "$2" < "$inp" > "${inp%.inp}.out" 2> "${inp%.inp}.err" || exit 4
            rm -f sr_gseed_tempfile
        done' sh "$OUT/frames" "$HOLE" || echo "mda_fps: HOLE failed ($OUT/frames)" >&2
    row hole plain "$rep" "$OUT/hole.$rep.time"
done

# vorball's stages: the mean per frame of every clock, per variant (last repeat).
# The run's clock (JSON "clock" after the frames): fps of the whole run.
python3 - "$OUT" $VARIANTS > "$OUT/stages.tsv" <<'EOF'
import json, os, sys
out = sys.argv[1]
head = None
for v in sys.argv[2:]:
    ahead, w = v.split(":")
    doc = json.load(open(os.path.join(out, "vorball_a%sw%s.json" % (ahead, w))))
    fr, run = doc["frames"], doc.get("clock", {})
    keys = [("ms", k) for k in fr[0]["ms"]] + [("clock", k) for k in fr[0]["clock"]]
    if head is None:
        head = keys
        print("\t".join(["ahead", "in_flight", "frames", "atoms", "run_fps", "run_cpu_ms_per_frame"] +
                        ["%s_%s" % k for k in keys]))
    print("\t".join([ahead, w, str(len(fr)), str(fr[0].get("atoms", "")),
                     "%.2f" % run.get("fps", 0), "%.1f" % run.get("cpu_per_frame", 0)] +
                    ["%.3f" % (sum(f[a][k] for f in fr) / len(fr)) for a, k in keys]))
EOF
column -t -s "$(printf '\t')" "$tsv" >&2 2>/dev/null || cat "$tsv" >&2
column -t -s "$(printf '\t')" "$OUT/stages.tsv" >&2 2>/dev/null || cat "$OUT/stages.tsv" >&2
