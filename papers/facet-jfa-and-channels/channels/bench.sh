#!/bin/sh
# Channel extraction (Sec. 4 of facet-jfa-and-channels.txt): frames per
# second and the validation runs (gramicidin A, cholera toxin, MD trajectory).
#
#   papers/facet-jfa-and-channels/channels/bench.sh VORBALL OUTDIR [DEVICE [quick]]
#
# DEVICE is passed to --device (default auto: the GPU when there is one);
# "quick" keeps the FPS runs at 128^3 with 5 repeats (PoCL) and skips the
# validation runs.
# Every run leaves its table (.csv/.json), per-frame statistics (_stats.csv)
# and the stderr summary line with ms/run and FPS (.err) in OUTDIR;
# tables.sh turns them into the tables of README.md.
set -u
V=$1
O=$2
DEV=${3:-auto}
QUICK=${4:-}
HERE=$(cd "$(dirname "$0")" && pwd)
D=$HERE/../../../corpus/data
GRM=$D/1grm_single_hole2.pdb
CHB=$D/1chb_hole2.pdb
MD=$D/ngl_md_ascii_trj.pdb
mkdir -p "$O"

run() { # name, then vorball channels arguments
    name=$1
    shift
    start=$(date +%s)
    timeout 150 "$V" channels --device "$DEV" "$@" 2> "$O/$name.err"
    echo "== $name: rc $? in $(($(date +%s) - start)) s: $*" >&2
}

# Frames per second: each run repeats one frame; upload, JFA, masks and
# compaction form the "GPU stages"; the host analysis (components,
# centrelines) is timed apart. 1grm with probe 1.0 (its pore is open), 1chb
# with the default 1.4.
grids="128 256"
[ -n "$QUICK" ] && grids=128
for n in $grids; do
    rep=100
    [ "$n" = 256 ] && rep=40
    [ -n "$QUICK" ] && rep=5
    for v in facet jfa+1; do
        run "fps_1grm_${n}_$v" "$GRM" --probe 1.0 --grid $n --jfa $v --repeat $rep \
            -o /dev/null --stats-file "$O/fps_1grm_${n}_${v}_stats.csv"
        run "fps_1chb_${n}_$v" "$CHB" --grid $n --jfa $v --repeat $rep \
            -o /dev/null --stats-file "$O/fps_1chb_${n}_${v}_stats.csv"
    done
done

[ -n "$QUICK" ] && exit 0

# Gramicidin A: the pore profile with our radii (Bondi) and HOLE's simple
# radii, and the probe at which the pore closes.
run grm_bondi_256 "$GRM" --probe 1.0 --grid 256 --json -o "$O/grm_bondi_256.json" \
    --centerlines "$O/grm_centrelines.pdb" --pymol "$O/grm.pml" --volume "$O/grm_channels.mrc" \
    --png "$O/grm_stages.png"
run grm_hole_256 "$GRM" --radii "$HERE/hole_simple.radii" --probe 1.0 --grid 256 --json \
    -o "$O/grm_hole_256.json"
for p in 1.1 1.2 1.25 1.3; do
    run "grm_probe_$p" "$GRM" --probe $p --grid 256 -o "$O/grm_probe_$p.csv"
done
# Cholera toxin B pentamer: its central pore.
run chb_256 "$CHB" --grid 256 --json -o "$O/chb_256.json" --centerlines "$O/chb_centrelines.pdb" \
    --pymol "$O/chb.pml" --png "$O/chb_stages.png"
run chb_hole_256 "$CHB" --radii "$HERE/hole_simple.radii" --grid 256 --json -o "$O/chb_hole_256.json"
# The 51-frame MD trajectory, frame by frame.
run md_128 "$MD" --grid 128 -o "$O/md_128.csv" --stats-file "$O/md_128_stats.csv" \
    --centerlines "$O/md_centrelines.pdb"
