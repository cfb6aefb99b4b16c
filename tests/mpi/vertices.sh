#!/bin/sh
# `vorball vertices` under mpirun -np 2 and -np 3 (and -np 1 for crambin and
# the degree-5 case) writes the bytes one process writes without mpirun:
# every corpus case, crambin (PDB) and the 1crn PQR, on the default
# device (PoCL on CI) and on the reference backend; a vertex of degree > 4
# certified by two ranks is merged (merged_repeats in --stats); the sampling
# proposer runs on rank 0 alone (W830) with the same output, --topology too.
# usage: vertices.sh VORBALL MPIEXEC CORPUS_DIR WORK_DIR
vorball=$1 mpiexec=$2 corpus=$3 work=$4/mpi_vertices
here=$(cd "$(dirname "$0")" && pwd)
. "$here/mpi_lib.sh"
mkdir -p "$work" || fail "cannot create $work"
repeats=0
for input in "$corpus"/inputs/*.xyzr "$corpus/data/1crn.pdb" "$corpus/data/1crn_apbs.pqr"; do
    case=$(basename "$input")
    device=ref
    case $case in 1crn*|degree5*|cubic*) device=auto ;; esac
    nps="2 3"
    case $case in 1crn.pdb|degree5*) nps="1 2 3" ;; esac
    run 0 "$work/$case.err" "$vorball" vertices --device $device "$input" -o "$work/$case.tsv"
    for np in $nps; do
        run 0 "$work/$case.$np.err" mpi $np "$vorball" vertices --device $device --stats "$input" \
            -o "$work/$case.$np.tsv"
        same_bytes "$case on $np ranks" "$work/$case.tsv" "$work/$case.$np.tsv"
        [ "$np" -eq 1 ] && continue
        expect_line "$work/$case.$np.err" "^ranks	$np$"
        r=$(sed -n 's/^merged_repeats	//p' "$work/$case.$np.err")
        repeats=$((repeats + r))
    done
done
# The degree-5 vertex and the lattices' vertices meet cells of several ranks.
[ "$repeats" -gt 0 ] || fail "no vertex certified by two ranks was merged"
crn=$corpus/data/1crn.pdb
run 0 "$work/s.1.err" "$vorball" vertices --proposer sampling --device ref "$crn" \
    -o "$work/s.1.tsv" --topology "$work/t.1.txt"
run 0 "$work/s.3.err" mpi 3 "$vorball" vertices --proposer sampling --device ref "$crn" \
    -o "$work/s.3.tsv" --topology "$work/t.3.txt"
same_bytes "sampling on 3 ranks" "$work/s.1.tsv" "$work/s.3.tsv"
same_bytes "topology on 3 ranks" "$work/t.1.txt" "$work/t.3.txt"
expect_line "$work/s.3.err" "^vorball: W830: .*rank 0 runs it alone, 2 rank"
[ "$(grep -c 'W830' "$work/s.3.err")" -eq 1 ] || fail "W830 printed more than once"
# Input warnings come once, from rank 0 (W713: PQR's radius-0 hydrogens).
run 0 "$work/w.3.err" mpi 3 "$vorball" vertices --device ref "$corpus/data/1crn_apbs.pqr" -o "$work/w.tsv"
[ "$(grep -c 'W713' "$work/w.3.err")" -eq 1 ] || { cat "$work/w.3.err" >&2; fail "W713 not printed exactly once"; }
# The other ranks' warnings reach rank 0 as records (number, file, line,
# message; cli/world_mpi.c) and are printed once, tagged with their ranks:
# without a GPU every rank falls back to the reference (W760).
run 0 "$work/g.3.err" mpi 3 "$vorball" vertices --device gpu "$corpus/inputs/contained_sphere.xyzr" \
    -o "$work/g.tsv"
if grep -q '^vorball: W760: no usable' "$work/g.3.err"; then
    expect_line "$work/g.3.err" '^vorball: W760: ranks 1, 2 of 3: no usable OpenCL device'
    [ "$(grep -c 'W760' "$work/g.3.err")" -eq 2 ] ||
        { cat "$work/g.3.err" >&2; fail "W760 not once from rank 0, once from ranks 1, 2"; }
fi
# bench: the split run, timed on rank 0, finds the same vertices.
run 0 "$work/b.1.out" "$vorball" bench --device ref --json "$crn"
run 0 "$work/b.2.out" mpi 2 "$vorball" bench --device ref --json "$crn"
v1=$(sed -n 's/.*"vertices": \([0-9]*\),.*/\1/p' "$work/b.1.out")
v2=$(sed -n 's/.*"vertices": \([0-9]*\),.*/\1/p' "$work/b.2.out")
[ -n "$v1" ] && [ "$v1" = "$v2" ] || fail "bench: $v1 vertices on one process, $v2 on 2 ranks"
expect_line "$work/b.2.out" '"ranks": 2, "combine": '
echo "ok: vertices on 1, 2 and 3 ranks are one process's bytes ($repeats vertices merged from two ranks)"
