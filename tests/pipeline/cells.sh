#!/bin/sh
# `vorball cells` as users run it: the tables' shape, the same bytes for 1
# and 2 threads on corpus cases, W850 for empty cells, numbered errors for
# bad options with no output file left behind.
# usage: cells.sh VORBALL CORPUS WORKDIR
vorball=$1 corpus=$2 work=$3
. "$(dirname "$0")/lib.sh"
fresh_dir "$work/cells"

printf '0 0 0 1.0\n1.5 0 0 1.0\n0 9 0 1.2\n' > three.xyzr
run 0 log "$vorball" cells three.xyzr --tolerance 1e-4 -o atoms.tsv --contacts contacts.tsv
expect_line atoms.tsv '^id	chain	resname	resseq	atom	volume	volume_lo	volume_hi	sas	sas_lo	sas_hi$'
expect_line atoms.tsv '^0	\.	\.	\.	\.	42\.08[0-9]*	'
expect_line atoms.tsv '^2	\.	\.	\.	\.	73\.622176[0-9]*	'
# The provenance (issue 35), as vertex files carry it: the tool, the input
# and its sphere count, the options that shape the table (-o left out, the
# other output paths written FILE); the same lines head both tables.
for t in atoms.tsv contacts.tsv; do
    expect_line $t '^# tool: vorball [0-9][0-9.]* \(commit [^)]*\)$'
    expect_line $t '^# input: three\.xyzr, 3 spheres$'
    expect_line $t '^# options: cells three\.xyzr --tolerance 1e-4 --contacts FILE$'
    [ "$(head -n 3 $t | grep -c '^# ')" -eq 3 ] || fail "$t: the provenance is not its first 3 lines"
done
[ "$(grep -vc '^#' atoms.tsv)" -eq 4 ] || fail "atoms.tsv: $(grep -vc '^#' atoms.tsv) lines, expected 4"
expect_line contacts.tsv '^id1	id2	area	area_lo	area_hi$'
expect_line contacts.tsv '^0	1	16\.328[0-9]*	'
[ "$(grep -vc '^#' contacts.tsv)" -eq 2 ] || fail "contacts.tsv: expected one contact"
# every row: lo <= value <= hi
awk -F'\t' '!/^#/ && $1 != "id" && !($7 <= $6 && $6 <= $8 && $10 <= $9 && $9 <= $11) { exit 1 }' atoms.tsv ||
    fail "a value outside its enclosure"

# --stats: the seconds per stage, every stage named (three closed-form
# cells: nothing left to the patches), and the tables the same bytes
run 0 log "$vorball" cells three.xyzr --tolerance 1e-4 -o st.tsv --contacts stc.tsv --stats
expect_line log '^cells stages \(CPU s, every thread summed\): neighbours [0-9.]* caps [0-9.]* arrangement [0-9.]* integrals [0-9.]* patches 0\.000$'
cmp -s atoms.tsv st.tsv && cmp -s contacts.tsv stc.tsv || fail "--stats changed a table"

for case in contained_sphere internally_tangent hexagonal_ring; do
    run 0 log1 "$vorball" cells "$corpus/inputs/$case.xyzr" --tolerance 1e-2 --max-patches 2000 --threads 1 \
        -o "$case.1.tsv" --contacts "$case.c1.tsv"
    run 0 log2 "$vorball" cells "$corpus/inputs/$case.xyzr" --tolerance 1e-2 --max-patches 2000 --threads 2 \
        -o "$case.2.tsv" --contacts "$case.c2.tsv"
    cmp -s "$case.1.tsv" "$case.2.tsv" || fail "$case: atoms differ between 1 and 2 threads"
    cmp -s "$case.c1.tsv" "$case.c2.tsv" || fail "$case: contacts differ between 1 and 2 threads"
    if [ "$case" = contained_sphere ]; then
        expect_line log1 'W850'
        # an empty cell's row holds zeros
        awk -F'\t' '!/^#/ && $1 != "id" && $6 == 0 && $8 == 0 { found = 1 } END { exit !found }' \
            "$case.1.tsv" || fail "no empty cell with zero volume"
    fi
done

run 2 log "$vorball" cells three.xyzr --probe -1 -o bad.tsv
expect_line log 'E7'
run 2 log "$vorball" cells three.xyzr --tolerance 1 -o bad.tsv --contacts badc.tsv
expect_line log 'E7'
[ ! -e bad.tsv ] && [ ! -e badc.tsv ] || fail "a failing command left an output file"
echo "cells: ok"
