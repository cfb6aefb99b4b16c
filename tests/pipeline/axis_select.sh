#!/bin/sh
# Issue 32: the pore axis at the defaults and --select, as users run them.
# - --select on vertices, cells and channels: the same atoms as a file cut
#   by hand; a malformed expression or an empty selection is E118 (exit 28)
#   naming the position; no output file is left.
# - the axis: cholera toxin B (1chb) by its C5 symmetry, the maltoporin
#   trimer (1af6) at plain defaults, its sugars and ions left out as ligands
#   (W811 names them; the same table as HOLE's example's --ignore FRU,GLC,MG;
#   --keep-ligands keeps them in the pores: the closed C3 axis) by one
#   subunit's barrel, one maltoporin chain (--select) by its barrel; W810
#   names the source, axis_why in the JSON says it in words; gramicidin's
#   HETATM ethanolamine caps stay (no W811); crambin keeps no pore (W808).
# usage: axis_select.sh VORBALL CORPUS_DIR WORK_DIR
vorball=$1 corpus=$2 work=$3/axis_select
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
fresh_dir "$work"
d=$corpus/data
out=$work/out.txt

# --select against a file cut by hand (chain A, residues 1-10 of 1chb's chain D).
awk 'substr($0,1,6)=="ATOM  " && substr($0,22,1)=="D" && substr($0,23,4)+0 >= 1 && substr($0,23,4)+0 <= 10' \
    "$d/1chb_hole2.pdb" > cut.pdb
[ "$(wc -l < cut.pdb)" -gt 50 ] || fail "the hand cut of 1chb is too small"
run 0 "$out" "$vorball" vertices "$d/1chb_hole2.pdb" --select "chain D and resid 1:10" -o sel.tsv
run 0 "$out" "$vorball" vertices cut.pdb -o cut.tsv
vertex_lines sel.tsv > a.txt
vertex_lines cut.tsv > b.txt
[ -s a.txt ] && cmp -s a.txt b.txt || fail "--select gave other vertices than the file cut by hand"
expect_line sel.tsv "^# options: .*--select"
run 0 "$out" "$vorball" cells cut.pdb -o cells_cut.tsv
run 0 "$out" "$vorball" cells "$d/1chb_hole2.pdb" --select "chain D and resid 1:10" -o cells_sel.tsv
vertex_lines cells_sel.tsv > a.txt
vertex_lines cells_cut.tsv > b.txt
[ -s a.txt ] && cmp -s a.txt b.txt || fail "cells: --select differs from the hand cut"

# E118: exit 28, the position named, no output left behind.
run 28 "$out" "$vorball" vertices "$d/1chb_hole2.pdb" --select "chain D and" -o bad.tsv
expect_line "$out" "E118.*at character 12"
[ ! -e bad.tsv ] || fail "E118 left an output file"
run 28 "$out" "$vorball" vertices "$d/1chb_hole2.pdb" --select "chain Q" -o bad.tsv
expect_line "$out" "E118.*selects none"
run 28 "$out" "$vorball" channels "$d/1grm_single_hole2.pdb" --device ref --select "resid 3:(" -o bad.csv
expect_line "$out" "E118"
[ ! -e bad.csv ] || fail "channels: E118 left an output file"

# The axis at the defaults.
pore() { # JSON -> "axis_from bottleneck"
    python3 -c "import json,sys; f=json.load(open(sys.argv[1]))['frames'][0]; p=f.get('pore')
print(p['axis_from'] if p else 'none', f['channels'][0]['bottleneck_A'] if p else '', p['axis_why'] if p else '')" "$1"
}
run 0 "$out" "$vorball" channels "$d/1chb_hole2.pdb" --device ref --json -o 1chb.json
expect_line "$out" "W810: .*pore axis \(symmetry\): C5 symmetry of chains"
set -- $(pore 1chb.json)
[ "$1" = symmetry ] || fail "1chb: axis from '$1', not its C5 symmetry"
awk -v r="$2" 'BEGIN { exit !(r > 3.0 && r < 3.4) }' || fail "1chb: pore $2 A (3.187 A expected)"
# Subunits resolved over different stretches (as in tetrameric channels
# whose loops are missing in some chains): 1chb with other residues cut
# from three of its five chains is still C5 by the residues all five hold
# (before: no group of equal sequences, the centroids' plane instead).
awk 'substr($0,1,6)=="ATOM  " { c = substr($0,22,1); r = substr($0,23,4) + 0
     if ((c == "D" && r >= 1 && r <= 4) || (c == "E" && r >= 40 && r <= 45) ||
         (c == "G" && r >= 100)) next } { print }' "$d/1chb_hole2.pdb" > 1chb_gaps.pdb
