#!/bin/sh
# One corpus case through `vorball vertices`: the certified vertices equal the
# golden (vertex lines; the golden's header names `reference`), the reference
# backend and the OpenCL backend on the CPU (PoCL) write byte-identical
# files, and culling changes nothing (--all-pairs).
# usage: vertices_golden.sh VORBALL CORPUS_DIR CASE WORK_DIR
vorball=$1 corpus=$2 case=$3 work=$4/vertices_$3
fail() { echo "FAIL: $case: $*" >&2; exit 1; }
mkdir -p "$work" || fail "cannot create $work"
cd "$corpus/inputs" || fail "no $corpus/inputs"
golden=../golden/$case.tsv
[ -f "$golden" ] || fail "no golden $golden"
"$vorball" vertices --device ref "$case.xyzr" > "$work/ref.tsv" 2> "$work/ref.err" ||
    { cat "$work/ref.err" >&2; fail "vertices --device ref failed"; }
grep -v '^#' "$golden" > "$work/golden.body"
grep -v '^#' "$work/ref.tsv" > "$work/ref.body"
cmp -s "$work/golden.body" "$work/ref.body" ||
    { diff "$work/golden.body" "$work/ref.body" | head -10 >&2; fail "differs from the golden"; }
"$vorball" vertices --device ref --all-pairs "$case.xyzr" > "$work/all.tsv" 2>/dev/null ||
    fail "--all-pairs failed"
# (the options line names --all-pairs; all else the same bytes)
grep -Ev '^# (tool|input|options): ' "$work/ref.tsv" > "$work/ref.sans"
grep -Ev '^# (tool|input|options): ' "$work/all.tsv" | cmp -s - "$work/ref.sans" || fail "culled and all-pairs outputs differ"
if "$vorball" devices 2>/dev/null | grep -qi cpu; then
    "$vorball" vertices --device cpu "$case.xyzr" > "$work/cpu.tsv" 2> "$work/cpu.err" ||
        { cat "$work/cpu.err" >&2; fail "vertices --device cpu failed"; }
    cmp -s "$work/ref.tsv" "$work/cpu.tsv" || fail "OpenCL (CPU) and reference outputs differ"
fi
echo "ok: $case ($(wc -l < "$work/ref.body") vertices)"
