#!/bin/sh
# A tie cluster the host's exact rank refutes is decided at once (stop 53,
# issue 30): the doubles call the list of a jittered crystal's split cube
# centre flat, the exact rank says it is not, and until stop 53 the host
# subdivided the patch on, its list unchanged, until a child one level down
# was decided as a stalled chain (sc 4,096 jittered 1e-12: 291k patches
# popped by the host's resume of 26k handed ones, 47k after). The envelope
# decision (core/cells/cover_envelope.c) is exact and complete on any closed
# patch of equal radii, so it is now taken on the refuted patch itself.
#
# Counts, not times (--stats; the same on every machine and thread count):
# the corpus's sc 64 jittered 1e-12 (each cube centre split five or six
# ways) covered in at most 17,100 patches writing at most 788 quadruples
# (18,756 and 806 when refuted clusters subdivide), on ref and on PoCL (the
# kernel hands such a patch, the host resumes it), and the same vertices as
# each other and as the golden's count (312).
# usage: refuted_cluster.sh VORBALL CORPUS_DIR WORK_DIR
vorball=$1 corpus=$2 work=$3/refuted_cluster
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
fresh_dir "$work"
export VORBALL_COVER_HOST_BACK=0
for dev in ref cpu; do
    run 0 "$dev.err" "$vorball" vertices "$corpus/inputs/sc_jitter12.xyzr" --device $dev \
        --threads 2 --stats -o "$dev.tsv"
    p=$(stat cover_patches "$dev.err") q=$(stat cover_quadruples "$dev.err")
    echo "$dev: patches $p, quadruples $q, vertices $(vertex_lines "$dev.tsv" | wc -l)"
    [ -n "$p" ] && [ "$p" -le 17100 ] || fail "$dev: $p patches (at most 17,100): refuted clusters subdivided?"
    [ -n "$q" ] && [ "$q" -le 788 ] || fail "$dev: $q quadruples (at most 788)"
    [ "$(vertex_lines "$dev.tsv" | wc -l)" -eq 312 ] || fail "$dev: not the golden's 312 vertices"
done
[ "$(vertex_lines cpu.tsv)" = "$(vertex_lines ref.tsv)" ] || fail "PoCL and ref wrote other vertices"
echo "ok: refuted tie clusters decided at once"
