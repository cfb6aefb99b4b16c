#!/bin/sh
# `vorball vertices --proposer sampling --topology` (the seed paper's Sec. 4
# evidence; the exact topology is checked in tests/pipeline/topology.sh) on the 3x3x3 cubic lattice (spacing 1, equal
# radii). Its Voronoi cells are unit cubes; the finite vertices are the 8
# centres of the lattice's unit cubes, (0.5|1.5)^3, each shared by 8 spheres.
# Counted by hand: the finite edges join cube centres one step apart, 3 axes
# x 4 = 12 edges; 8 vertices x 3 outward directions = 24 edges to infinity;
# 3 axes x 2 x 9 = 54 face-sharing pairs. Four spheres meet along every edge
# and each of the four triples of them whose two faces meet there is one
# edge line, so there are 4 x 12 = 48 finite and 4 x 24 = 96 infinite edge
# lines. Every cell edge runs along a seam of the sampling cube, so this
# checks the seam cells. Reference and PoCL backends write the same
# topology bytes on every corpus input.
# usage: topology_cli.sh VORBALL CORPUS_INPUTS_DIR WORK_DIR
vorball=$1 inputs=$2 work=$3/topology_cli lattice=$2/cubic_lattice.xyzr
fail() { echo "FAIL: $*" >&2; exit 1; }
mkdir -p "$work" || fail "cannot create $work"
"$vorball" vertices --device ref --proposer sampling --topology "$work/ref.top" -o "$work/ref.tsv" "$lattice" \
    2> "$work/ref.err" || fail "ref run failed: $(cat "$work/ref.err")"
[ "$(grep -vc '^#' "$work/ref.tsv")" -eq 8 ] || fail "expected 8 vertices"
[ "$(grep -c '^face' "$work/ref.top")" -eq 54 ] || fail "expected 54 faces"
fin=$(awk '$1 == "edge" && $3 != -1' "$work/ref.top" | wc -l)
inf=$(awk '$1 == "edge" && $3 == -1' "$work/ref.top" | wc -l)
[ "$fin" -eq 48 ] || fail "expected 48 finite edge lines, got $fin"
[ "$inf" -eq 96 ] || fail "expected 96 infinite edge lines, got $inf"
# Vertex rows as 0/1 bits of their (x, y, z) = 0.5 + bit; a finite edge
# joins two rows whose bits differ in exactly one axis.
awk '!/^#/ { print n++, ($2 > 1) * 4 + ($3 > 1) * 2 + ($4 > 1) }' "$work/ref.tsv" \
    > "$work/bits" || fail "vertex bits"
