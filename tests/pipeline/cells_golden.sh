#!/bin/sh
# `vorball cells` against byte goldens (corpus/golden/cells, written by
# corpus/regenerate_cells.sh): the per-atom TSV and the --contacts TSV of a
# few small cases at the default tolerance (a tangent pair, nested and
# contained spheres, a protein fragment, crambin), on 1 and 2 threads, byte
# for byte less the provenance lines. The other cells tests check
# enclosures, which a reordered sum or a changed piece keeps valid; these
# pin the last digits (cells has no --device: the measures are plain C
# whatever backend found the vertices).
# usage: cells_golden.sh VORBALL CORPUS WORKDIR
vorball=$1 corpus=$2 work=$3
. "$(dirname "$0")/lib.sh"
fresh_dir "$work/cells_golden"
cases="inputs/internally_tangent.xyzr inputs/nested_tangent_cluster.xyzr inputs/contained_sphere.xyzr
       inputs/intersecting_spheres.xyzr inputs/crambin_fragment.xyzr data/1crn.pdb"
cd "$corpus" || fail "no $corpus"
for input in $cases; do
    name=$(basename "$input" | sed 's/\.[^.]*$//')
    g=golden/cells/$name
    [ -f "$g.tsv" ] && [ -f "$g.contacts.tsv" ] || fail "no golden $g.tsv / $g.contacts.tsv"
    # the golden holds rows, not only a header
    [ "$(grep -vc '^#' "$g.tsv")" -ge 2 ] || fail "$g.tsv: no rows"
    for t in 1 2; do
        o=$work/cells_golden/$name.t$t
        run 0 "$o.log" "$vorball" cells "$input" --threads $t -o "$o.tsv" --contacts "$o.contacts.tsv"
        for f in tsv contacts.tsv; do
            sans_provenance "$o.$f" > "$o.$f.body"
            cmp -s "$o.$f.body" "$g.$f" || {
                diff "$g.$f" "$o.$f.body" | head -10 >&2
                fail "$name, $t threads: $f differs from $g.$f (see corpus/regenerate_cells.sh)"
            }
        done
    done
done
echo "cells_golden: ok"
