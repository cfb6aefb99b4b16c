#!/bin/sh
# The pore verdict (issue 32; vbc_pore.h): a pore is reported only when its
# path crosses the molecule walled by the molecule's atoms for 15 A or more.
# Gramicidin A and cholera toxin keep their pores; crambin, three of its
# atoms and adenylate kinase (soluble) get none: W808 names the buried
# length, the command exits 0 and the table has no pore row. A path along an
# axis the user gives is reported as it is.
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
echo "pore verdict: ok"
