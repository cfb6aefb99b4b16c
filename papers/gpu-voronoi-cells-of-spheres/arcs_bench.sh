#!/bin/sh
# The cost of the second proof (issue #30, "--arcs near free"): the whole
# process of `vorball vertices --device DEVICE --quiet` without and with
# --arcs on the EV71 capsid (26,430 atoms) and its 2x2x2 tiling (211,440),
# best of REPEAT wall seconds each, for one or two builds (NEW and, to set
# beside it in the same session, BASE; "-" for none). The --arcs run's
# --stats timers (arc_*) are kept, and the --arcs --topology outputs of each
# build on DEVICE and on --device ref are compared byte for byte (provenance
# lines aside).
# usage: arcs_bench.sh NEW BASE OUTDIR REPEAT DEVICE
# OUTDIR/arcs.tsv: input, atoms, build, plain_s, arcs_s, overhead, same_as_ref;
# OUTDIR/stats_BUILD_INPUT.txt: the best --arcs run's arc_* lines.
# INPUTS="capsid capsid222" (the default) picks inputs: OUTDIR/in/NAME.xyzr.
set -u
[ $# -eq 5 ] || { sed -n '2,/^set -u/p' "$0" | sed '$d;s/^# \{0,1\}//'; exit 2; }
new=$1 base=$2 out=$3 repeat=$4 dev=$5
here=$(cd "$(dirname "$0")" && pwd)
data=$(cd "$here/../../corpus/data" && pwd)
mkdir -p "$out/in" || exit 1
[ -s "$out/in/capsid.xyzr" ] ||
    python3 "$here/cif_to_xyzr.py" "$data/4yvs_ev71_capsid.cif" "$out/in/capsid.xyzr" || exit 1
[ -s "$out/in/capsid222.xyzr" ] ||
    python3 "$here/tile_input.py" "$out/in/capsid.xyzr" 2 2 2 "$out/in/capsid222.xyzr" || exit 1
# best wall seconds of $repeat runs of "$@" (one untimed run first: the
# device's program cache); the best run's stderr in $out/best.err
best() {
    "$@" 2>/dev/null >/dev/null
    b=""
    i=0
    while [ $i -lt "$repeat" ]; do
        t0=$(date +%s.%N)
        "$@" 2>"$out/run.err" >/dev/null || { echo "failed: $*" >&2; cat "$out/run.err" >&2; }
        t=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.3f", b - a }')
        if [ -z "$b" ] || awk -v t="$t" -v b="$b" 'BEGIN { exit !(t < b) }'; then
            b=$t
            cp "$out/run.err" "$out/best.err"
        fi
        i=$((i + 1))
    done
    echo "$b"
}
printf 'input\tatoms\tbuild\tplain_s\tarcs_s\toverhead\tsame_as_ref\n' > "$out/arcs.tsv"
for f in ${INPUTS:-capsid capsid222}; do
    in=$out/in/$f.xyzr
    atoms=$(grep -vc '^#' "$in")
    for build in new base; do
        eval bin=\$$build
        [ "$bin" = - ] && continue
        p=$(best "$bin" vertices "$in" --quiet --device "$dev" -o "$out/plain.tsv")
        a=$(best "$bin" vertices "$in" --quiet --device "$dev" --arcs --stats -o "$out/arcs.tsv.out")
        grep '^arc_' "$out/best.err" > "$out/stats_${build}_$f.txt"
        ov=$(awk -v a="$a" -v p="$p" 'BEGIN { printf "%.1f", 100 * (a - p) / p }')
        same=yes
        for d in "$dev" ref; do
            "$bin" vertices "$in" --quiet --device "$d" --arcs --topology "$out/topo.$d" \
                -o "$out/v.$d" 2>/dev/null || same=failed
            grep -v '^# \(tool\|options\):' "$out/v.$d" > "$out/v.$d.body"
        done
        cmp -s "$out/v.$dev.body" "$out/v.ref.body" && cmp -s "$out/topo.$dev" "$out/topo.ref" ||
            same=no
        printf '%s\t%s\t%s\t%s\t%s\t%s%%\t%s\n' "$f" "$atoms" "$build" "$p" "$a" "$ov" "$same" \
            >> "$out/arcs.tsv"
    done
done
cat "$out/arcs.tsv"
