#!/bin/sh
# A guard on the cover's ring fetches where a cell sees a large hull (stop
# 42): 26974b6 ("one ring to infinity", reverted in ec6f44f) let a patch
# whose LO reached past the farthest centre fetch every sphere at once, and
# on the 211,440-atom capsid tiling a cell facing the capsid's cavity then
# fetched the whole input (ref CPU 70.6 -> 112.6 s); no test noticed,
# because no test had a large hull. This one has: a capsid-like shell of
# 3,000 balls (centres uniform between radii 17 and 23, one ball per ~10
# cubic angstroms as in a protein, radii 1.2-1.9) around an empty cavity
# 34 wide, made here by a Park-Miller generator (exact in doubles, so every
# awk writes the same file).
#
# The counter: --stats cover_max_cell_neighbours, the most neighbour records
# one cell built (its near list and every ring its patches fetched). The
# bound, 2 N = 6,000 records:
# - main (ec6f44f and after, doubling rings): a fetching patch's ring grows
#   at most twice per step and takes only the spheres that can reach the
#   LO of one of its parts (vbq_walk); the LO rises with what each ring
#   found, so a cavity-facing patch stops at the far wall. The inner wall
#   is nearly cospherical about the cavity's centre, so an inner cell's
#   LO is reached by much of it and the worst cell builds 4,380 records
#   (1.46 N; 3,000 records is the whole input once, and a cell's patches
#   fetch some spheres more than once);
# - the regression: each cavity-facing patch with a positive LO fetched at
#   once every sphere that reaches its parts' LO from there, which at the
#   cavity's tiny LO is every sphere in front of c_i: about N / 2 per
#   patch, and an inner cell has many such patches: 14,069 records (4.7 N)
#   with 26974b6 on this input (its total over all cells 436 k -> 698 k).
# 2 N lies between: 1.37 times main's worst cell, 2.3 times below the
# regression's. Counts, not times: the same on every machine and thread
# count; PoCL's work-item kernel runs the same walk (vb_cover_shared.h).
# usage: hull_fetch.sh VORBALL WORK_DIR
vorball=$1 work=$2/hull_fetch
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
fresh_dir "$work"
n=3000
awk -v n=$n 'function rnd() { s = (16807 * s) % 2147483647; return s / 2147483647 }
BEGIN { s = 12345; k = 0
    while (k < n) {
        x = (2 * rnd() - 1) * 23; y = (2 * rnd() - 1) * 23; z = (2 * rnd() - 1) * 23
        r = 1.2 + 0.7 * rnd(); d2 = x * x + y * y + z * z
        if (d2 > 23 * 23 || d2 < 17 * 17)
            continue
        printf "%.3f %.3f %.3f %.3f\n", x, y, z, r; k++ } }' > shell.xyzr
[ "$(wc -l < shell.xyzr)" -eq $n ] || fail "input not made"
[ "$(head -1 shell.xyzr)" = "-8.032 10.347 -17.196 1.572" ] || fail "the generator's first ball differs: $(head -1 shell.xyzr)"
# stat NAME FILE: the counter NAME of a --stats dump
bound=$((2 * n))
for dev in ref cpu; do
    run 0 "$dev.err" "$vorball" vertices shell.xyzr --device $dev --stats -o "$dev.tsv"
    expect_line "$dev.tsv" '^# complete: '
    max=$(stat cover_max_cell_neighbours "$dev.err") total=$(stat cover_neighbours "$dev.err")
    echo "$dev: $(grep -vc '^#' "$dev.tsv") vertices, neighbour records $total, most in one cell $max (bound $bound)"
    [ -n "$max" ] && [ "$max" -gt 0 ] || fail "$dev: no cover_max_cell_neighbours in --stats"
    [ "$max" -le "$bound" ] ||
        fail "$dev: a cell built $max neighbour records, above $bound: do hull cells fetch the whole input?"
done
grep -v '^#' ref.tsv > a.txt
grep -v '^#' cpu.tsv > b.txt
cmp a.txt b.txt || fail "PoCL and the reference differ"
echo "ok: hull fetch"
