#!/bin/sh
# `vorball vertices` and `vorball bench` as users run them: a missing device
# falls back to the reference backend with warning W760 and the same bytes;
# bench prints its table and JSON; --topology on a general-position set
# satisfies the edge count of a simple diagram (every vertex has four edges:
# 2 finite + infinite = 4 V); the thread count never changes the output;
# bad options are usage errors (exit 2).
# usage: vertices_cli.sh VORBALL WORK_DIR
vorball=$1 work=$2/vertices_cli
fail() { echo "FAIL: $*" >&2; exit 1; }
mkdir -p "$work" || fail "cannot create $work"
# 60 spheres, 3-decimal coordinates, mixed radii (deterministic).
awk 'BEGIN { s = 7; for (i = 0; i < 60; i++) {
        for (k = 0; k < 3; k++) { s = (s * 1103515245 + 12345) % 2147483648; c[k] = (s % 12000) / 1000 }
        s = (s * 1103515245 + 12345) % 2147483648
        printf "%.3f %.3f %.3f %.2f\n", c[0], c[1], c[2], 1.2 + (s % 7) / 10 } }' > "$work/set.xyzr"
"$vorball" vertices --device ref "$work/set.xyzr" > "$work/ref.tsv" 2> "$work/ref.err" ||
    fail "ref run failed: $(cat "$work/ref.err")"
n=$(grep -vc '^#' "$work/ref.tsv")
[ "$n" -gt 100 ] || fail "only $n vertices"
if ! "$vorball" devices 2>/dev/null | grep -q 'GPU'; then
    "$vorball" vertices --device gpu "$work/set.xyzr" > "$work/gpu.tsv" 2> "$work/gpu.err" ||
        fail "--device gpu without a GPU must fall back, not fail"
    grep -q 'W760' "$work/gpu.err" || fail "no W760 warning on fallback"
    cmp -s "$work/ref.tsv" "$work/gpu.tsv" || fail "fallback output differs from ref"
fi
# Matching (Sec. 5.4-5.5): of the 264 vertices the sampling sees, all but
# at most 2 are found from every one of their spheres once the targeted
# search has run (it solves the vertex's own triple when the shrinking
# cells never show all three colours).
"$vorball" vertices --device ref --proposer sampling --stats "$work/set.xyzr" > /dev/null 2> "$work/stats.err" ||
    fail "--stats run failed"
stat() { awk -v k="$1" '$1 == k { print $2 }' "$work/stats.err"; }
[ "$(stat sampled_vertices)" = 264 ] || fail "sampled_vertices $(stat sampled_vertices), expected 264"
[ "$(stat vertices_incomplete)" -le 2 ] || fail "vertices_incomplete $(stat vertices_incomplete) > 2"
[ "$(stat certified_vertices)" = "$n" ] || fail "certified_vertices $(stat certified_vertices) != $n"
# Host threads never change the bytes: --threads, VORBALL_THREADS, and the
# OpenCL CPU device (its set-up overlaps the culling) against ref.
for t in 1 3 7; do
    "$vorball" vertices --device ref --threads $t "$work/set.xyzr" > "$work/t$t.tsv" 2>/dev/null ||
        fail "--threads $t failed"
    cmp -s "$work/ref.tsv" "$work/t$t.tsv" || fail "--threads $t output differs"
done
VORBALL_THREADS=5 "$vorball" vertices --device auto "$work/set.xyzr" > "$work/env.tsv" 2>/dev/null ||
    fail "VORBALL_THREADS run failed"
