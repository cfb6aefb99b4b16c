#!/bin/sh
# PoCL's hand-off keeps the kernel's work (stop 47): a CPU device's
# work-item kernel hands a patch it does not decide (a tie cluster, an
# envelope past its double filter or undecided by it) to the host with the
# patch's list and goes on with its cell; the host covers that patch alone
# (core/cells/cover_resume.c). Until stop 47 it handed the whole cell, and
# the host covered it again from its roots, the kernel's work on it lost
# (EXTREMESET Congruent 300: 266 of 300 cells).
#
# Counters, not times (--stats, --device cpu against --device ref):
# - cover_host_cells 0: no cell is covered whole again on the host (each of
#   these inputs hands patches: 6-24 cells went to the host before);
# - cover_resumed_patches > 0: the patches were handed and resumed;
# - cover_patches equal to ref's: the kernel's patches and the resumed ones
#   are the host's own, each counted once (a patch resumed twice, or the
#   kernel's share of a handed cell counted with a whole host cover, would
#   show);
# - the vertex rows equal to ref's;
# - the same with the handed patches resumed by the host threads
#   (VORBALL_COVER_RESUME_SPREAD=1, a GPU's default) instead of the device's.
# The inputs: the exact sc and fcc blocks (tie clusters), 1,000 random equal
# balls (envelopes of more than 32 owned labels) and sc jittered 1e-12
# (envelopes the double filter leaves undecided).
# usage: handoff_resume.sh VORBALL CORPUS_DIR WORK_DIR
vorball=$1 corpus=$2 work=$3/handoff_resume
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
fresh_dir "$work"
# Every cell to the device (VORBALL_COVER_HOST_BACK=0; --device ref has no
# device and ignores it): otherwise the host threads take cells from the
# back of the queue beside the kernel, and which cells the kernel covers,
# so how many patches it hands, depends on the timing (corpus fcc on the idle
# 2-core machine: 0 to 168 resumed patches, the rows the same).
export VORBALL_COVER_HOST_BACK=0
for in in equal-radius/sc equal-radius/fcc equal-radius/random-1000 inputs/sc_jitter12; do
    name=$(basename "$in")
    for dev in ref cpu; do
        run 0 "$name.$dev.err" "$vorball" vertices "$corpus/$in.xyzr" --device $dev --threads 2 \
            --stats -o "$name.$dev.tsv"
    done
    host=$(stat cover_host_cells "$name.cpu.err") res=$(stat cover_resumed_patches "$name.cpu.err")
    pr=$(stat cover_patches "$name.ref.err") pc=$(stat cover_patches "$name.cpu.err")
    echo "$name: cells covered whole on the host $host, patches resumed $res, patches $pc (ref $pr)"
    [ "$host" = 0 ] || fail "$name: $host cells handed whole to the host"
    [ -n "$res" ] && [ "$res" -gt 0 ] || fail "$name: no patch resumed ('$res')"
    [ "$pc" = "$pr" ] || fail "$name: $pc patches on PoCL, $pr on ref"
    [ "$(vertex_lines "$name.cpu.tsv")" = "$(vertex_lines "$name.ref.tsv")" ] ||
        fail "$name: PoCL wrote other vertices"
    VORBALL_COVER_RESUME_SPREAD=1 run 0 "$name.spread.err" "$vorball" vertices "$corpus/$in.xyzr" \
        --device cpu --threads 2 --stats -o "$name.spread.tsv"
    [ "$(stat cover_resumed_patches "$name.spread.err")" = "$res" ] ||
        fail "$name: resumed by the host threads: other patches"
    [ "$(stat cover_patches "$name.spread.err")" = "$pr" ] ||
        fail "$name: resumed by the host threads: other patch count"
    [ "$(vertex_lines "$name.spread.tsv")" = "$(vertex_lines "$name.ref.tsv")" ] ||
        fail "$name: resumed by the host threads: other vertices"
done
echo "ok: handed patches resumed alone, no cell covered again"
