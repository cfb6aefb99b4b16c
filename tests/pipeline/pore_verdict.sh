#!/bin/sh
# The pore verdict (issue 32; vbc_pore.h): a pore is reported only when its
# path crosses the molecule walled by the molecule's atoms for 15 A or more.
# Gramicidin A and cholera toxin keep their pores; crambin, three of its
# atoms and adenylate kinase (soluble) get none: W808 names the buried
# length, the command exits 0 and the table has no pore row. A path along an
# axis the user gives is reported as it is. The membrane (OPM's dummy atoms
# DUM, also as OPM writes them, lipid and detergent residues) is left out by
# default with W809.
# usage: pore_verdict.sh VORBALL CORPUS_DIR WORK_DIR
vorball=$1 corpus=$2 work=$3/pore_verdict
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
fresh_dir "$work"
out=$work/out.txt

pore_rows() { grep -c '^0,[0-9]*,[0-9]*,pore,' "$1" || true; }

run 0 "$out" "$vorball" channels --device ref --grid 64 "$corpus/data/1grm_single_hole2.pdb" -o grm.csv
[ "$(pore_rows grm.csv)" = 1 ] || fail "gramicidin lost its pore"
! grep -q W808 "$out" || fail "W808 on gramicidin"
run 0 "$out" "$vorball" channels --device ref --grid 64 "$corpus/data/1chb_hole2.pdb" -o chb.csv
[ "$(pore_rows chb.csv)" = 1 ] || fail "cholera toxin lost its pore"

run 0 "$out" "$vorball" channels --device ref --grid 64 "$corpus/data/1crn.pdb" -o crn.csv
expect_line "$out" "W808: .*1crn.pdb: no pore: the widest path along the principal axis is walled by the molecule's atoms for [0-9.]+ A only"
[ "$(pore_rows crn.csv)" = 0 ] || fail "crambin has a pore row"
head -1 crn.csv | grep -q '^frame,model,channel,kind' || fail "crambin's table has no header"

grep '^ATOM' "$corpus/data/1crn.pdb" | head -3 > three.pdb
run 0 "$out" "$vorball" channels --device ref --grid 32 three.pdb -o three.csv
expect_line "$out" "W808"
[ "$(pore_rows three.csv)" = 0 ] || fail "three atoms have a pore"

run 0 "$out" "$vorball" channels --device ref --grid 64 "$corpus/data/adk_open.pdb.gz" -o adk.csv
expect_line "$out" "W808"
[ "$(pore_rows adk.csv)" = 0 ] || fail "adenylate kinase has a pore"

# The user's axis is swept and reported whatever the verdict.
run 0 "$out" "$vorball" channels --device ref --grid 64 --axis 0,0,1 "$corpus/data/1crn.pdb" -o crnz.csv
[ "$(pore_rows crnz.csv)" = 1 ] || fail "the given axis was not reported"
# Gramicidin in an OPM-style membrane: two planes of DUM atoms (N and O,
# 1.5 A apart) normal to its pore (y) at y = +-15 A, and a POPC "lipid"
# beside it. At the defaults the membrane is left out (W809 names it), its
# normal is the axis (W810: membrane normal, y) and the pore is
# gramicidin's (the same bottleneck); with --membrane none the dummy atoms
# close it.
grep -v '^END' "$corpus/data/1grm_single_hole2.pdb" > mem.pdb
awk 'BEGIN { n = 5000
  for (p = -1; p <= 1; p += 2) for (i = -10; i <= 10; i++) for (j = -10; j <= 10; j++) {
    e = (i + j) % 2 ? "N" : "O"
    printf "HETATM%5d  %-3s DUM D   1    %8.3f%8.3f%8.3f  1.00  0.00           %s\n", n++ % 100000, e, 1.5 * i, 15 * p, 1.5 * j, e }
  for (k = 0; k < 3; k++)
    printf "HETATM%5d  C%-2d POPCL   2    %8.3f%8.3f%8.3f  1.00  0.00           C\n", n++, k, 25 + 1.5 * k, 0, 25 }' >> mem.pdb
