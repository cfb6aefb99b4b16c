#!/bin/sh
# Cost follows the output on exact ties (issue 27): the cover decides tie
# clusters exactly instead of writing every quadruple of their labels. Counts,
# not times: a 5x5x5 fcc crystal (500 balls, hull ties at infinity, degree-6
# octahedral vertices) proposed 1,387,126 quadruples for its 1,225 vertices
# before; 78 exactly cospherical balls (one vertex of degree 78) 1,425,737.
# Both must now propose a few quadruples per vertex (6,089 and 336 at
# 625c315) and give the same
# vertices on the reference backend and PoCL.
# usage: degenerate_cost.sh VORBALL WORK_DIR
vorball=$1 work=$2/degenerate_cost
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
fresh_dir "$work"
# fcc, a = 3.61, r = 1.28: every coordinate a multiple of 1.805, written exactly
awk 'BEGIN { split("0 0 0 1 1 0 1 0 1 0 1 1", b, " ")
    for (i = 0; i < 5; i++) for (j = 0; j < 5; j++) for (k = 0; k < 5; k++) for (s = 0; s < 4; s++)
        printf "%.3f %.3f %.3f 1.28\n", (2 * i + b[3 * s + 1]) * 1.805, (2 * j + b[3 * s + 2]) * 1.805,
               (2 * k + b[3 * s + 3]) * 1.805 }' > fcc.xyzr
# the first 78 integer points of x^2 + y^2 + z^2 = 81 in lexicographic order, radius 1
awk 'BEGIN { n = 0; for (x = -9; x <= 9; x++) for (y = -9; y <= 9; y++) for (z = -9; z <= 9; z++)
    if (x * x + y * y + z * z == 81 && n < 78) { print x, y, z, 1; n++ } }' > cosph.xyzr
[ "$(wc -l < fcc.xyzr)" -eq 500 ] && [ "$(wc -l < cosph.xyzr)" -eq 78 ] || fail "inputs not made"
# stat NAME FILE: the counter NAME of a --stats dump
for case in fcc cosph; do
    for dev in ref cpu; do
        run 0 "$case.$dev.err" "$vorball" vertices "$case.xyzr" --device $dev --stats -o "$case.$dev.tsv"
        expect_line "$case.$dev.tsv" '^# complete: '
    done
    grep -v '^#' "$case.ref.tsv" > a.txt
    grep -v '^#' "$case.cpu.tsv" > b.txt
    cmp a.txt b.txt || fail "$case: PoCL and the reference differ"
    nv=$(grep -vc '^#' "$case.ref.tsv")
    nq=$(stat cover_quadruples "$case.ref.err")
    echo "$case: $nv vertices, $nq quadruples"
    case $case in
    fcc)
        [ "$nv" -eq 1225 ] || fail "fcc: $nv vertices, expected 1225"
        [ "$(awk -F '\t' 'split($1, m, ",") == 6' a.txt | wc -l)" -gt 0 ] || fail "fcc: no degree-6 vertex"
        [ "$nq" -le $((10 * nv)) ] || fail "fcc: $nq quadruples for $nv vertices (at most 10 per vertex)" ;;
    cosph)
        [ "$nv" -eq 1 ] && awk -F '\t' '{ exit !(split($1, m, ",") == 78 && $2 == 0 && $3 == 0 && $4 == 0 && $5 == 8) }' a.txt ||
            fail "cosph: one vertex of degree 78 at the origin, t = 8, expected"
        [ "$nq" -le 500 ] || fail "cosph: $nq quadruples (at most 500)" ;;
    esac
done
echo "ok: degenerate cost"
