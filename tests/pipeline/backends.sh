#!/bin/sh
# Every backend against the reference: `vorball vertices --device DEVICE`
# must write exactly the golden's vertex lines (ids, doubles to the last bit,
# order) for every corpus case (the goldens' headers are `vorball reference`'s),
# and, for a DEVICE other than ref, the same file as `--device ref` but its
# provenance lines (the certificate line included).
# usage: backends.sh VORBALL CORPUS_DIR WORK_DIR DEVICE
vorball=$1 corpus=$2 device=$4 work=$3/backend_$4
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
mkdir -p "$work" || fail "cannot create $work"
cd "$corpus/inputs" || fail "no $corpus/inputs"
bad=0
for input in *.xyzr; do
    case=${input%.xyzr}
    if ! "$vorball" vertices --device "$device" "$input" -o "$work/$case.tsv" 2> "$work/$case.err"; then
        cat "$work/$case.err" >&2
        echo "FAIL: $case: vorball vertices --device $device failed" >&2
        bad=1
        continue
    fi
    # A kernel that does not build falls back to --device ref with the same
    # bytes (W760): on a device that exists that is a failure of the kernel.
    if [ "$device" != ref ] && grep -q 'OpenCL program build failed' "$work/$case.err"; then
        grep 'W76' "$work/$case.err" | head -3 >&2
        echo "FAIL: $case: the $device kernel did not build (fell back to ref)" >&2
        bad=1
        continue
    fi
    vertex_lines "../golden/$case.tsv" > "$work/$case.golden"
    vertex_lines "$work/$case.tsv" > "$work/$case.got"
    if ! cmp -s "$work/$case.golden" "$work/$case.got"; then
        echo "FAIL: $case: vertices differ from the golden (< golden, > $device):" >&2
        diff "$work/$case.golden" "$work/$case.got" | head -10 >&2
        bad=1
    fi
    # The whole file but its provenance equals --device ref's: the header's
    # certificate line too (its quadruple count follows the cover's decisions).
    [ "$device" = ref ] && continue
    if ! "$vorball" vertices --device ref "$input" -o "$work/$case.ref.tsv" 2> "$work/$case.ref.err" ||
       ! sans_provenance "$work/$case.ref.tsv" > "$work/$case.ref.full" ||
       ! sans_provenance "$work/$case.tsv" > "$work/$case.full" ||
       ! cmp -s "$work/$case.ref.full" "$work/$case.full"; then
        echo "FAIL: $case: the file differs from --device ref's (< ref, > $device):" >&2
        diff "$work/$case.ref.full" "$work/$case.full" | head -6 >&2
        bad=1
    fi
done
[ $bad -eq 0 ] || exit 1
echo "ok: backend $device matches every golden"
