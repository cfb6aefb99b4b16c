#!/bin/bash
# PBA+ (Zheng & Tan's parallel banding algorithm plus: exact Euclidean distance
# transform / discrete Voronoi diagram of integer sites on the GPU) on the JFA
# cases of facet-jfa-and-channels, as the peer of `vorball jfa`.
#
# usage: pba_bench.sh PBABIN OUTDIR [VORBALL]
#   PBABIN   the 3D PBA+ driver (pba3d_bench: reads integer seeds 'x y z', times the
#            PBA+ kernels with CUDA events, checks every voxel exactly; built apart)
#   OUTDIR   gets seeds/*.txt (the seed layouts, shared by both tools), pba_*.json
#            (one JSON object per case), vorball_*.json when VORBALL is given, and
#            pba_bench.tsv (one row per case and tool)
#   VORBALL  optional: runs `vorball jfa` on the same seed files (variants VARIANTS)
# Cases (3D, uniform distinct integer sites): 256^3 x 13,573 (2OAU's atom count),
# 256^3 x 100,000, 512^3 x 1,000 (the paper's 3D point), 512^3 x 100,000.
# Environment (optional):
#   PBA2D=PATH    also the 2D driver (pba2d_bench) on the paper's 2D grid: N = 256..4096,
#                 K = 10, 100, 1000, 10000, 100000 (K <= N^2/4)
#   CASES3D="N:K ..."  replaces the 3D cases;  CASES2D="N:K ..." the 2D ones
#   REPEAT=R      timed runs after one warm-up (default 20)
#   CHECK=all|M|0 PBA+ check: all voxels (default), M random voxels, or none
#   VARIANTS=...  vorball jfa variants (default jfa,jfa+1,facet); VORBALL_CHECK=0 drops --check
#   RNG=S         seed of the layouts (default 1)
# Times (TSV): PBA+ 'time_ms' is its kernels alone (CUDA events between upload and
# download; the driver's compute_ms), 'whole_ms' adds the host-device copies; vorball's
# are `vorball jfa`'s time_ms (the algorithm on the device) and gpu_ms (its commands'
# summed execution); means (and min) over REPEAT runs after a warm-up. 'wrong': voxels
# whose site is not a nearest one (PBA+: exact squared distances; vorball: its --check).
# Needs bash, python3 (standard library) and the binaries; nothing is built here.
set -u
if [ $# -lt 2 ]; then
    sed -n '2,/^# Needs/p' "$0" | sed 's/^# \{0,1\}//'
    exit 2
fi
PBA=$1 OUT=$2 VORBALL=${3:-}
PBA2D=${PBA2D:-}
REPEAT=${REPEAT:-20}
CHECK=${CHECK:-all}
VARIANTS=${VARIANTS:-jfa,jfa+1,facet}
VORBALL_CHECK=${VORBALL_CHECK:-1}
RNG=${RNG:-1}
CASES3D=${CASES3D:-"256:13573 256:100000 512:1000 512:100000"}
if [ -z "${CASES2D:-}" ]; then
    CASES2D=""
    for n in 256 512 1024 2048 4096; do
        for k in 10 100 1000 10000 100000; do
            [ "$k" -le $((n * n / 4)) ] && CASES2D="$CASES2D $n:$k"
        done
    done
fi
mkdir -p "$OUT/seeds" || exit 3
tsv=$OUT/pba_bench.tsv
[ -s "$tsv" ] || printf 'tool\tdim\tn\tseeds\tvariant\ttime_ms_mean\ttime_ms_min\tgpu_ms\twhole_ms_mean\twhole_ms_min\twrong\tchecked\trc\tfile\n' > "$tsv"

seeds() { # dim n k -> path of a seed file of k distinct uniform integer sites in [0,n)^dim
    local f="$OUT/seeds/seeds_${1}d_${2}_${3}_rng${RNG}.txt"
    [ -s "$f" ] || python3 - "$1" "$2" "$3" "$RNG" "$f" <<'EOF'
import random, sys
dim, n, k, rng, path = int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), sys.argv[5]
if k > n ** dim:
    sys.exit("pba_bench: %d seeds do not fit %d^%d pixels" % (k, n, dim))
r = random.Random(rng * 1000003 + n * 31 + dim)
seen, rows = set(), []
while len(rows) < k:
    p = tuple(r.randrange(n) for _ in range(dim))
    if p not in seen:
        seen.add(p)
        rows.append(" ".join(map(str, p)) + "\n")
with open(path, "w") as f:
    f.writelines(rows)
EOF
    echo "$f"
}