echo END >> mem.pdb
run 0 "$out" "$vorball" channels --device ref --grid 64 mem.pdb -o mem.csv
expect_line "$out" "W809: mem.pdb: 885 atoms left out: membrane \(--membrane none keeps it\): DUM 882, POPC 3"
expect_line "$out" "W810: mem.pdb: pore axis \(membrane\): membrane normal \(882 DUM atoms"
run 0 "$out" "$vorball" channels --device ref --grid 64 mem.pdb --json -o mem.json
grep -q '"axis": \[0.00000, 1.00000, 0.00000\]' mem.json || fail "the membrane normal is not y: $(grep -o '"axis": [^]]*' mem.json)"
grep -q '"axis_from": "membrane"' mem.json || fail "axis_from is not membrane"
# The bottleneck (the pore row's 7th field) as gramicidin's alone.
cut -d, -f1-5,7 grm.csv | sed -n 2p > want.txt
cut -d, -f1-5,7 mem.csv | sed -n 2p > got.txt
cmp -s want.txt got.txt || fail "gramicidin in a membrane: $(cat got.txt), alone: $(cat want.txt)"
run 0 "$out" "$vorball" channels --device ref --grid 64 --membrane none mem.pdb -o memkept.csv
! grep -q W809 "$out" || fail "W809 with --membrane none"
cmp -s grm.csv memkept.csv && fail "--membrane none changed nothing"
run 0 "$out" "$vorball" channels --device ref --grid 64 --membrane POPC mem.pdb -o mempopc.csv
expect_line "$out" "W809: mem.pdb: 3 atoms left out: membrane \(--membrane none keeps it\): POPC 3"
# The same as OPM writes its dummy atoms: HETATM, residue DUM numbered as the
# atom, no chain, no element, the record ending at column 54; a 2 A lattice
# alternating N and O in the planes z = +-15.2 A (OPM's membrane normal is
# z), gramicidin turned so that its pore runs along z ((x, y, z) -> (x, -z,
# y)). They are the membrane (W809), not ligands (no W811), and their normal
# z is the axis: the bottleneck is that of the turned gramicidin alone along
# the axis given as z.
pdb_y_to_z "$corpus/data/1grm_single_hole2.pdb" > grmz.pdb
cp grmz.pdb opm.pdb
awk 'BEGIN { n = 3001
  for (p = -1; p <= 1; p += 2) for (i = -8; i <= 8; i++) for (j = -8; j <= 8; j++) {
    printf "HETATM%5d  %-3s DUM  %4d    %8.3f%8.3f%8.3f\n", n, (i + j) % 2 ? "N" : "O", n, 2 * i, 2 * j, 15.2 * p
    n++ } }' >> opm.pdb
echo END >> opm.pdb
[ "$(grep -c ' DUM ' opm.pdb)" = 578 ] || fail "the OPM-style file has $(grep -c ' DUM ' opm.pdb) DUM atoms, not 578"
run 0 "$out" "$vorball" channels --device ref --grid 64 opm.pdb --json -o opm.json
expect_line "$out" "W809: opm.pdb: 578 atoms left out: membrane \(--membrane none keeps it\): DUM 578"
expect_line "$out" "W810: opm.pdb: pore axis \(membrane\): membrane normal \(578 DUM atoms"
! grep -q W811 "$out" || fail "OPM's dummy atoms taken for ligands"
grep -q '"axis": \[0.00000, 0.00000, 1.00000\]' opm.json || fail "OPM's membrane normal is not z: $(grep -o '"axis": [^]]*' opm.json)"
run 0 "$out" "$vorball" channels --device ref --grid 64 opm.pdb -o opm.csv
run 0 "$out" "$vorball" channels --device ref --grid 64 --axis 0,0,1 grmz.pdb -o grmz.csv
cut -d, -f1-5,7 grmz.csv | sed -n 2p > wantz.txt
cut -d, -f1-5,7 opm.csv | sed -n 2p > got.txt
cmp -s wantz.txt got.txt || fail "gramicidin in OPM's dummy atoms: $(cat got.txt), alone along z: $(cat wantz.txt)"
# The user's axis still wins over the membrane's normal.
run 0 "$out" "$vorball" channels --device ref --grid 64 --axis 1,0,0 opm.pdb --json -o opmx.json
grep -q '"axis": \[1.00000, 0.00000, 0.00000\]' opmx.json || fail "--axis lost to the membrane normal"
! grep -q W810 "$out" || fail "W810 with --axis"
run 0 "$out" "$vorball" channels --device ref --grid 64 --membrane none opm.pdb -o opmkept.csv
cut -d, -f1-5,7 opmkept.csv | sed -n 2p > got.txt
cmp -s wantz.txt got.txt && fail "--membrane none: OPM's dummy atoms changed nothing"
echo "pore verdict: ok"
