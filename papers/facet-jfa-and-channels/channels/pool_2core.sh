#!/bin/bash
# Stop 44 (resident thread pool): `vorball channels` per frame for two
# binaries, alternating ROUNDS times at each VORBALL_THREADS of THREADS, on
# 1chb_hole2.pdb (--repeat 10) and adk_oplsaa (10 XTC frames) at grid 128:
# one line per run with the median per-frame "ms" of the pore stages,
# analysis and total, and the CPU seconds of the whole run (GNU time).
# usage: pool_2core.sh OUT.tsv LABEL=VORBALL LABEL=VORBALL
#   ROUNDS (default 3)  THREADS (default "1 2 16")  MDA (default /work/peers/mda)
set -u
[ $# -ge 3 ] || { sed -n '2,/^# usage/p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
out=$1; shift
here=$(cd "$(dirname "$0")" && pwd)
D=$(cd "$here/../../../corpus/data" && pwd) M=${MDA:-/work/peers/mda}
tmp=$(mktemp -d) || exit 3
printf 'case\tthreads\tlabel\tround\tanalysis\trefine\tsweep\tverdict\tpore\ttotal\tcpu_s\n' > "$out"
for r in $(seq "${ROUNDS:-3}"); do
  for t in ${THREADS:-1 2 16}; do
    for c in 1chb adk; do
      [ $c = 1chb ] && A=("$D/1chb_hole2.pdb" --repeat 10) || A=("$M/adk_oplsaa.gro" --traj "$M/adk_oplsaa.xtc")
      for lv in "$@"; do
        L=${lv%%=*} V=${lv#*=}
        VORBALL_THREADS=$t /usr/bin/time -f '%U %S' -o "$tmp/t" "$V" --quiet channels --device ref \
          --grid 128 --json -o "$tmp/j.json" "${A[@]}" 2> /dev/null
        python3 - "$tmp/j.json" "$tmp/t" "$c" "$t" "$L" "$r" >> "$out" <<'PY'
import json, statistics as S, sys
fr = json.load(open(sys.argv[1]))["frames"]
u, s = map(float, open(sys.argv[2]).read().split()[-2:])
med = lambda k: "%.2f" % S.median(f["ms"][k] for f in fr)
print("\t".join(sys.argv[3:7] + [med(k) for k in ("analysis", "refine", "sweep", "verdict", "pore", "total")] + ["%.2f" % (u + s)]))
PY
      done
    done
  done
done
rm -rf "$tmp"
