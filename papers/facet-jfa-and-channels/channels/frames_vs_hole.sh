#!/bin/bash
# Seconds per frame of `vorball channels` against HOLE 2 on the same frames, in
# the same session (issue 33: "per frame no slower than HOLE 2 on the same
# frame"), and vorball's per-stage milliseconds from its --json clocks.
#
# usage: frames_vs_hole.sh HOLEBIN VORBALL DEVICE GRID REPEATS OUTDIR
#   HOLEBIN  the hole binary (built apart); its radius file is HOLE_RAD, by default
#            $(dirname HOLEBIN)/../rad/simple.rad (the source tree's layout), else
#            HOLE's install layout $(dirname HOLEBIN)/../share/hole2/rad/simple.rad
#   VORBALL  the vorball binary;  DEVICE its --device (ref, cpu, gpu, auto)
#   GRID     its --grid;  REPEATS how many times each timed run is repeated
#   OUTDIR   gets frames_vs_hole.tsv (one row per run: input, frames, tool, variant,
#            repeat, wall, user and system seconds, seconds per frame on the wall
#            clock and in CPU time), stages_2core.tsv (vorball's mean per frame of
#            each "ms" key (wall ms) and of the "clock" object (write, frame and cpu
#            in ms, fps), per input, from the last repeat), the vorball tables and
#            HOLE's inputs and outputs
# Inputs (DATA, default the repository's corpus/data): 1chb_hole2.pdb (the cholera
# toxin B pentamer, HOLE's example 2, one frame) and ngl_md_ascii_trj.pdb (51 frames
# of a 183-atom peptide; every MODEL a frame). Both tools get the same radii (HOLE's
# simple.rad; vorball through hole_compare.py radii) and leave water out (HOLE's
# 'ignore hoh tip wat'; vorball drops water by default). HOLE reads one structure
# per run, so each frame is its own PDB file and its own HOLE process, as a HOLE
# user runs a trajectory. HOLE runs twice per frame: "plain" (coord, radius,
# ignore, raseed 1, the pore profile printed) and "conn+sph" (its CONN option and
# the SPHPDB sphere-centre output as well, example 2's own input). Times by
# /usr/bin/time -v over the whole run (every HOLE process of a repeat together).
# Needs bash, python3 (standard library), GNU time and the binaries.
set -u
if [ $# -lt 6 ]; then
    sed -n '2,/^# Needs/p' "$0" | sed 's/^# \{0,1\}//'
    exit 2
fi
HOLE=$1 VORBALL=$2 DEVICE=$3 GRID=$4 REPEATS=$5 OUT=$6
here=$(cd "$(dirname "$0")" && pwd)
DATA=${DATA:-$here/../../../corpus/data}
. "$here/hole_setup.sh"
hole_setup frames_vs_hole

tsv=$OUT/frames_vs_hole.tsv
printf 'input\tframes\ttool\tvariant\trepeat\twall_s\tuser_s\tsys_s\ts_per_frame\tcpu_s_per_frame\n' > "$tsv"

row() { # input frames tool variant repeat timefile
    read -r w u s < <(time_secs "$6")
    awk -v w="$w" -v u="$u" -v s="$s" -v n="$2" -v head="$1\t$2\t$3\t$4\t$5" 'BEGIN {
        printf "%s\t%.3f\t%.3f\t%.3f\t%.4f\t%.4f\n", head, w, u, s, w / n, (u + s) / n }' >> "$tsv"
}

