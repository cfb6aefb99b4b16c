#!/bin/sh
# The device's set-up overlapped with the cover's host work (issue 30): the
# device opens on its own thread while the cover builds its tree (and, with
# VORBALL_DEVICE_CERT=1, the certification filter) before it waits for it
# (core/cells/proposer_cover.c). Under the shim, clCreateContext sleeps
# 400 ms (VB_CLFAULT_SLOW), so the cover's work is done long before the
# device is known:
#   - set-up that then fails: W760 and the bytes of --device ref;
#   - set-up that is only slow: no warning, kernels on OpenCL, the bytes of
#     --device ref, and setup_s counts the whole set-up (>= 0.4 s) while
#     setup_wait_s (what the cover still waited for it) lies within
#     propose_s (a join that returns late can make it exceed setup_s).
# Each with the filter off and on.
# usage: slow_setup.sh VORBALL SHIM CORPUS_DIR WORK_DIR
vorball=$1 shim=$2 corpus=$3 work=$4/slow_setup
. "$(dirname "$0")/shim_env.sh"
in=$corpus/inputs/crambin_fragment.xyzr
# every cell to the device: on a loaded machine the host threads could
# otherwise take every cell before its first launch (no kernel would run)
export VORBALL_COVER_HOST_BACK=0
rm -f "$work/ref.tsv"
run 0 "$work/ref.err" "$vorball" vertices "$in" --device ref -o "$work/ref.tsv"
[ -s "$work/ref.tsv" ] || fail "--device ref wrote nothing"

# stat FILE NAME: the value of the --stats line NAME in FILE.
stat() {
    awk -F '\t' -v k="$2" '$1 == k { print $2 }' "$1"
}

for cert in 0 1; do
    rm -f "$work/v.tsv"
    run 0 "$work/fail.err" env VORBALL_DEVICE_CERT=$cert LD_PRELOAD="$shim" \
        VB_CLFAULT_SLOW=clCreateContext:400 VB_CLFAULT_FUNC=clCreateContext VB_CLFAULT_AT=1 \
        "$vorball" vertices "$in" --device cpu -o "$work/v.tsv"
    expect_line "$work/fail.err" '^clfault: clCreateContext call 1 fails'
    expect_line "$work/fail.err" 'W760: '
    cmp -s "$work/v.tsv" "$work/ref.tsv" ||
        fail "cert=$cert: a slow set-up that failed: output differs from --device ref"

    rm -f "$work/v.tsv" "$work/counts.txt"
    run 0 "$work/slow.err" env VORBALL_DEVICE_CERT=$cert LD_PRELOAD="$shim" \
        VB_CLFAULT_SLOW=clCreateContext:400 VB_CLFAULT_COUNTS="$work/counts.txt" \
        "$vorball" vertices "$in" --device cpu --stats -o "$work/v.tsv"
    if grep -Eq 'W[0-9]+: ' "$work/slow.err"; then
        cat "$work/slow.err" >&2
        fail "cert=$cert: a slow set-up warned"
    fi
    grep -q '^clEnqueueNDRangeKernel ' "$work/counts.txt" ||
        fail "cert=$cert: a slow set-up ran no kernel on OpenCL"
    cmp -s "$work/v.tsv" "$work/ref.tsv" ||
        fail "cert=$cert: a slow set-up: output differs from --device ref"
    setup=$(stat "$work/slow.err" setup_s) wait=$(stat "$work/slow.err" setup_wait_s)
    prop=$(stat "$work/slow.err" propose_s)
    [ -n "$setup" ] && [ -n "$prop" ] || { cat "$work/slow.err" >&2; fail "cert=$cert: no setup_s"; }
    wait=${wait:-0} # a zero is not printed
    awk -v s="$setup" -v w="$wait" -v p="$prop" 'BEGIN { exit !(s >= 0.4 && w >= 0 && w <= p) }' ||
        fail "cert=$cert: setup_s $setup, setup_wait_s $wait, propose_s $prop" \
            "(want setup_s >= 0.4, the wait within the proposer's call)"
done
echo "slow set-up: 4 runs, fallbacks and bytes as --device ref"
