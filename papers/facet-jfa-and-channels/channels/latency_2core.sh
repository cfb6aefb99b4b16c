#!/bin/bash
# Per-stage host CPU of `vorball channels` per frame (issue 33) for two
# binaries, alternating, in one session: perf's cpu-clock samples with DWARF
# call graphs on one thread (latency_stages.py), and the wall medians of the
# --json "ms" clocks on THREADS threads.
#
# usage: latency_2core.sh OUTDIR LABEL=VORBALL [LABEL=VORBALL ...]
#   DEV      --device (default ref)    THREADS  threads of the wall run (default 2)
#   MDA      adk_oplsaa.gro/.xtc and YiiP_lipids.gro.gz (default /work/peers/mda)
#   DATA     the corpus data (default this repository's corpus/data)
#   CASES    which of adk128 adk256 1chb128 1chb256 yiip128 yiip256 ngl128 (default
#            all but ngl128: ngl_md_ascii_trj.pdb, 51 frames of 183 atoms)
# OUTDIR gets NAME.LABEL.stages (latency_stages.py's lines), NAME.LABEL.wall
# (median ms per JSON key), NAME.LABEL.time (/usr/bin/time -v of the perf run).
# Needs bash, perf, python3 (standard library), GNU time.
set -u
if [ $# -lt 2 ]; then
    sed -n '2,/^# Needs/p' "$0" | sed 's/^# \{0,1\}//'
    exit 2
fi
O=$1; shift
here=$(cd "$(dirname "$0")" && pwd)
D=${DATA:-$(cd "$here/../../../corpus/data" && pwd)} M=${MDA:-/work/peers/mda}
mkdir -p "$O" || exit 3
case_args() { # name -> ARGS, RUNS, FRAMES
    case $1 in
    adk*) ARGS=("$M/adk_oplsaa.gro" --traj "$M/adk_oplsaa.xtc"); RUNS=10 FRAMES=10 ;;
    1chb*) ARGS=("$D/1chb_hole2.pdb" --repeat 10); RUNS=10 FRAMES=1 ;;
    yiip*) ARGS=("$M/YiiP_lipids.gro.gz" --repeat 3); RUNS=3 FRAMES=1 ;;
    ngl*) ARGS=("$D/ngl_md_ascii_trj.pdb"); RUNS=51 FRAMES=51 ;;
    esac
    GRID=${1##*[a-z]}
}
for c in ${CASES:-adk128 adk256 1chb128 1chb256 yiip128 yiip256}; do
    case_args "$c"
    for lv in "$@"; do
        L=${lv%%=*} V=${lv#*=}
        echo "latency_2core: $c $L" >&2
        VORBALL_THREADS=1 /usr/bin/time -v -o "$O/$c.$L.time" perf record -q -F 4000 \
            --call-graph dwarf,32768 -o "$O/p.data" "$V" --quiet channels --device "${DEV:-ref}" \
            --grid "$GRID" --json -o "$O/p.json" "${ARGS[@]}" 2> /dev/null
        perf script -i "$O/p.data" 2> /dev/null > "$O/p.txt"
        python3 "$here/latency_stages.py" "$O/p.txt" 0.25 "$RUNS" "$FRAMES" > "$O/$c.$L.stages"
        rm -f "$O/p.data" "$O/p.txt"
        VORBALL_THREADS=${THREADS:-2} "$V" --quiet channels --device "${DEV:-ref}" --grid "$GRID" \
            --json -o "$O/w.json" "${ARGS[@]}" 2> /dev/null
        python3 - "$O/w.json" > "$O/$c.$L.wall" <<'PY'
import json, statistics as S, sys
d = json.load(open(sys.argv[1])); fr = d["frames"]
for k in fr[0]["ms"]:
    print("%s\t%.2f" % (k, S.median(f["ms"][k] for f in fr)))
PY
    done
done