cmp -s "$work/ref.tsv" "$work/env.tsv" || fail "VORBALL_THREADS=5 output differs"
# The crossover of --device auto (VB_HOST_BELOW_DEFAULT, 20,000 spheres):
# where the host shows a GPU, a small input runs on host threads and opens
# no device; without a GPU it stays on the CPU device (PoCL). VORBALL_HOST_BELOW=1
# (the tests' environment) always opens the device, a threshold at the input's
# size still does and one above it does not where there is a GPU; the same
# bytes each way.
backend_of() { grep '^backend' "$1" | cut -f2; }
spheres=$(grep -vc '^#' "$work/set.xyzr")
gpu=0   # the hint auto reads: a GPU driver's device node
ls /dev | grep -q '^kfd$\|^nvidia[0-9]' && gpu=1
for below in unset 1 "$spheres" $((spheres + 1)); do
    if [ "$below" = unset ]; then
        env -u VORBALL_HOST_BELOW "$vorball" vertices --stats "$work/set.xyzr" -o "$work/auto.tsv" \
            2> "$work/auto.err" || fail "auto run failed"
        want=device
        [ $gpu -eq 1 ] && want=ref
    else
        VORBALL_HOST_BELOW=$below "$vorball" vertices --stats "$work/set.xyzr" -o "$work/auto.tsv" \
            2> "$work/auto.err" || fail "auto run (VORBALL_HOST_BELOW=$below) failed"
        want=device
        [ "$below" -gt "$spheres" ] && [ $gpu -eq 1 ] && want=ref
    fi
    got=$(backend_of "$work/auto.err")
    if [ "$want" = ref ]; then
        [ "$got" = ref ] || fail "auto below the crossover ($below) ran on '$got', not host threads"
        ! grep -q W760 "$work/auto.err" || fail "auto below the crossover warned W760"
    else # the device, or the reference after W760 where no OpenCL device is usable
        [ "$got" = opencl ] || grep -q W760 "$work/auto.err" ||
            fail "auto above the crossover ($below) ran on '$got' without W760"
    fi
    cmp -s "$work/ref.tsv" "$work/auto.tsv" || fail "auto ($below) output differs from --device ref"
done
# The device opened ahead while the input is read (vb_vertices_open_early):
# a file whose size promises more than the crossover opens it; one that
# holds fewer spheres after all (comment lines) runs on host threads where
# there is a GPU (without one, on the opened CPU device) while that opening
# finishes beside it, and one that holds what it promised takes
# the opened device; the same bytes each way.
{ awk 'BEGIN { for (i = 0; i < 22000; i++) printf "# %s\n", sprintf("%0197d", 0) }'
  cat "$work/set.xyzr"; } > "$work/padded.xyzr"
env -u VORBALL_HOST_BELOW "$vorball" vertices --stats "$work/padded.xyzr" -o "$work/padded.tsv" \
    2> "$work/padded.err" || fail "padded run failed"
got=$(backend_of "$work/padded.err")
if [ $gpu -eq 1 ]; then
    [ "$got" = ref ] || fail "padded input (60 spheres) left host threads"
else # without a GPU auto stays the CPU device, opened ahead or not
    [ "$got" = opencl ] || grep -q W760 "$work/padded.err" ||
        fail "padded input without a GPU ran on '$got' without W760"
fi
grep -v '^# \(input\|options\)' "$work/padded.tsv" > "$work/padded.cmp"
grep -v '^# \(input\|options\)' "$work/ref.tsv" > "$work/ref.cmp"
cmp -s "$work/ref.cmp" "$work/padded.cmp" || fail "padded input's output differs from --device ref"
VORBALL_HOST_BELOW=1 "$vorball" vertices --stats "$work/padded.xyzr" -o "$work/padded.tsv" \
    2> "$work/padded.err" || fail "padded run (device) failed"
got=$(backend_of "$work/padded.err")
[ "$got" = opencl ] || grep -q W760 "$work/padded.err" ||
    fail "padded input with VORBALL_HOST_BELOW=1 ran on '$got' without W760"
grep -v '^# \(input\|options\)' "$work/padded.tsv" > "$work/padded.cmp"
cmp -s "$work/ref.cmp" "$work/padded.cmp" || fail "padded input on the device differs from --device ref"
# --stats ends with the whole process by stage (vb_stage_clock.h): every
# stage once, wall and CPU, the stages adding up to the totals (laps of one
# clock), the run's stage holding the run's own clock.
"$vorball" vertices --stats --device ref "$work/set.xyzr" -o "$work/st.tsv" 2> "$work/st.err" ||
    fail "--stats run failed"
