#!/bin/bash
# The exact tiled engine (`vorball jfa -V exact`, issue 23) on the GPU: the
# issue's benchmark cases beside Facet-JFA and JFA+1, and the JFA stage of
# `vorball channels` per protein of corpus/data with --jfa facet and exact.
# About 2 minutes on one H200 (runs stop starting after 4 minutes).
#
# usage: device_exact.sh BUILD_DIR OUTDIR
#   BUILD_DIR  a vorball build tree (BUILD_DIR/cli/vorball)
#   OUTDIR     gets one JSON (vorball jfa) or stats CSV (vorball channels) per
#              run, its stderr (.err), and summary.tsv (one row per run)
# Cases (vorball jfa --device "$DEV", uniform real-valued seeds, rng 1):
#   check_*  -V exact --check --repeat $REP: time, the engine's work counts
#            (tiles, uniform tiles, candidates, survivors, float evaluations,
#            integer-decided voxels) and the comparison with the exact
#            reference (wrong and differ must be 0)
#   time_*   -V facet,jfa+1 --repeat $REP, no --check: the approximate peers
#   3D 256^3 x 13,573 and x 100,000; 512^3 x 1,000 and x 100,000; 512^3 with
#   the atom centres of 4yvs (26,430); 2D 4096^2 x 100,000.
# Channels: every protein of corpus/data at 256^3 (1chb also at 128^3 and
#   512^3), --jfa facet and --jfa exact, --repeat $CREP; ms_jfa is the stage time
#   (mean of the frame's repeats, from --stats).
# Times: vorball jfa's time_ms is the algorithm on the device (uploads,
# downloads and the host's seed grid excluded; prep_transfer_ms is those),
# gpu_ms its commands' summed execution. Needs bash and python3 (standard
# library); builds nothing, reaches no network.
set -u
if [ $# -lt 2 ]; then
    sed -n '2,/^# library/p' "$0" | sed 's/^# \{0,1\}//'
    exit 2
fi
B=$1 O=$2
V=$B/cli/vorball
HERE=$(cd "$(dirname "$0")" && pwd)
D=$HERE/../../corpus/data
[ -x "$V" ] || { echo "device_exact: no $V" >&2; exit 3; }
mkdir -p "$O" || exit 3
(nvidia-smi -L || true) > "$O/device.txt" 2>&1
# DEVICE=cpu|ref with QUICK=1: a smoke run of this script on small grids.
DEV=${DEVICE:-gpu}
N1=256 N2=512 N2D=4096 KB=100000 REP=20 CREP=5 C1=128 C2=256 C3=512
[ -n "${QUICK:-}" ] && N1=32 N2=64 N2D=256 KB=3000 REP=2 CREP=1 C1=32 C2=32 C3=64

run() { # name, limit in s, then the vorball arguments
    local name=$1 lim=$2
    shift 2
    if [ $SECONDS -gt 240 ]; then # the whole script's budget: skip the rest
        printf '%s\tskipped\t0\n' "$name" >> "$O/runs.tsv"
        return
    fi
    local start=$(date +%s%N)
    timeout "$lim" "$V" "$@" 2> "$O/$name.err"
    local rc=$? ms=$((($(date +%s%N) - start) / 1000000))
    printf '%s\t%s\t%s\n' "$name" "$rc" "$ms" >> "$O/runs.tsv"
    echo "== $name: rc $rc in $ms ms: $*" >&2
}

jfa() { # name, then vorball jfa arguments
    local name=$1
    shift
    run "check_$name" 60 jfa --device "$DEV" --json --check -V exact --repeat $REP "$@" \
        -o "$O/check_$name.json"
    run "time_$name" 30 jfa --device "$DEV" --json -V facet,jfa+1 --repeat $REP "$@" \
        -o "$O/time_$name.json"
}

: > "$O/runs.tsv"
jfa 3d_${N1}_13573 -d 3 -n $N1 -k 13573
jfa 3d_${N1}_$KB -d 3 -n $N1 -k $KB
jfa 3d_${N2}_1000 -d 3 -n $N2 -k 1000
jfa 3d_${N2}_$KB -d 3 -n $N2 -k $KB
jfa 3d_${N2}_4yvs -n $N2 --protein "$D/4yvs_ev71_capsid.cif"
jfa 2d_${N2D}_$KB -d 2 -n $N2D -k $KB

chan() { # name, input, grid, then more channels arguments
    local name=$1 in=$2 n=$3
    shift 3
    for v in facet exact; do
        run "chan_${name}_${n}_$v" 40 channels "$in" --device "$DEV" --grid "$n" --jfa "$v" \
            --repeat $CREP "$@" -o /dev/null --stats-file "$O/chan_${name}_${n}_$v.csv"
    done
}
chan 1chb "$D/1chb_hole2.pdb" $C1
chan 1chb "$D/1chb_hole2.pdb" $C3
for n in $C2; do
    chan 1chb "$D/1chb_hole2.pdb" $n
    chan 1grm "$D/1grm_single_hole2.pdb" $n --probe 1.0
    chan 1crn "$D/1crn.pdb" $n
    chan 3pqr "$D/3pqr.pqr" $n
    chan 4yvs "$D/4yvs_ev71_capsid.cif" $n
    chan md "$D/ngl_md_ascii_trj.pdb" $n
done

python3 - "$O" <<'EOF'
import csv, glob, json, os, sys
out = sys.argv[1]
rows = [["run", "variant", "n", "seeds", "ms", "ms_min", "gpu_ms", "prep_ms", "tiles",
         "tiles_uniform", "survivors", "evals", "exact_voxels", "wrong", "differ"]]
for path in sorted(glob.glob(os.path.join(out, "*_*.json"))):
    name = os.path.basename(path)[:-5]
    try:
        doc = json.load(open(path))
    except (OSError, ValueError):
        rows.append([name, "failed"] + [""] * 13)
        continue
    for r in doc.get("runs", []):
        rows.append([name, r["variant"], doc.get("n", ""), doc.get("seeds", ""),
                     r["time_ms"], r["time_ms_min"], r["gpu_ms"], r.get("prep_transfer_ms", ""),
                     r.get("tiles", ""), r.get("tiles_uniform", ""), r.get("survivors", ""),
                     r.get("evals", ""), r.get("exact_voxels", ""), r.get("wrong", ""),
                     r.get("differ", "")])
for path in sorted(glob.glob(os.path.join(out, "chan_*.csv"))):
    name = os.path.basename(path)[:-4]
    try:
        st = list(csv.DictReader(open(path)))
    except OSError:
        st = []
    ms = [float(r["ms_jfa"]) for r in st if r.get("ms_jfa")]
    parts = name.split("_")
    rows.append([name, parts[-1], parts[-2], "", "%.3f" % (sum(ms) / len(ms)) if ms else "failed",
                 "%.3f" % min(ms) if ms else ""] + [""] * 9)
with open(os.path.join(out, "summary.tsv"), "w") as f:
    for r in rows:
        f.write("\t".join(str(x) for x in r) + "\n")
EOF
cat "$O/summary.tsv"
