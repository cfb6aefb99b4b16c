#!/bin/sh
# The input options every command shares (cli/input_options.c), as users
# type them: each is accepted, a bad or missing value is a usage error
# (exit 2), --help lists them, and a missing file is an i/o error (exit 3)
# naming it.
# usage: input_options.sh VORBALL CORPUS_DIR WORK_DIR
vorball=$1 corpus=$2 work=$3/input_options
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
mkdir -p "$work" || fail "cannot create $work"
cd "$corpus/inputs" || fail "no $corpus/inputs"
out=$work/out.txt
in=cubic_lattice.xyzr
run 0 "$out" "$vorball" reference --format xyzr --model 1 --water --no-hydrogens \
    --strict-elements --zero-radius point "$in" -o "$work/ref.tsv"
# (the options line names the options; everything else is the golden's)
sans_provenance "$work/ref.tsv" | cmp -s - ../golden/cubic_lattice.tsv ||
    fail "options changed the xyzr vertices"
expect_line "$work/ref.tsv" "^# options: reference --format xyzr --model 1 --water --no-hydrogens --strict-elements --zero-radius point $in$"
# gzip and bzip2 input, on stdin too: told by magic number, the same vertices.
gzip -c "$in" > "$work/in.gz" && bzip2 -c "$in" > "$work/in.bz2" || fail "cannot compress $in"
run 0 "$out" "$vorball" reference "$work/in.bz2" -o "$work/ref_bz2.tsv"
# (the header line names the input; the vertices must be the same bytes)
grep -v '^#' ../golden/cubic_lattice.tsv > "$work/golden_body.tsv"
grep -v '^#' "$work/ref_bz2.tsv" | cmp -s - "$work/golden_body.tsv" || fail "bzip2 input changed the vertices"
"$vorball" reference - -o "$work/ref_gz.tsv" < "$work/in.gz" > "$out" 2>&1 || fail "gzip on stdin failed"
grep -v '^#' "$work/ref_gz.tsv" | cmp -s - "$work/golden_body.tsv" || fail "gzip on stdin changed the vertices"
# --atoms FILE: the sphere table, one row per 0-based id, exact decimals.
run 0 "$out" "$vorball" reference "$in" --atoms "$work/atoms.tsv" -o "$work/ref_atoms.tsv"
[ "$(grep -vc '^#' "$work/atoms.tsv")" -eq 28 ] || fail "--atoms: not 27 rows and a header"
expect_line "$work/atoms.tsv" "^# vorball atoms: cubic_lattice.xyzr, 27 spheres$"
expect_line "$work/atoms.tsv" "^id	chain	resname	resseq	icode	atom	element	altloc	serial	line	x	y	z	r$"
expect_line "$work/atoms.tsv" "^0	\.	\.	\.	\.	\.	\.	\.	\.	1	0	0	0	0\.25$"
expect_line "$work/atoms.tsv" "^26	\.	\.	\.	\.	\.	\.	\.	\.	27	2	2	2	0\.25$"
run 0 "$out" "$vorball" vertices --device ref ../data/1crn.pdb --atoms "$work/atoms_1crn.tsv" -o "$work/1crn.tsv"
expect_line "$work/atoms_1crn.tsv" "^0	A	THR	1	\.	N	N	\.	1	273	17\.047	14\.099	3\.625	1\.55$"
[ "$(grep -vc '^#' "$work/atoms_1crn.tsv")" -eq 328 ] || fail "--atoms: 1crn has 327 atoms"
run 2 "$out" "$vorball" vertices --atoms
run 0 "$out" "$vorball" --help
expect_line "$out" "vorball --version"
run 0 "$out" "$vorball" --version
expect_line "$out" "^vorball [0-9][0-9.]* \\(commit [0-9a-z]"
expect_line "$out" "^build: [A-Za-z]*, [A-Za-z]* [0-9]"
expect_line "$out" "^exact arithmetic: GMP [0-9][0-9.]*, MPFR [0-9]"
expect_line "$out" "^device \\(--device auto\\): "
run 0 "$out" "$vorball" reference --help
for name in "--format F" "--model N" "--radii FILE" "--water" "--no-hydrogens" "--strict-elements" \
            "--zero-radius M" "--assembly N"; do
    expect_line "$out" "^  $name"
done
run 2 "$out" "$vorball" reference --format xtc "$in"
expect_line "$out" "unknown format 'xtc'"
# XYZR forced to GRO: malformed at its count line (exit 11), not an empty frame.
run 11 "$out" "$vorball" reference --format gro "$in"
expect_line "$out" "E101: cubic_lattice.xyzr:2:"
run 2 "$out" "$vorball" reference --model 0 "$in"
run 2 "$out" "$vorball" reference --model x2 "$in"
run 2 "$out" "$vorball" reference "$in" --model
run 2 "$out" "$vorball" reference --zero-radius maybe "$in"
run 3 "$out" "$vorball" reference --radii /nonexistent/radii.txt "$in"
expect_line "$out" "/nonexistent/radii.txt"
run 3 "$out" "$vorball" reference /nonexistent/in.xyzr
expect_line "$out" "/nonexistent/in.xyzr"
head -3 "$in" > "$work/three.xyzr"
run 16 "$out" "$vorball" reference "$work/three.xyzr"
# A radius file in HOLE's format (issue 32): rows matched per atom and
# residue name as HOLE matches them, the first matching row winning;
# remarks, BOND rows and AMBER's zero-radius lone pairs are skipped. A file
# whose rows name only first letters (and a GLN row: no GLN in gramicidin)
# gives the pore the plain element file gives; a row for C-alpha atoms,
# placed first, gives them its radius (W736, which left such rows out, is
# retired).
grm=$corpus/data/1grm_single_hole2.pdb
cat > "$work/hole.rad" << 'EOF2'
remark: element radii in HOLE's format
VDWR C??? ??? 1.85
VDWR O??? ??? 1.65
VDWR S??? ??? 2.00
VDWR N??? ??? 1.75
VDWR H??? ??? 1.00
VDWR P??? ??? 2.10
VDWR C??? ??? 9.99
VDWR E2?  GLN 1.00
VDWR LP?? ??? 0.00
BOND C??? 0.85
EOF2
printf 'C 1.85\nO 1.65\nS 2.00\nN 1.75\nH 1.00\nP 2.10\n' > "$work/plain.radii"
run 0 "$out" "$vorball" channels --device ref --grid 32 --radii "$work/hole.rad" "$grm" -o "$work/hole.csv"
grep -q "W736" "$out" && fail "W736 is retired"
run 0 "$out" "$vorball" channels --device ref --grid 32 --radii "$work/plain.radii" "$grm" -o "$work/plain.csv"
cmp -s "$work/hole.csv" "$work/plain.csv" || fail "HOLE's radius format gave other radii than the plain file"
{ echo "VDWR CA   ??? 1.00"; cat "$work/hole.rad"; } > "$work/ca.rad"
run 0 "$out" "$vorball" vertices --radii "$work/ca.rad" "$grm" --atoms "$work/ca_atoms.tsv" -o "$work/ca.tsv"
awk -F'\t' '$1 ~ /^[0-9]/ && (($6 == "CA") != ($14 == "1")) { bad = 1 } END { exit bad }' \
    "$work/ca_atoms.tsv" || fail "the CA row of a HOLE radius file was not matched per atom name"
[ "$(awk -F'\t' '$6 == "CA"' "$work/ca_atoms.tsv" | wc -l)" -eq 32 ] || fail "gramicidin has 32 CA atoms"
echo "ok: input options"