for input in 1chb_hole2.pdb ngl_md_ascii_trj.pdb; do
    name=${input%%_*}
    dir=$OUT/$name
    mkdir -p "$dir/frames" || exit 3
    cp "$DATA/$input" "$dir/$input" || exit 3
    # One PDB per MODEL (the whole file when it has none).
    frames=$(python3 - "$dir/$input" "$dir/frames" <<'EOF'
import os, sys
src, dst = sys.argv[1], sys.argv[2]
frames, cur, head = [], None, []
for line in open(src):
    rec = line[:6]
    if rec.startswith("MODEL"):
        cur = []
    elif rec.startswith("ENDMDL"):
        frames.append(cur)
        cur = None
    elif rec.startswith(("ATOM", "HETATM")):
        (cur if cur is not None else head).append(line)
if not frames:
    frames = [head]
for k, f in enumerate(frames):
    with open(os.path.join(dst, "f%04d.pdb" % k), "w") as o:
        o.writelines(f)
        o.write("END\n")
print(len(frames))
EOF
)
    [ "${frames:-0}" -gt 0 ] || { echo "frames_vs_hole: no frames in $input" >&2; exit 6; }
    cp "$OUT/hole.rad" "$dir/frames/hole.rad"
    for f in "$dir"/frames/f*.pdb; do
        b=$(basename "$f" .pdb)
        printf '%s\n' "coord $b.pdb" "radius hole.rad" "ignore hoh tip wat" "raseed 1" > "$dir/frames/$b.plain.inp"
        printf '%s\n' "coord $b.pdb" "radius hole.rad" "ignore hoh tip wat" "conn" \
            "sphpdb $b.sph" "raseed 1" > "$dir/frames/$b.conn.inp"
    done
    for rep in $(seq 1 "$REPEATS"); do
        for variant in plain conn; do
            echo "frames_vs_hole: $name: HOLE $variant, repeat $rep ($frames frames)" >&2
            /usr/bin/time -v -o "$dir/hole_$variant.$rep.time" sh -c '
                cd "$1" || exit 3
                for inp in f*.'"$variant"'.inp; do
                    "$2" < "$inp" > "${inp%.inp}.out" 2> "${inp%.inp}.err" || exit 4
                    rm -f sr_gseed_tempfile
                done' sh "$dir/frames" "$HOLE" || echo "frames_vs_hole: HOLE failed ($dir)" >&2
            row "$name" "$frames" hole "$([ $variant = conn ] && echo conn+sph || echo plain)" "$rep" \
                "$dir/hole_$variant.$rep.time"
        done
        echo "frames_vs_hole: $name: vorball channels --device $DEVICE --grid $GRID, repeat $rep" >&2
        /usr/bin/time -v -o "$dir/vorball.$rep.time" "$VORBALL" --quiet channels --device "$DEVICE" \
            --grid "$GRID" --radii "$OUT/vorball.radii" --json -o "$dir/vorball.json" \
            "$dir/$input" 2> "$dir/vorball.$rep.err" || echo "frames_vs_hole: vorball failed ($dir)" >&2
        row "$name" "$frames" vorball "$DEVICE grid $GRID" "$rep" "$dir/vorball.$rep.time"
    done
done

# vorball's stages: the mean per frame of every clock of the last repeat.
python3 - "$OUT" "$GRID" "$DEVICE" > "$OUT/stages_2core.tsv" <<'EOF'
import json, os, sys
out, grid, device = sys.argv[1:4]
keys = None
rows = []
for name in ("1chb", "ngl"):
    d = json.load(open(os.path.join(out, name, "vorball.json")))
    fr = d["frames"]
    ms = [k for k in fr[0]["ms"]] + ["clock_" + k for k in fr[0]["clock"]]
    keys = keys or ms
    mean = lambda k: sum((f["clock"][k[6:]] if k.startswith("clock_") else f["ms"][k]) for f in fr) / len(fr)
    rows.append([name, str(len(fr)), device, grid] + ["%.3f" % mean(k) for k in keys])
names = [("clock_%s%s" % (k[6:], "" if k == "clock_fps" else "_ms")) if k.startswith("clock_") else "ms_" + k
         for k in keys]
print("\t".join(["input", "frames", "device", "grid"] + names))
for r in rows:
    print("\t".join(r))
EOF
column -t -s "$(printf '\t')" "$tsv" >&2 2>/dev/null || cat "$tsv" >&2
column -t -s "$(printf '\t')" "$OUT/stages_2core.tsv" >&2 2>/dev/null || cat "$OUT/stages_2core.tsv" >&2