pairs=$(awk 'NR == FNR { b[$1] = $2; next }
    $1 == "edge" && $3 != -1 { x = b[$2] - b[$3]; if (x < 0) x = -x
        if (x != 1 && x != 2 && x != 4) { print "bad " $0; exit } print $2, $3 }' \
    "$work/bits" "$work/ref.top" | sort -u)
echo "$pairs" | grep -q bad && fail "edge between non-adjacent centres: $pairs"
[ "$(echo "$pairs" | wc -l)" -eq 12 ] || fail "expected 12 distinct finite edges: $pairs"
# Explicit edges (sphere id = 9x + 3y + z): centre (0.5,0.5,0.5) to
# (1.5,0.5,0.5) along x is surrounded by spheres 9,10,12,13 (x = 1).
v0=$(awk '!/^#/ { n++ } $1 == "0,1,3,4,9,10,12,13" { print n - 1 }' "$work/ref.tsv")
v4=$(awk '!/^#/ { n++ } $1 == "9,10,12,13,18,19,21,22" { print n - 1 }' "$work/ref.tsv")
v7=$(awk '!/^#/ { n++ } $1 == "13,14,16,17,22,23,25,26" { print n - 1 }' "$work/ref.tsv")
v6=$(awk '!/^#/ { n++ } $1 == "12,13,15,16,21,22,24,25" { print n - 1 }' "$work/ref.tsv")
for t in 9,10,12 9,10,13 9,12,13 10,12,13; do
    grep -q "^edge	$v0	$v4	$t\$" "$work/ref.top" || fail "missing edge $v0-$v4 ($t)"
done
grep -q "^edge	$v6	$v7	13,16,22\$" "$work/ref.top" || fail "missing edge $v6-$v7"
grep -q "^edge	$v0	-1	0,1,3\$" "$work/ref.top" || fail "missing infinite edge of $v0"
"$vorball" vertices --device cpu --proposer sampling --topology "$work/cpu.top" -o "$work/cpu.tsv" "$lattice" \
    2> "$work/cpu.err" || fail "cpu run failed: $(cat "$work/cpu.err")"
cmp -s "$work/ref.tsv" "$work/cpu.tsv" || fail "vertex output differs ref/cpu"
cmp -s "$work/ref.top" "$work/cpu.top" || fail "topology differs ref/cpu"
grep -q W760 "$work/cpu.err" && echo "note: no OpenCL device, cpu ran the reference backend"
for f in "$inputs"/*.xyzr; do
    "$vorball" vertices --device ref --proposer sampling --topology "$work/a.top" "$f" > /dev/null 2>&1 ||
        fail "ref run failed on $f"
    "$vorball" vertices --device cpu --proposer sampling --topology "$work/b.top" "$f" > /dev/null 2>&1 ||
        fail "cpu run failed on $f"
    cmp -s "$work/a.top" "$work/b.top" || fail "topology differs ref/cpu on $f"
done
# Edge lines checked line for line by an exact rational computation on
# the equal-radius corpus inputs (papers/gpu-voronoi-cells-of-spheres):
# their counts, and two known lines of lattice_subset: the degree-6 vertex
# (-0.5, 1.5, 0.5) has an edge to infinity along 9,16,27, and the triple
# 2,7,25 meets at vertex 9 only in a point (no edge).
for c in bcc_lattice:240 hexagonal_ring:32 lattice_subset:185; do
    f=${c%%:*} want=${c#*:}
    "$vorball" vertices --device ref --proposer sampling --topology "$work/$f.top" -o "$work/$f.tsv" \
        "$inputs/$f.xyzr" 2> /dev/null || fail "run failed on $f"
    got=$(grep -c '^edge' "$work/$f.top")
    [ "$got" -eq "$want" ] || fail "$f: $got edge lines, expected $want"
done
v41=$(awk '!/^#/ { n++ } $1 == "9,16,21,23,26,27" { print n - 1 }' "$work/lattice_subset.tsv")
grep -q "^edge	$v41	-1	9,16,27\$" "$work/lattice_subset.top" ||
    fail "lattice_subset: missing infinite edge of the degree-6 vertex"
grep -q "	2,7,25\$" "$work/lattice_subset.top" && fail "lattice_subset: false edge 2,7,25"
# General position: every vertex has four edges (crambin fragment; and the
# collinear centres, whose collinear triples have a circle as trisector).
for f in crambin_fragment collinear_centres; do
    "$vorball" vertices --device ref --proposer sampling --topology "$work/$f.top" -o "$work/$f.tsv" \
        "$inputs/$f.xyzr" 2> "$work/$f.err" || fail "$f run failed"
    grep -q W765 "$work/$f.err" && fail "$f: unpaired trisectors"
    odd=$(awk '$1 == "edge" { d[$2]++; if ($3 != -1) d[$3]++ } END { n = 0; for (v in d) if (d[v] != 4) n++; print n + 0 }' "$work/$f.top")
    [ "$odd" -eq 0 ] || fail "$f: $odd vertices without exactly four edges"
    [ "$(awk '$1 == "edge" { d[$2] = 1; if ($3 != -1) d[$3] = 1 } END { n = 0; for (v in d) n++; print n }' "$work/$f.top")" -eq "$(grep -vc '^#' "$work/$f.tsv")" ] ||
        fail "$f: a vertex without edges"
done
echo "ok: 8 vertices, 54 faces, 12 finite edges ($fin lines), $inf infinite lines"
