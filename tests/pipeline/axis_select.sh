#!/bin/sh
# Issue 32: the pore axis at the defaults and --select, as users run them.
# - --select on vertices, cells and channels: the same atoms as a file cut
#   by hand; a malformed expression or an empty selection is E118 (exit 28)
#   naming the position; no output file is left.
# - the axis: cholera toxin B (1chb) by its C5 symmetry, the maltoporin
#   trimer (1af6, sugars left out as HOLE's example does) by one subunit's
#   barrel, one maltoporin chain (--select) by its barrel; W810 names the
#   source, axis_why in the JSON says it in words; crambin keeps no pore (W808).
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
run 0 "$out" "$vorball" channels "$d/1af6_hole2.pdb.gz" --device ref --ignore FRU,GLC,MG --json -o 1af6.json
expect_line "$out" "W810: .*pore axis \(subunit\): beta-barrel of chain"
set -- $(pore 1af6.json)
[ "$1" = subunit ] || fail "1af6: axis from '$1', not a subunit"
awk -v r="$2" 'BEGIN { exit !(r > 1.9 && r < 2.5) }' || fail "1af6: pore $2 A (2.2 A expected)"
run 0 "$out" "$vorball" channels "$d/1af6_hole2.pdb.gz" --device ref --ignore FRU,GLC,MG \
    --select "chain B" --json -o 1af6_B.json
set -- $(pore 1af6_B.json)
[ "$1" = barrel ] || fail "1af6 chain B: axis from '$1', not its barrel"
run 0 "$out" "$vorball" channels "$d/1crn.pdb" --device ref -o 1crn.csv
expect_line "$out" "W808"
exit 0