row_pba() { # json file dim n k -> tsv row
    python3 - "$1" "$tsv" "$2" "$3" "$4" <<'EOF'
import json, sys
path, tsv, dim, n, k = sys.argv[1:6]
try:
    j = json.load(open(path))
except (OSError, ValueError):
    j = {}
rc = open(path + ".rc").read().strip()
cols = ["PBA+", j.get("dim", dim), j.get("n", n), j.get("sites", k), "pba+", j.get("compute_ms_mean", ""),
        j.get("compute_ms_min", ""), "", j.get("whole_ms_mean", ""), j.get("whole_ms_min", ""),
        j.get("wrong_voxels", ""), j.get("checked_voxels", ""), rc, path]
open(tsv, "a").write("\t".join(map(str, cols)) + "\n")
EOF
}

row_vorball() { # json file dim n k
    python3 - "$1" "$tsv" "$2" "$3" "$4" <<'EOF'
import json, sys
path, tsv, dim, n, k = sys.argv[1:6]
rc = open(path + ".rc").read().strip()
try:
    j = json.load(open(path))
except (OSError, ValueError):
    j = None
def walk(o):  # variant records, whatever the nesting of vorball's JSON
    if isinstance(o, dict):
        if "variant" in o:
            yield o
        for v in o.values():
            yield from walk(v)
    elif isinstance(o, list):
        for v in o:
            yield from walk(v)
recs = list(walk(j)) if j is not None else []
with open(tsv, "a") as f:
    if not recs:
        f.write("\t".join(["vorball", dim, n, k] + [""] * 8 + [rc, path]) + "\n")
    for r in recs:
        checked = int(n) ** int(dim) if "wrong" in r else ""
        f.write("\t".join(map(str, ["vorball", dim, n, k, r.get("variant"), r.get("time_ms", ""),
                r.get("time_ms_min", ""), r.get("gpu_ms", ""), "", "", r.get("wrong", ""), checked, rc,
                path])) + "\n")
EOF
}

run_case() { # dim n k bin
    local dim=$1 n=$2 k=$3 bin=$4 f j
    f=$(seeds "$dim" "$n" "$k") || exit 3
    j=$OUT/pba_${dim}d_${n}_${k}.json
    echo "pba_bench: PBA+ ${dim}D ${n} x ${k}" >&2
    "$bin" -n "$n" --repeat "$REPEAT" --check "$CHECK" "$f" > "$j" 2> "${j%.json}.err"
    echo $? > "$j.rc"
    row_pba "$j" "$dim" "$n" "$k"
    if [ -n "$VORBALL" ]; then
        j=$OUT/vorball_${dim}d_${n}_${k}.json
        echo "pba_bench: vorball jfa ${dim}D ${n} x ${k} ($VARIANTS)" >&2
        local chk=()
        [ "$VORBALL_CHECK" = 1 ] && chk=(--check)
        "$VORBALL" jfa -d "$dim" -n "$n" -V "$VARIANTS" --device auto --repeat "$REPEAT" \
            "${chk[@]}" --json -o "$j" "$f" 2> "${j%.json}.err"
        echo $? > "$j.rc"
        row_vorball "$j" "$dim" "$n" "$k"
    fi
}

for c in $CASES3D; do run_case 3 "${c%%:*}" "${c##*:}" "$PBA"; done
if [ -n "$PBA2D" ]; then
    for c in $CASES2D; do run_case 2 "${c%%:*}" "${c##*:}" "$PBA2D"; done
fi
column -t -s "$(printf '\t')" "$tsv" >&2 2>/dev/null || cat "$tsv" >&2
