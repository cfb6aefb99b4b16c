#!/bin/sh
# Regenerates the byte goldens of `vorball cells` (corpus/golden/cells/NAME.tsv
# and NAME.contacts.tsv, NAME the input's name less its extension) that
# tests/pipeline/cells_golden.sh holds every later change to, byte for byte,
# at the default tolerance.
#
# The cells tests elsewhere check enclosures (lo <= exact <= hi), which any
# reordering of the sums keeps valid; these files pin the last digits, so a
# change that moves them is seen. Regenerate ONLY for a change meant to move
# the values, and only where it is proven: every new interval must still
# enclose the exact value (meet the old interval, contain the closed forms
# or high-precision values the measures tests use), and the commit must say
# which change moved which digits and why. Regenerating to make a failing
# test pass hides the bug the test found (a reordered sum, a changed piece).
#
# usage: corpus/regenerate_cells.sh --deliberately VORBALL [INPUT...]
#   VORBALL  path of the vorball executable; INPUT (relative to corpus/)
#            defaults to the cases below.
set -u
cases="inputs/internally_tangent.xyzr inputs/nested_tangent_cluster.xyzr inputs/contained_sphere.xyzr
       inputs/intersecting_spheres.xyzr inputs/crambin_fragment.xyzr data/1crn.pdb"
if [ "${1:-}" != "--deliberately" ] || [ $# -lt 2 ]; then
    sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//' >&2
    exit 2
fi
vorball=$(cd "$(dirname "$2")" && pwd)/$(basename "$2")
shift 2
cd "$(dirname "$0")" || exit 3
mkdir -p golden/cells
[ $# -gt 0 ] || set -- $cases
status=0
for input in "$@"; do
    # as tests/pipeline/cells_golden.sh runs it: one thread, the input named
    # relative to corpus/; the provenance lines left out
    name=$(basename "$input" | sed 's/\.[^.]*$//')
    g=golden/cells/$name
    if "$vorball" cells "$input" --threads 1 -o "$g.tsv.raw" --contacts "$g.contacts.tsv.raw" &&
        grep -Ev '^# (tool|input|options): ' "$g.tsv.raw" > "$g.tsv" &&
        grep -Ev '^# (tool|input|options): ' "$g.contacts.tsv.raw" > "$g.contacts.tsv"; then
        echo "$name: $(grep -vc '^#' "$g.tsv") rows, $(grep -vc '^#' "$g.contacts.tsv") contact rows"
    else
        echo "$input: vorball cells failed" >&2
        status=1
    fi
    rm -f "$g.tsv.raw" "$g.contacts.tsv.raw"
done
exit $status
