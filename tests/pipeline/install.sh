#!/bin/sh
# The installed library as a program outside the tree sees it: `cmake
# --install` of the libvorball component into a scratch prefix, a client
# compiled against the installed headers with the flags of the installed
# vorball.pc (pkg-config), linked to the installed libvorball.so only, run
# on a corpus case: it must certify the golden number of vertices and
# verify all of them in memory. A second client runs channels through the
# public handle alone (vb_channels.h), one frame and every frame of a
# trajectory: its tables must be the command's bytes. A third runs `vorball
# jfa` through vb_jfa.h alone: its JSON must be the command's but the times.
# usage: install.sh BUILD_DIR CC CORPUS WORK_DIR [EXTRA_CFLAGS]
build=$1 cc=$2 corpus=$3 work=$4/install extra=$5
. "$(dirname "$0")/lib.sh"
rm -rf "$work" && mkdir -p "$work" || fail "cannot create $work"
cmake --install "$build" --prefix "$work/prefix" --component libvorball > "$work/install.log" 2>&1 ||
    { cat "$work/install.log" >&2; fail "cmake --install failed"; }
pc=$(find "$work/prefix" -name vorball.pc | head -n 1)
[ -n "$pc" ] || fail "no vorball.pc installed"
libdir=$(dirname "$(dirname "$pc")")
# The installed headers are vorball.h and what it includes, nothing more.
inc=$(dirname "$(find "$work/prefix" -name vorball.h | head -n 1)")
[ -f "$inc/vorball.h" ] || fail "no vorball.h installed"
reached=vorball.h todo=vorball.h
while [ -n "$todo" ]; do
    next=""
    for h in $todo; do
        [ -f "$inc/$h" ] || fail "$h (included by the public headers) is not installed"
        for d in $(sed -n 's/^#include "\(.*\)"$/\1/p' "$inc/$h"); do
            case " $reached " in *" $d "*) ;; *) reached="$reached $d" next="$next $d" ;; esac
        done
    done
    todo=$next
done
for f in "$inc"/*.h; do
    case " $reached " in *" $(basename "$f") "*) ;;
        *) fail "$(basename "$f") is installed but vorball.h does not include it" ;; esac
done
# The channel analysis's and the discrete Voronoi engine's internals
# (core/discrete's vbc_* and vbj_*) are not installed: channels and jfa
# runs are reached through vb_channels.h and vb_jfa.h.
for f in "$inc"/vbc_*.h "$inc"/vbj_*.h; do
    [ -e "$f" ] && fail "$(basename "$f") is installed: an internal header of core/discrete"
done
cflags=$(PKG_CONFIG_PATH=$(dirname "$pc") pkg-config --cflags vorball) || fail "pkg-config --cflags"
libs=$(PKG_CONFIG_PATH=$(dirname "$pc") pkg-config --libs vorball) || fail "pkg-config --libs"
# shellcheck disable=SC2086 # the flags are words
"$cc" -std=c11 -Wall -Wextra -Werror $extra $cflags "$(dirname "$0")/install_client.c" $libs \
    -Wl,-rpath,"$libdir" -o "$work/client" > "$work/cc.log" 2>&1 ||
    { cat "$work/cc.log" >&2; fail "the client does not compile against the installed headers"; }
case=cubic_lattice
"$work/client" "$corpus/inputs/$case.xyzr" > "$work/out.txt" 2> "$work/err.txt" ||
    { cat "$work/err.txt" >&2; fail "client failed"; }
n=$(vertex_lines "$corpus/golden/$case.tsv" | wc -l)
[ "$(cat "$work/out.txt")" = "$n $n" ] ||
    fail "client printed '$(cat "$work/out.txt")', expected '$n $n' (golden $case)"
# Nothing but the library's own dependencies: the client needs no static archive.
ldd "$work/client" | grep -q "$libdir/libvorball.so" || fail "client not linked to the installed libvorball"
# Channels through the installed public handle: the command's tables.
# shellcheck disable=SC2086 # the flags are words
"$cc" -std=c11 -Wall -Wextra -Werror $extra $cflags "$(dirname "$0")/install_channels.c" $libs \
    -Wl,-rpath,"$libdir" -o "$work/channels" > "$work/cc2.log" 2>&1 ||
    { cat "$work/cc2.log" >&2; fail "the channels client does not compile against the installed headers"; }
one=$corpus/data/1grm_single_hole2.pdb top=$corpus/data/ngl_md_ascii_trj.pdb xtc=$corpus/data/ngl_md_10frames.xtc
"$work/channels" one "$one" > "$work/one.csv" 2> "$work/one.err" ||
    { cat "$work/one.err" >&2; fail "channels client (one frame) failed"; }
"$build/cli/vorball" channels "$one" --grid 64 --device ref -o "$work/one_cmd.csv" 2> /dev/null ||
    fail "vorball channels (one frame) failed"
cmp -s "$work/one.csv" "$work/one_cmd.csv" || fail "channels client: one frame's table differs from the command's"
[ "$(cat "$work/one.err")" = "rows $(($(wc -l < "$work/one_cmd.csv") - 1))" ] ||
    fail "channels client: '$(cat "$work/one.err")' for $(($(wc -l < "$work/one_cmd.csv") - 1)) rows"
"$work/channels" frames "$top" "$xtc" > "$work/frames.csv" 2> "$work/frames.err" ||
    { cat "$work/frames.err" >&2; fail "channels client (frames) failed"; }
"$build/cli/vorball" channels "$top" --traj "$xtc" --grid 64 --device ref -o "$work/frames_cmd.csv" 2> /dev/null ||
    fail "vorball channels (frames) failed"
cmp -s "$work/frames.csv" "$work/frames_cmd.csv" || fail "channels client: the trajectory's table differs from the command's"
[ "$(cat "$work/frames.err")" = "frames 10" ] || fail "channels client: '$(cat "$work/frames.err")', expected 'frames 10'"
# jfa through the installed public handle: the command's JSON but the times.
# shellcheck disable=SC2086 # the flags are words
"$cc" -std=c11 -Wall -Wextra -Werror $extra $cflags "$(dirname "$0")/install_jfa.c" $libs \
    -Wl,-rpath,"$libdir" -o "$work/jfa" > "$work/cc3.log" 2>&1 ||
    { cat "$work/cc3.log" >&2; fail "the jfa client does not compile against the installed headers"; }
untimed() { sed -E 's/"(time_ms|time_ms_min|gpu_ms|fill_ms|prep_transfer_ms|prep_ms|exact_ms)": [0-9.e+-]+/"\1": T/g' "$1"; }
"$work/jfa" > "$work/jfa.json" 2> "$work/jfa.err" || { cat "$work/jfa.err" >&2; fail "jfa client failed"; }
"$build/cli/vorball" jfa -n 64 -k 50 --device ref -V all --check --json -o "$work/jfa_cmd.json" 2> /dev/null ||
    fail "vorball jfa failed"
[ "$(untimed "$work/jfa.json")" = "$(untimed "$work/jfa_cmd.json")" ] ||
    fail "jfa client: the JSON differs from the command's (times aside)"
[ "$(cat "$work/jfa.err")" = "runs 6 wrong 0
bad --size '32768'" ] || fail "jfa client: '$(cat "$work/jfa.err")'"
echo "ok: installed libvorball certified and verified $n vertices of $case; channels as the command"
