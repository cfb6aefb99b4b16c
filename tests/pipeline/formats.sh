#!/bin/sh
# `vorball reference --output-format json|voronota` output read back by
# `vorball verify` (format detected by content): every vertex certified and,
# for Voronota lines, regrouped into as many vertices as the golden has.
# usage: formats.sh VORBALL CORPUS_DIR WORK_DIR
vorball=$1 corpus=$2 work=$3/formats
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
mkdir -p "$work" || fail "cannot create $work"
cd "$corpus/inputs" || fail "no $corpus/inputs"
out=$work/out.txt
for c in cubic_lattice hexagonal_ring two_vertices_one_quadruple jittered_lattice; do
    nv=$(vertex_lines "../golden/$c.tsv" | wc -l)
    run 0 "$out" "$vorball" reference "$c.xyzr" --output-format json -o "$work/$c.json"
    run 0 "$out" "$vorball" verify "$c.xyzr" "$work/$c.json" --complete
    expect_line "$out" "^verify: $nv lines \(json\): $nv certified, .* 0 missed$"
    run 0 "$out" "$vorball" reference "$c.xyzr" --output-format voronota -o "$work/$c.voronota"
    run 0 "$out" "$vorball" verify "$c.xyzr" "$work/$c.voronota" --complete
    expect_line "$out" "^verify: [0-9]+ lines \(voronota, $nv vertices\): [0-9]+ certified, 0 not a vertex.* 0 missed$"
done
echo "ok: formats"
