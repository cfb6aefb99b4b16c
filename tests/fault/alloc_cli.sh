#!/bin/sh
# Allocation failures (issue 28, as SQLite's malloc fault tests): COMMAND
# runs under vorball_allocfault (alloc_fault.c: the n-th allocation of
# vorball's own code fails). A counting pass finds how many allocations the
# command makes; then every n from 1 to that count (and one past it; or
# every STRIDE-th of them, the first and the last always) fails once, and, from the first, a middle and the last, every later one fails
# too (the memory stays short). Each run must end either in success, with
# the bytes of the counting pass, or in a clean numbered error: a
# `vorball: E<n>:` line whose exit status is E<n>'s in core/vb_diag.h, no
# signal, no sanitizer report (the sanitizer tree: leaks of every failure
# path), and no output file left behind.
# usage: alloc_cli.sh VORBALL_ALLOCFAULT SOURCE_DIR WORK_DIR
#          vertices|vertices_arcs|vertices_threads|vertices_periodic|verify_arcs|channels|
#          channels_frames|jfa
#          [STRIDE]
vorball=$1 src=$2 cmd=$4 work=$3/alloc_$4 stride=${5:-1}
corpus=$src/corpus
here=$(cd "$(dirname "$0")" && pwd)
. "$here/../pipeline/lib.sh"
fresh_dir "$work"
in=$corpus/inputs/degree5_vertex.xyzr
case $cmd in
vertices)
    outs="v.tsv"
    set -- vertices "$in" --device ref --threads 1 -o v.tsv ;;
vertices_arcs)
    # Arc closure and the exact topology behind the cover.
    outs="v.tsv t.txt"
    set -- vertices "$corpus/inputs/crambin_fragment.xyzr" --device ref --threads 1 --arcs \
        --topology t.txt -o v.tsv ;;
vertices_threads)
    # The cover's and the certifier's worker threads (the count of
    # allocations varies by one or two from run to run).
    outs="v.tsv"
    set -- vertices "$corpus/equal-radius/random-100.xyzr" --device ref --threads 2 -o v.tsv ;;
vertices_periodic)
    # Periodic boxes (issue 34): images, the cover on the atoms' cells,
    # canonical translates, the periodic writer.
    printf '0.1 0.2 0.3 1.2\n2.1 2.2 0.3 1.2\n2.1 0.2 2.3 1.2\n0.1 2.2 2.3 1.2\n' > fcc1.xyzr
    outs="p.tsv"
    set -- vertices fcc1.xyzr --box 4 4 4 --device ref --threads 1 -o p.tsv ;;
verify_arcs)
    "$vorball" vertices "$in" --device ref --threads 1 -o given.tsv > /dev/null 2>&1 ||
        fail "vertices for verify failed"
    outs="r.txt"
    set -- verify "$in" given.tsv --arcs --threads 1 -o r.txt ;;
channels)
    outs="c.csv c.pdb"
    set -- channels --grid 32 "$corpus/data/1grm_single_hole2.pdb" --device ref -o c.csv \
        --centerlines c.pdb ;;
channels_frames)
    # Frames in flight (issue 33): the fetcher, the reader, 3 frames in
    # analysis on threads of their own (the count varies by a few from run
    # to run), their held lines.
    export VORBALL_FRAMES_IN_FLIGHT=3 VORBALL_FRAMES_AHEAD=2
    outs="c.csv c.pdb"
    set -- channels --grid 32 "$corpus/data/ngl_md_ascii_trj.pdb" --traj "$corpus/data/ngl_md_10frames.xtc" \
        --frames 0:4 --device ref -o c.csv --centerlines c.pdb ;;
jfa)
    outs="j.png"
    set -- jfa -n 64 -k 20 -V jfa+1,facet --check --device ref --png j.png -o /dev/null ;;
*) fail "unknown command $cmd" ;;
esac
# E number -> exit status, from the catalogue.
sed -n 's/^ *X(E, *\([0-9]*\), *[A-Z_0-9]*, *\([0-9]*\),.*/\1 \2/p' "$src/core/vb_diag.h" > exits.txt
[ -s exits.txt ] || fail "no E entries read from vb_diag.h"

clean() { for o in $outs; do rm -f "$o"; done; }

clean
VB_FAIL_ALLOC_COUNTS=counts.txt "$vorball" "$@" > count.err 2>&1 ||
    { cat count.err >&2; fail "the counting pass failed"; }
for o in $outs; do
    [ -s "$o" ] || fail "the counting pass wrote no $o"
    mv "$o" "ref.$o"
done
total=$(sed -n 's/^allocations //p' counts.txt)
[ "${total:-0}" -gt 0 ] || fail "no allocation counted (not wrapped?)"

runs=0 bad=0 errors=0
# check WHAT: judges the last run (exit in $rc, stderr in run.err).
check() {
    runs=$((runs + 1))
    why=""
    if grep -q 'Sanitizer\|runtime error:' run.err; then
        why="sanitizer report"
    elif [ "$rc" -gt 125 ]; then
        why="exit $rc (signal or abort)"
    elif [ "$rc" -eq 0 ]; then
        for o in $outs; do
            cmp -s "$o" "ref.$o" || why="$why $o differs"
        done
    else
        errors=$((errors + 1))
        num=$(sed -n 's/^vorball[a-z ]*: E\([0-9]*\): .*/\1/p' run.err | head -n 1)
        want=$(awk -v n="$num" '$1 == n { print $2 }' exits.txt)
        if [ -z "$num" ]; then
            why="exit $rc without a 'vorball: E<n>:' line"
        elif [ "$want" != "$rc" ]; then
            why="E$num with exit $rc (the catalogue says ${want:-none})"
        fi
        for o in $outs; do
            [ ! -e "$o" ] || why="$why, $o left behind"
        done
    fi
    if [ -n "$why" ]; then
        sed 's/^/    /' run.err | head -n 20 >&2
        echo "FAIL: $cmd: $1: $why" >&2
        bad=$((bad + 1))
    fi
}

n=1
while [ $n -le $((total + 1)) ]; do
    clean
    VB_FAIL_ALLOC_AT=$n "$vorball" "$@" > run.err 2>&1
    rc=$?
    check "allocation $n of $total fails"
    if [ $n -le "$total" ] && [ $((n + stride)) -gt "$total" ]; then
        n=$total # the last allocation, whatever the stride
    fi
    n=$((n + stride))
done
for n in $(printf '%s\n' 1 $(((total + 1) / 2)) "$total" | sort -un); do
    clean
    VB_FAIL_ALLOC_AT=$n VB_FAIL_ALLOC_STICKY=1 "$vorball" "$@" > run.err 2>&1
    rc=$?
    check "allocations $n.. of $total fail"
done
clean
[ $bad -eq 0 ] || fail "$cmd: $bad of $runs runs with failed allocations did not end cleanly"
echo "ok: $cmd: $runs runs ($total allocations counted), $errors clean errors, the rest the same bytes"
