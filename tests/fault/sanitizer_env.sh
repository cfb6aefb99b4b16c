#!/bin/sh
# The OpenCL path under ASan (issue 18, item 13): every test of a sanitizer
# build runs with ASan's alternate signal stack off (tests/CMakeLists.txt
# VB_TEST_ENV), without which ASan aborted when a PoCL worker thread exited
# on some hosts; vorball itself defaults to it (__asan_default_options in
# cli/main.c), so a run by hand is safe too. Checks both, then runs PoCL's
# threads through jfa and vertices on the CPU device.
# usage: sanitizer_env.sh VORBALL CORPUS_DIR
vorball=$1 corpus=$2
case ":$ASAN_OPTIONS:" in
*:use_sigaltstack=0:*) ;;
*) echo "FAIL: ASAN_OPTIONS='$ASAN_OPTIONS' lacks use_sigaltstack=0" >&2; exit 1 ;;
esac
# The binary's own default: ASan's help=1 lists each flag's current value.
opts=$(ASAN_OPTIONS=help=1 "$vorball" --version 2>&1 | grep -A1 '^[[:space:]]*use_sigaltstack$')
case $opts in
*"(Current Value: false)"*) ;;
*) echo "FAIL: vorball does not default to use_sigaltstack=0:" >&2
   echo "$opts" >&2; exit 1 ;;
esac
"$vorball" jfa -n 64 -k 20 -V jfa+1 --device cpu --check -o /dev/null || exit 1
"$vorball" vertices --device cpu "$corpus/inputs/cubic_lattice.xyzr" -o /dev/null || exit 1
echo "ok: ASan with use_sigaltstack=0 on the OpenCL path"