run 0 "$out" "$vorball" channels 1chb_gaps.pdb --device ref --json -o 1chb_gaps.json
expect_line "$out" "W810: .*pore axis \(symmetry\): C5 symmetry of chains"
set -- $(pore 1chb_gaps.json)
[ "$1" = symmetry ] || fail "1chb with gaps: axis from '$1', not its C5 symmetry"
awk -v r="$2" 'BEGIN { exit !(r > 3.0 && r < 3.4) }' || fail "1chb with gaps: pore $2 A"
run 0 "$out" "$vorball" channels "$d/1af6_hole2.pdb.gz" --device ref --json -o 1af6.json
expect_line "$out" "W810: .*pore axis \(subunit\): beta-barrel of chain"
expect_line "$out" "W811: .*73 ligand atoms left out .*: GLC 33, FRU 36, MG 4$"
set -- $(pore 1af6.json)
[ "$1" = subunit ] || fail "1af6: axis from '$1', not a subunit"
awk -v r="$2" 'BEGIN { exit !(r > 1.9 && r < 2.5) }' || fail "1af6: pore $2 A (2.2 A expected)"
run 0 "$out" "$vorball" channels "$d/1af6_hole2.pdb.gz" --device ref --ignore FRU,GLC,MG -o ign.csv
run 0 "$out" "$vorball" channels "$d/1af6_hole2.pdb.gz" --device ref -o lig.csv
cmp -s ign.csv lig.csv || fail "1af6: the ligands left out by default differ from --ignore FRU,GLC,MG"
run 0 "$out" "$vorball" channels "$d/1af6_hole2.pdb.gz" --device ref --keep-ligands --json -o keep.json
grep -q "W811" "$out" && fail "--keep-ligands still left ligands out"
set -- $(pore keep.json)
[ "$1" = symmetry ] || fail "1af6 --keep-ligands: axis from '$1', not the C3 axis"
awk -v r="$2" 'BEGIN { exit !(r < 0.5) }' || fail "1af6 --keep-ligands: pore $2 A (the sugars close it)"
run 0 "$out" "$vorball" channels "$d/1grm_single_hole2.pdb" --device ref -o grm.csv
grep -q "W811" "$out" && fail "1grm: its ethanolamine caps were taken for ligands"
run 0 "$out" "$vorball" channels "$d/1af6_hole2.pdb.gz" --device ref --ignore FRU,GLC,MG \
    --select "chain B" --json -o 1af6_B.json
set -- $(pore 1af6_B.json)
[ "$1" = barrel ] || fail "1af6 chain B: axis from '$1', not its barrel"
run 0 "$out" "$vorball" channels "$d/1crn.pdb" --device ref -o 1crn.csv
expect_line "$out" "W808"

# --axis-refit: two models of 1chb, the second turned 16 degrees about x and
# moved 1.5 A along x. Refitted, the second frame's axis is the first's
# turned the same way; with --axis fixed (the default) it stays the first's.
python3 - "$d/1chb_hole2.pdb" chb2.pdb << 'EOF2' || fail "cannot write the turned 1chb"
import math, sys
atoms = [l for l in open(sys.argv[1]) if l.startswith(("ATOM", "HETATM"))]
with open(sys.argv[2], "w") as f:
    for m, deg in enumerate((0, 16)):
        c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
        f.write("MODEL     %4d\n" % (m + 1))
        for l in atoms:
            x, y, z = float(l[30:38]), float(l[38:46]), float(l[46:54])
            f.write(l[:30] + "%8.3f%8.3f%8.3f" % (x + 1.5 * m, c * y - s * z, s * y + c * z) + l[54:])
        f.write("ENDMDL\n")
    f.write("END\n")
EOF2
axes() { # JSON -> the two frames' axes and bottlenecks, and the first's turned by 16 degrees
    python3 -c "import json, math, sys
f = json.load(open(sys.argv[1]))['frames']
a, b = f[0]['pore']['axis'], f[1]['pore']['axis']
c, s = math.cos(math.radians(16)), math.sin(math.radians(16))
t = [a[0], c * a[1] - s * a[2], s * a[1] + c * a[2]]
print(max(abs(x - y) for x, y in zip(b, t)), max(abs(x - y) for x, y in zip(b, a)),
      f[0]['channels'][0]['bottleneck_A'], f[1]['channels'][0]['bottleneck_A'])" "$1"
}
run 0 "$out" "$vorball" channels chb2.pdb --device ref --axis-refit --json -o refit.json
set -- $(axes refit.json)
awk -v e="$1" -v r0="$3" -v r1="$4" 'BEGIN { exit !(e < 1e-3 && r0 - r1 < 0.01 && r1 - r0 < 0.01) }' ||
    fail "--axis-refit: the second frame's axis is $1 off the turned axis (bottlenecks $3, $4)"
run 0 "$out" "$vorball" channels chb2.pdb --device ref --axis fixed --json -o fixed.json
set -- $(axes fixed.json)
awk -v e="$2" 'BEGIN { exit !(e == 0) }' || fail "--axis fixed: the second frame's axis moved"
exit 0
