#!/bin/sh
# Out of memory said at once (issue 28, item 7: 2e6 spheres under a 4 GB
# limit ran 8 minutes before E4). `vertices` estimates what it needs before
# the work starts (core/cells/vertices_memory.c) and, under a limit that
# cannot hold it, stops within seconds with E140 (exit 44) saying how much
# is needed, how much is available and under which limit, writing nothing;
# under a comfortable limit it runs. ASan maps terabytes of shadow memory,
# which no ulimit -v admits: the sanitizer tree (SANITIZE=1) checks the
# estimate's unlimited run alone.
# usage: memory_limit.sh VORBALL WORK_DIR [SANITIZE]
vorball=$1 work=$2/memory_limit sanitize=${3:-0}
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
fresh_dir "$work"
out=$work/out.txt

# 2e5 random centres at the density of corpus/equal-radius/random-10000
# (box edge 64.633 per 10^4 spheres, radius 1.6): written in a second.
awk 'BEGIN { srand(28); n = 200000; e = 64.633 * (n / 10000) ^ (1 / 3);
             for (i = 0; i < n; i++)
                 printf "%.3f %.3f %.3f 1.6\n", rand() * e, rand() * e, rand() * e }' > big.xyzr
head -n 5000 big.xyzr > small.xyzr

if [ "$sanitize" = 1 ]; then
    run 0 "$out" "$vorball" vertices small.xyzr --device ref --threads 2 -o small.tsv
    [ "$(vertex_lines small.tsv | wc -l)" -gt 30000 ] || fail "small.xyzr: too few vertices"
    echo "ok: sanitizer tree: the unlimited run only (no ulimit -v under ASan)"
    exit 0
fi

# 400 MB of address space: the estimate for 2e5 cells is over 500 MB
# (about 370 MB touched, 150 MB of two threads' stacks and arenas); the
# run needs 460 MB resident (measured).
t0=$(date +%s)
(ulimit -v 400000 && exec "$vorball" vertices big.xyzr --device ref --threads 2 -o big.tsv) \
    > "$out" 2>&1
rc=$?
t1=$(date +%s)
[ "$rc" -eq 44 ] || { cat "$out" >&2; fail "under ulimit -v 400000: exit $rc, expected 44"; }
expect_line "$out" '^vorball: E140: big\.xyzr: 200000 spheres \(2[0-9]{5} cells\) need at least [0-9]+ MB for vertices, [0-9]+ MB available under ulimit -v \(RLIMIT_AS\): refused before starting$'
need=$(sed -n 's/.*need at least \([0-9]*\) MB.*/\1/p' "$out")
have=$(sed -n 's/.* \([0-9]*\) MB available.*/\1/p' "$out")
[ "$need" -gt "$have" ] || fail "refused, but $need MB needed is not over $have MB available"
[ "$have" -lt 410 ] || fail "$have MB said available under a 410 MB limit"
[ "$need" -ge 450 ] && [ "$need" -le 700 ] || fail "estimate $need MB for 2e5 spheres: outside 450-700"
[ $((t1 - t0)) -le 10 ] || fail "the refusal took $((t1 - t0)) s"
[ ! -e big.tsv ] || fail "a refused run left big.tsv"

# A comfortable limit: 5000 spheres (about 25 MB resident) under 1 GB.
(ulimit -v 1000000 && exec "$vorball" vertices small.xyzr --device ref --threads 2 -o small.tsv) \
    > "$out" 2>&1 || { cat "$out" >&2; fail "5000 spheres under ulimit -v 1000000 failed"; }
[ "$(vertex_lines small.tsv | wc -l)" -gt 30000 ] || fail "small.xyzr: too few vertices"
echo "ok: E140 in $((t1 - t0)) s ($need MB needed, $have MB available); 5000 spheres under 1 GB"
