#!/bin/bash
# Issue 33: the analysis's sweeps per component on host threads
# (VORBALL_DEVICE_PATHS=0, the default) against batches on the device
# (=1: the kernels on a GPU, the twin on ref or a CPU device; =2 forces the
# kernels on a CPU device), on a trajectory: per-frame milliseconds of the
# analysis and of its batch sweeps (JSON ms.analysis, ms.graph), end to end
# (clock.frame) and the process CPU (clock.cpu), medians over the frames, and
# whether every table and JSON (less its clocks and device line) is the same
# bytes as --device ref's.
# usage: paths_device.sh VORBALL TOPOLOGY TRAJ OUTDIR [DEVICE [REPEAT]]
#   e.g. paths_device.sh build/cli/vorball adk_oplsaa.gro adk_oplsaa.xtc out gpu 3
set -u
[ $# -ge 4 ] || { sed -n '2,12p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
V=$1 TOP=$2 TRAJ=$3 OUT=$4 DEV=${5:-gpu} REP=${6:-3}
mkdir -p "$OUT" || exit 3
strip() { sed -E 's/"ms": \{[^}]*\}//; s/"clock": \{[^}]*\}//' "$1" | grep -v '"device":\|"tool":'; }
"$V" channels "$TOP" --traj "$TRAJ" --device ref --json -o "$OUT/ref.json" 2> "$OUT/ref.err" || exit 4
printf 'device\tpaths\trun\tframes\tanalysis_ms\tgraph_ms\tframe_ms\tcpu_ms\tsame_as_ref\n'
for p in 0 1; do
    for r in $(seq 1 "$REP"); do
        j="$OUT/${DEV}_p${p}_r$r.json"
        VORBALL_DEVICE_PATHS=$p "$V" channels "$TOP" --traj "$TRAJ" --device "$DEV" --json -o "$j" \
            2> "${j%.json}.err" || { echo "run failed: $j" >&2; continue; }
        same=no
        cmp -s <(strip "$OUT/ref.json") <(strip "$j") && same=yes
        python3 - "$j" "$DEV" "$p" "$r" "$same" <<'PY'
import json, statistics as st, sys
j, dev, p, r, same = sys.argv[1:]
fr = json.load(open(j))["frames"]
med = lambda k, sub: st.median(f[sub].get(k, 0.0) for f in fr)
print("%s\t%s\t%s\t%d\t%.2f\t%.2f\t%.2f\t%.2f\t%s" % (dev, p, r, len(fr), med("analysis", "ms"),
      med("graph", "ms"), med("frame", "clock"), med("cpu", "clock"), same))
PY
    done
done
