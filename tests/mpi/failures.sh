#!/bin/sh
# A rank that fails stops every rank: the job exits with the failing rank's
# exit status, its numbered error names the rank, rank 0 adds W831, and no
# vertex file or channels table is left. Errors every rank meets alike (bad
# input) are one line naming the ranks; commands that do not split refuse
# several ranks (E151), as does stdin input (E152).
# usage: failures.sh VORBALL MPIEXEC CORPUS_DIR WORK_DIR
vorball=$1 mpiexec=$2 corpus=$3 work=$4/mpi_failures
here=$(cd "$(dirname "$0")" && pwd)
. "$here/mpi_lib.sh"
mkdir -p "$work" || fail "cannot create $work"
crn=$corpus/data/1crn.pdb
rm -f "$work/f.tsv" "$work/fc.csv"
VORBALL_TEST_FAIL_RANK=1
export VORBALL_TEST_FAIL_RANK
run 6 "$work/f.err" mpi 3 -x VORBALL_TEST_FAIL_RANK "$vorball" vertices --device ref "$crn" -o "$work/f.tsv"
expect_line "$work/f.err" '^vorball: E6: rank 1 of 3: failure injected'
expect_line "$work/f.err" '^vorball: W831: rank 1 of 3 failed \(E6\): every rank stopped'
[ ! -e "$work/f.tsv" ] || fail "a failed job left $work/f.tsv"
VORBALL_TEST_FAIL_RANK=2
run 6 "$work/fc.err" mpi 3 -x VORBALL_TEST_FAIL_RANK "$vorball" channels --no-pore --grid 32 --frames ::10 \
    --device ref "$corpus/data/ngl_md_ascii_trj.pdb" -o "$work/fc.csv"
expect_line "$work/fc.err" '^vorball: E6: rank 2 of 3: failure injected'
[ ! -e "$work/fc.csv" ] || fail "a failed channels job left $work/fc.csv"
unset VORBALL_TEST_FAIL_RANK
printf '0 0 0 1\n1 0 0 1\n0 x 0 1\n0 0 1 1\n' > "$work/bad.xyzr"
run 11 "$work/b.err" mpi 3 "$vorball" vertices "$work/bad.xyzr" -o "$work/b.tsv"
expect_line "$work/b.err" '^vorball: E101: ranks 0-2 of 3: .*bad.xyzr:3: '
[ "$(grep -c '^vorball: E' "$work/b.err")" -eq 1 ] || fail "bad input reported more than once"
run 3 "$work/o.err" mpi 2 "$vorball" vertices --device ref "$crn" -o "$work/no/such/dir/x.tsv"
expect_line "$work/o.err" '^vorball: E8: rank 0 of 2: '
run 2 "$work/c.err" mpi 2 "$vorball" reference "$work/bad.xyzr"
expect_line "$work/c.err" '^vorball: E151: '
run 2 "$work/i.err" sh -c "'$mpiexec' --allow-run-as-root --oversubscribe -np 2 '$vorball' vertices - < '$crn'"
expect_line "$work/i.err" '^vorball: E152: '
run 2 "$work/u.err" mpi 3 "$vorball" vertices --no-such-option "$crn"
[ "$(grep -c 'unknown option' "$work/u.err")" -eq 1 ] || fail "usage error printed more than once"
echo "ok: failures stop every rank with the failing rank's status and name"
