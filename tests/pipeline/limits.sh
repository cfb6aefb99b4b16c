#!/bin/sh
# Limits of the commands, each refused with its own number (issue 18, items
# 5 and 11) instead of an answer that is silently wrong or takes hours:
# radii below 1e-50 of the extent (E131, exit 41; all vertices were lost from
# 1e-78 on) and --tol below 1e-12 of it (E132, exit 42; vertices were lost)
# for the sampling proposer, while `reference` and the cover proposer (the
# default, which has no such limit) compute the same input and the sampling
# agrees with them at 1e-40; `reference` above 500 spheres without
# --force (E130, exit 40; it grows as n^2.7 or worse).
# usage: limits.sh VORBALL CORPUS_DIR WORK_DIR
vorball=$1 corpus=$2 work=$3/limits
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
fresh_dir "$work"
out=$work/out.txt
frag=$corpus/inputs/crambin_fragment.xyzr

# Item 5: tiny radii, fine tolerances.
awk '!/^#/ { print $1, $2, $3, "1e-78" }' "$frag" > r78.xyzr
awk '!/^#/ { print $1, $2, $3, "1e-40" }' "$frag" > r40.xyzr
for dev in ref cpu; do
    run 41 "$out" "$vorball" vertices --proposer sampling --device $dev r78.xyzr -o v78.tsv
    expect_line "$out" "E131: r78.xyzr:1: radius 1e-78 is below 1e-50 of the input's extent"
    [ ! -e v78.tsv ] || fail "a refused run wrote v78.tsv"
done
run 0 "$out" "$vorball" reference r78.xyzr -o ref78.tsv
[ "$(vertex_lines ref78.tsv | wc -l)" -eq 347 ] || fail "reference: not 347 vertices at 1e-78"
run 0 "$out" "$vorball" vertices --device ref r78.xyzr -o c78.tsv
vertex_lines ref78.tsv > a.txt
vertex_lines c78.tsv > b.txt
cmp -s a.txt b.txt || fail "the cover and reference differ at radius 1e-78"
run 0 "$out" "$vorball" reference r40.xyzr -o ref40.tsv
run 0 "$out" "$vorball" vertices --proposer sampling --device ref r40.xyzr -o v40.tsv
vertex_lines ref40.tsv > a.txt
vertex_lines v40.tsv > b.txt
cmp -s a.txt b.txt || fail "vertices and reference differ at radius 1e-40"
[ "$(wc -l < a.txt)" -eq 347 ] || fail "not 347 vertices at radius 1e-40"
run 42 "$out" "$vorball" vertices --proposer sampling --device ref --tol 1e-18 "$frag"
expect_line "$out" "E132: .*crambin_fragment.xyzr: --tol 1e-18 is below 1e-12 of the input's extent"
run 0 "$out" "$vorball" vertices --proposer sampling --device ref "$frag" -o default.tsv
run 0 "$out" "$vorball" vertices --proposer sampling --device ref --tol 1e-10 "$frag" -o fine.tsv
sans_provenance default.tsv > default.body
sans_provenance fine.tsv | cmp -s - default.body || fail "--tol 1e-10 (above the bound) lost vertices"
# The cover at --tol 1e-18: every vertex (349), as at the default.
run 0 "$out" "$vorball" vertices --device ref --tol 1e-18 "$frag" -o cover18.tsv
[ "$(vertex_lines cover18.tsv | wc -l)" -eq 349 ] || fail "the cover lost vertices at --tol 1e-18"

# Item 11: reference above 500 spheres.
awk 'BEGIN { for (i = 0; i < 501; i++)
    printf "%d.%03d %d.%03d %d.%03d 1.5\n", (i * 7) % 40, (i * 13) % 1000, (i * 11) % 37,
        (i * 29) % 1000, (i * 3) % 41, (i * 17) % 1000 }' > big.xyzr
run 40 "$out" "$vorball" reference big.xyzr -o big.tsv
expect_line "$out" "E130: big.xyzr: 501 spheres: the exact reference takes at most 500 without --force"
[ ! -e big.tsv ] || fail "a refused reference wrote big.tsv"
# --force runs it: W720 at the start, then the enumeration (stopped here).
timeout 5 "$vorball" reference --force big.xyzr -o big.tsv > "$out" 2>&1
rc=$?
[ $rc -eq 124 ] || [ $rc -eq 0 ] || { cat "$out" >&2; fail "reference --force exited $rc"; }
expect_line "$out" "W720: big.xyzr: exact reference on 501 spheres"
echo "ok: limits"
