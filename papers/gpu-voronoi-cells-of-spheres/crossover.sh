#!/bin/sh
# Where the device pays off (issue #30, fixed cost): the whole process of
# `vorball vertices` by input size on each device kind, so that `--device auto`
# can be set from a measured crossover. Inputs: the first N spheres of the
# EV71 capsid (contiguous chains of a protein, so protein-like neighbourhoods)
# for N = 327 .. 26,430, the capsid itself and its 2x2x2 tiling.
# usage: crossover.sh VORBALL OUTDIR REPEAT DEVICE...   (DEVICE: gpu, cpu, ref)
# OUTDIR/crossover.tsv: atoms, device, best and median wall seconds of REPEAT
# warm runs (one untimed run first fills the program cache), user+sys CPU
# seconds of the best run, peak RSS (KiB), vertex lines; the vertex files of
# the devices are compared byte for byte (provenance lines aside) and the
# verdict is written as the last column. INPUTS="first327 ..." picks inputs.
set -u
[ $# -ge 4 ] || { sed -n '2,/^set -u/p' "$0" | sed '$d;s/^# \{0,1\}//'; exit 2; }
vorball=$1 out=$2 repeat=$3
shift 3
here=$(cd "$(dirname "$0")" && pwd)
data=$(cd "$here/../../corpus/data" && pwd)
mkdir -p "$out/in" || exit 1
python3 "$here/cif_to_xyzr.py" "$data/4yvs_ev71_capsid.cif" "$out/in/capsid.xyzr" || exit 1
python3 "$here/tile_input.py" "$out/in/capsid.xyzr" 2 2 2 "$out/in/capsid222.xyzr" || exit 1
for n in 327 1000 3000 10000; do
    grep -v '^#' "$out/in/capsid.xyzr" | head -n "$n" > "$out/in/first$n.xyzr"
done
printf 'atoms\tdevice\tbest_s\tmedian_s\tcpu_s\tmax_rss_kib\tlines\tsame_as_first\n' > "$out/crossover.tsv"
for f in ${INPUTS:-first327 first1000 first3000 first10000 capsid capsid222}; do
    in=$out/in/$f.xyzr
    atoms=$(grep -vc '^#' "$in")
    first=""
    for dev in "$@"; do
        "$vorball" vertices --quiet --device "$dev" "$in" -o "$out/$f.$dev.tsv" 2> "$out/$f.$dev.err"
        r=1
        while [ "$r" -le "$repeat" ]; do
            python3 "$here/measure.py" "$out/$f.$dev.$r.json" --stderr "$out/$f.$dev.err" -- \
                "$vorball" vertices --quiet --device "$dev" "$in" -o "$out/$f.$dev.tsv"
            r=$((r + 1))
        done
        grep -v '^# \(options\|input\)' "$out/$f.$dev.tsv" > "$out/$f.$dev.cmp"
        same=-
        if [ -z "$first" ]; then first=$out/$f.$dev.cmp; else
            cmp -s "$first" "$out/$f.$dev.cmp" && same=yes || same=NO; fi
        python3 - "$atoms" "$dev" "$same" "$out/$f.$dev.tsv" "$out/$f.$dev".*.json <<'EOF' >> "$out/crossover.tsv"
import json, statistics, sys
atoms, dev, same, tsv, runs = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], sys.argv[5:]
rs = [json.load(open(p)) for p in runs]
best = min(rs, key=lambda r: r["wall_s"])
lines = sum(1 for l in open(tsv) if not l.startswith("#"))
print("\t".join([atoms, dev, "%.3f" % best["wall_s"],
                 "%.3f" % statistics.median(r["wall_s"] for r in rs),
                 "%.3f" % (best["user_s"] + best["sys_s"]), str(best["max_rss_kib"]),
                 str(lines), same]))
EOF
        rm -f "$out/$f.$dev".*.json "$out/$f.$dev.tsv"
    done
    rm -f "$out/$f".*.cmp
done
cat "$out/crossover.tsv"
