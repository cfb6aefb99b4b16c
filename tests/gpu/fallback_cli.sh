#!/bin/sh
# A machine without any OpenCL platform (OCL_ICD_VENDORS names an empty
# directory): `vertices` and `jfa` must warn and fall back to their plain-C
# reference backends (W760, W781), exit 0, and write what the reference backend
# writes when asked for directly. `--device gpu` on such a machine falls back
# the same way.
# usage: fallback_cli.sh VORBALL CORPUS_INPUTS_DIR WORK_DIR
vorball=$1 inputs=$2 work=$3/fallback_cli
fail() { echo "FAIL: $*" >&2; exit 1; }
mkdir -p "$work/no-vendors" || fail "cannot create $work"
for case in cubic_lattice two_vertices_one_quadruple; do
    "$vorball" vertices --device ref "$inputs/$case.xyzr" > "$work/$case.ref" 2> "$work/$case.ref.err" ||
        fail "$case: ref run failed"
    for dev in auto gpu; do
        OCL_ICD_VENDORS=$work/no-vendors "$vorball" vertices --device $dev "$inputs/$case.xyzr" \
            > "$work/$case.$dev" 2> "$work/$case.$dev.err" || fail "$case $dev: exit $?"
        grep -q "W760" "$work/$case.$dev.err" || fail "$case $dev: no W760 fallback warning"
        cmp -s "$work/$case.ref" "$work/$case.$dev" || fail "$case $dev: output differs from ref"
    done
done
"$vorball" jfa --device ref -n 64 -k 20 --check --json > "$work/jfa.ref" 2> /dev/null ||
    fail "jfa ref run failed"
OCL_ICD_VENDORS=$work/no-vendors "$vorball" jfa -n 64 -k 20 --check --json > "$work/jfa.auto" \
    2> "$work/jfa.auto.err" || fail "jfa auto: exit $?"
grep -q "W781" "$work/jfa.auto.err" || fail "jfa: no W781 fallback warning"
# The figures other than timings must agree: labels are those of the reference.
strip() { sed -E 's/"(time_ms|time_ms_min|gpu_ms|fill_ms|prep_transfer_ms|exact_ms)": [0-9.e+-]+/"\1": T/g; s/"device": "[^"]*"/"device": D/' "$1"; }
[ "$(strip "$work/jfa.ref")" = "$(strip "$work/jfa.auto")" ] || fail "jfa: figures differ from ref"
echo "fallback_cli: ok"
