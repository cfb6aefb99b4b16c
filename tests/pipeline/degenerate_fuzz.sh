#!/bin/sh
# Degenerate fuzz (issue 27): N small seeded sets of 4-12 balls (nested,
# internally tangent, tangent pairs, coincident centres, exact and jittered
# grids, cospherical groups; degenerate_fuzz_gen.py) through the CLI. For each
# set, `vorball vertices` (cover, --device ref) must list exactly the vertex
# lines of `vorball reference` (ids, x, y, z, t, status: the same bytes once
# sorted), and `vorball verify IN OUT --complete` must accept its output; every
# 50th set also runs on --device cpu (PoCL) and must give the ref bytes.
# Prints each failing seed with its input and the difference; exits 1 if any.
#
# usage: degenerate_fuzz.sh VORBALL WORK_DIR
# env:   VORBALL_FUZZ_N (sets, default 1000), VORBALL_FUZZ_SEED (first seed,
#        default 1), VORBALL_FUZZ_CPU_EVERY (default 50; 0: no PoCL runs)
vorball=$1 work=$2
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
case $vorball in /*) ;; *) vorball=$(pwd)/$vorball ;; esac
n=${VORBALL_FUZZ_N:-1000} seed=${VORBALL_FUZZ_SEED:-1} cpu_every=${VORBALL_FUZZ_CPU_EVERY:-50}
command -v python3 > /dev/null || fail "python3 is needed to generate the sets"
fresh_dir "$work"
python3 "$here/degenerate_fuzz_gen.py" "$seed" "$n" in || fail "generator failed"

failed=0 shown=0 failures=
k=0
while [ $k -lt "$n" ]; do
    s=$((seed + k)) k=$((k + 1))
    in=in/$s.xyzr why=
    "$vorball" vertices "$in" --device ref --threads 1 -o v.tsv 2> v.err
    rc=$?
    "$vorball" reference "$in" -o r.tsv 2> r.err
    rrc=$?
    if [ $rc -ne 0 ] || [ $rrc -ne 0 ]; then
        why="vertices exited $rc, reference exited $rrc"
    else
        grep -v '^#' v.tsv | sort > v.lines
        grep -v '^#' r.tsv | sort > r.lines
        if ! cmp -s v.lines r.lines; then
            why="vertices and reference differ"
        elif [ -s v.lines ]; then
            "$vorball" verify "$in" v.tsv --complete > c.txt 2>&1 || why="verify --complete: $(grep -v '^verify:' c.txt | head -3)"
        fi
        if [ -z "$why" ] && [ "$cpu_every" -gt 0 ] && [ $((k % cpu_every)) -eq 0 ]; then
            "$vorball" vertices "$in" --device cpu -o p.tsv 2> p.err || why="vertices --device cpu failed"
            [ -n "$why" ] || cmp -s v.tsv p.tsv || why="--device cpu and --device ref differ"
        fi
    fi
    if [ -n "$why" ]; then
        failed=$((failed + 1)) failures="$failures $s"
        if [ $shown -lt 10 ]; then
            shown=$((shown + 1))
            echo "FAIL seed $s: $why" >&2
            sed 's/^/    in: /' "$in" >&2
            [ -f v.lines ] && [ -f r.lines ] && diff v.lines r.lines | sed -n 's/^</    vertices only:/p; s/^>/    reference only:/p' >&2
        else
            echo "FAIL seed $s: $why" >&2
        fi
    fi
    rm -f v.lines r.lines
done
if [ $failed -ne 0 ]; then
    kinds=$(for s in $failures; do sed -n '1s/.*: \([a-z]*\),.*/\1/p' in/$s.xyzr; done | sort | uniq -c | tr -s ' \n' ' ')
    [ $failed -le 40 ] || failures="$(echo $failures | cut -d' ' -f1-40) ..."
    fail "$failed of $n sets failed (by kind:$kinds); seeds: $failures"
fi
echo "degenerate fuzz: $n sets from seed $seed, vertices = reference on every one"
