#!/bin/sh
# One corpus case: `vorball reference` reproduces the golden byte for byte,
# `vorball verify --complete` accepts the golden, every arc of it closes
# (verify --arcs, and vertices --arcs reproduces it with its certificate on
# any thread count, and its exact topology: topology.sh), and the golden shows the property the case was built
# for (properties.sh).
# usage: golden.sh VORBALL CORPUS_DIR CASE WORK_DIR
vorball=$1 corpus=$2 case=$3 work=$4/golden_$3
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
mkdir -p "$work" || fail "cannot create $work"
# Inputs are named relative to corpus/inputs, as corpus/regenerate.sh does,
# so that the file name inside the golden's header is the same.
cd "$corpus/inputs" || fail "no $corpus/inputs"
golden=../golden/$case.tsv
[ -f "$golden" ] || fail "no golden $golden"
"$vorball" reference "$case.xyzr" > "$work/reference.tsv" 2> "$work/reference.err"
rc=$?
[ $rc -eq 0 ] || { cat "$work/reference.err" >&2; fail "reference exited $rc"; }
# Byte for byte, header included, less the provenance lines (the tool line
# names the commit; goldens hold none, corpus/regenerate.sh drops them), which
# are checked on their own.
sans_provenance "$work/reference.tsv" > "$work/reference.body"
sans_provenance "$golden" > "$work/golden.body"
cmp "$work/reference.body" "$work/golden.body" || {
    diff "$work/reference.body" "$work/golden.body" | head -20 >&2
    fail "reference output differs from $golden"
}
n_in=$(sed -n "s/^# vorball reference $case\.xyzr: \([0-9]*\) spheres, .*/\1/p" "$golden")
sed -n 2,4p "$work/reference.tsv" > "$work/provenance.txt"
expect_line "$work/provenance.txt" "^# tool: vorball [0-9]+\.[0-9]+\.[0-9]+ \(commit [^)]+\)$"
expect_line "$work/provenance.txt" "^# input: $case\.xyzr, $n_in spheres$"
expect_line "$work/provenance.txt" "^# options: reference $case\.xyzr$"
run 0 "$work/verify.txt" "$vorball" verify "$case.xyzr" "$golden" --complete
expect_line "$work/verify.txt" "^verify: .* 0 not a vertex, 0 wrong coordinates, 0 missing members, 0 duplicate, 0 missed$"
# exact arc closure: every Voronoi edge of the golden ends at a golden vertex
run 0 "$work/arcs.txt" "$vorball" verify "$case.xyzr" "$golden" --arcs
expect_line "$work/arcs.txt" "^$golden: arcs: [0-9]+ vertices traced, [0-9]+ half arcs: .* 0 undecided; 0 vertices added; [0-9]+ components$"
# vertices --arcs: the cover's list traced, the golden's vertices written
# with the certificate's header line, the same bytes on 1 and 3 threads;
# with --topology the traced edges too (topology.sh checks them)
for t in 1 3; do
    run 0 "$work/arcs$t.err" "$vorball" vertices --device ref --arcs --threads $t "$case.xyzr" \
        -o "$work/arcs$t.tsv" --topology "$work/arcs$t.top"
done
cmp "$work/arcs1.tsv" "$work/arcs3.tsv" || fail "vertices --arcs differs between 1 and 3 threads"
cmp "$work/arcs1.top" "$work/arcs3.top" || fail "vertices --topology differs between 1 and 3 threads"
sh "$here/topology.sh" "$case" "$work/arcs1.tsv" "$work/arcs1.top" || fail "$case: exact topology"
vertex_lines "$work/arcs1.tsv" > "$work/arcs1.lines"
vertex_lines "$golden" > "$work/golden.lines"
cmp "$work/arcs1.lines" "$work/golden.lines" || fail "vertices --arcs does not reproduce $golden"
n=$(grep -c . "$work/golden.lines")
expect_line "$work/arcs1.tsv" "^# arcs: every arc closed exactly: $n vertices, [0-9]+ half arcs: .* 0 undecided; 0 vertices added by tracing; [0-9]+ connected components$"
sh "$here/properties.sh" "$case" "$golden" "$work" || fail "$case: property does not hold"
echo "ok: $case ($(vertex_lines "$golden" | wc -l) vertices)"
