#!/bin/sh
# Early tracing through the command (VORBALL_ARCS_EARLY=1, off by default
# since stop 53): with the cover's quadruples certified in parts
# (VORBALL_COVER_PARTS=3), the parts' arcs traced while the proposer runs
# must give the closure's own bytes: the vertex file (less its '# tool'
# line), the --topology file and the '# arcs:' report equal to the run
# without it, on ref and PoCL; and the early path must be on in every run
# (an arc_early_parts line in --stats, where the default run has none) and
# have traced a part before the proposer returned in at least one of them
# (whether it does in a given run depends on timing: under load the cover
# may finish first, so one run alone would make the test flaky).
# usage: arcs_early.sh VORBALL CORPUS_DIR WORK_DIR
vorball=$1 corpus=$2 work=$3/arcs_early
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
fresh_dir "$work"
export VORBALL_COVER_PARTS=3
early_any=0
for in in crambin_fragment jittered_fcc; do
    for dev in ref cpu; do
        run 0 "late.err" "$vorball" vertices "$corpus/inputs/$in.xyzr" --device $dev --threads 2 \
            --topology late.top --stats -o late.tsv
        VORBALL_ARCS_EARLY=1 run 0 "early.err" "$vorball" vertices "$corpus/inputs/$in.xyzr" \
            --device $dev --threads 2 --topology early.top --stats -o early.tsv
        [ -z "$(stat arc_early_parts late.err)" ] || fail "$in $dev: early tracing ran by default"
        p=$(stat arc_early_parts early.err)
        [ -n "$p" ] || fail "$in $dev: VORBALL_ARCS_EARLY=1 left the early path off"
        [ "$p" -gt 0 ] && early_any=1
        [ "$(grep -v '^# tool' late.tsv)" = "$(grep -v '^# tool' early.tsv)" ] ||
            fail "$in $dev: early tracing changed the vertex file"
        [ "$(grep -v '^# tool' late.top)" = "$(grep -v '^# tool' early.top)" ] ||
            fail "$in $dev: early tracing changed the topology"
        grep -q '^# arcs: every arc closed' early.tsv || fail "$in $dev: no '# arcs:' report"
        echo "$in $dev: $p parts traced early, same bytes"
    done
done
[ $early_any = 1 ] || fail "VORBALL_ARCS_EARLY=1 traced no part early in any run"
echo "ok: early tracing (opt-in) writes the closure's bytes"