awk -F'\t' '
    /^process_(read|validate|run|complete|write|free)_s\t/ { w += $2; nw++ }
    /^process_(read|validate|run|complete|write|free)_cpu_s\t/ { c += $2; nc++ }
    $1 == "process_total_s" { tw = $2 } $1 == "process_total_cpu_s" { tc = $2 }
    $1 == "process_run_s" { pr = $2 } $1 == "run_s" { r = $2 }
    END { d = w - tw; e = c - tc
          exit !(nw == 6 && nc == 6 && tw > 0 && d < 1e-5 && d > -1e-5 && e < 1e-5 && e > -1e-5 &&
                 r > 0 && pr >= r) }' "$work/st.err" ||
    fail "--stats process stages do not add up: $(grep '^process_\|^run_s' "$work/st.err" | tr '\n' ' ')"
# The program binary cache: written on the first OpenCL run, used by the
# next; a damaged binary falls back to the source build, same bytes. (On
# PoCL vorball keeps binaries other than cover.cl's only when
# VORBALL_PROGRAM_CACHE=1 asks.)
if "$vorball" devices 2>/dev/null | grep -q 'CPU'; then
    rm -rf "$work/cache"
    for k in 1 2 3; do
        VORBALL_PROGRAM_CACHE=1 XDG_CACHE_HOME="$work/cache" "$vorball" vertices --device cpu "$work/set.xyzr" \
            > "$work/cache$k.tsv" 2>/dev/null || fail "cached run $k failed"
        cmp -s "$work/ref.tsv" "$work/cache$k.tsv" || fail "cached run $k output differs"
        nbin=$(ls "$work/cache/vorball/" 2>/dev/null | grep -c '\.bin$')
        # The default proposer, the cover, builds one program (cover.cl).
        [ "$nbin" -eq 1 ] || fail "expected 1 cached program binary, found $nbin"
        [ $k -eq 2 ] && for b in "$work/cache/vorball/"*.bin; do echo damaged > "$b"; done
    done
fi
"$vorball" vertices --threads 0 "$work/set.xyzr" > /dev/null 2>&1
[ $? -eq 2 ] || fail "--threads 0 must be a usage error"
"$vorball" vertices --device ref --topology "$work/topo.tsv" "$work/set.xyzr" > /dev/null 2>&1 ||
    fail "--topology failed"
fin=$(awk '$1 == "edge" && $3 != -1' "$work/topo.tsv" | wc -l)
inf=$(awk '$1 == "edge" && $3 == -1' "$work/topo.tsv" | wc -l)
[ $((2 * fin + inf)) -eq $((4 * n)) ] || fail "edges: 2*$fin + $inf != 4*$n"
[ "$(grep -c '^face' "$work/topo.tsv")" -gt "$n" ] || fail "too few faces"
"$vorball" bench --device ref --samples 8,12 --json "$work/set.xyzr" > "$work/bench.json" ||
    fail "bench --json failed"
[ "$(grep -c '"vertices": '"$n"',' "$work/bench.json")" -eq 2 ] || fail "bench vertex counts"
grep -q '"certification":' "$work/bench.json" || fail "bench json lacks stage times"
"$vorball" bench --device ref "$work/set.xyzr" | grep -q '^set.xyzr .* 60 ' || fail "bench table row"
"$vorball" vertices --samples 1 "$work/set.xyzr" > /dev/null 2>&1
[ $? -eq 2 ] || fail "--samples 1 must be a usage error"
# The ranges are the library's (vb_propose_options_check): the message
# names each option's range, and a value inside it runs.
for bad in "--samples 4097:2..4096" "--tiles 3:power of two in 1..64" "--threads 65:1..64" \
           "--tol 0:positive"; do
    opt=${bad%%:*} why=${bad#*:}
    # shellcheck disable=SC2086
    msg=$("$vorball" vertices $opt "$work/set.xyzr" 2>&1 > /dev/null)
    [ $? -eq 2 ] || fail "$opt must be a usage error"
    case $msg in *E7:*"$why"*) ;; *) fail "$opt: no E7 naming '$why' in: $msg" ;; esac
done
"$vorball" vertices --device ref --samples 4096 --tiles 64 --threads 64 "$work/set.xyzr" > /dev/null ||
    fail "the ranges' ends must run"
"$vorball" vertices --device tpu "$work/set.xyzr" > /dev/null 2>&1
[ $? -eq 2 ] || fail "--device tpu must be a usage error"
echo "ok: $n vertices, $fin finite + $inf infinite edges"
