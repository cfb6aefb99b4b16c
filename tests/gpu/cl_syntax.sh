#!/bin/sh
# Every OpenCL kernel as a GPU compiles it: OpenCL C 1.2, the options the
# drivers pass, checked by clang's OpenCL front end (-fsyntax-only). PoCL
# builds only the CPU forms and the C emulation has no address spaces, so a
# GPU-only form (VBQ_GPU_FORM, a __local pointer passed where OpenCL 1.2
# has no generic one) would otherwise first fail on a GPU, where the run
# falls back to the host with W760 (stop 49: cover_wg.cl's budget hand-off).
# usage: cl_syntax.sh SRC_DIR [CLANG]   (exit 77: no clang, skipped)
src=$1 clang=${2:-}
[ -n "$clang" ] || clang=$(command -v clang-14 || command -v clang || true)
[ -n "$clang" ] || { echo "cl_syntax: no clang: skipped"; exit 77; }
inc="-I $src/gpu -I $src/core -I $src/core/cells -I $src/core/discrete"
fail=0 n=0
check() { # file, options
    f=$1; shift
    n=$((n + 1))
    if ! out=$("$clang" -x cl -cl-std=CL1.2 -fsyntax-only -Xclang -finclude-default-header \
                $inc "$@" "$src/gpu/$f" 2>&1); then
        echo "cl_syntax: $f $*: FAILED"; echo "$out" | grep -E "error" | head -5
        fail=1
    fi
}
for k in "$src"/gpu/*.cl; do
    case $(basename "$k") in jfa.cl) continue ;; esac   # built with its block sizes, below
    check "$(basename "$k")"
done
# the option sets the drivers build with (gpu/cover_ocl.c, gpu/jfa.c)
check cover_wg.cl -DVBQ_HANDOFF
check cover_wg.cl -DVBQ_HANDOFF -DVBQ_HOST_FORM
check cover.cl -DVBQ_WALK_V4_CL
check cover.cl -DVBQ_WALK_V4_CL -DVBQ_CACHES_CL
for o in "" "-DVBJ_LABEL16" "-DVBJ_DIST64" "-DVBJ_DISTF" "-DVBJ_LABEL16 -DVBJ_DIST64"; do
    # shellcheck disable=SC2086
    check jfa.cl $o -DVBJ_BX=8 -DVBJ_BY=8 -DVBJ_BZ=4 -DVBJ_BY2=16
done
[ $fail -eq 0 ] && echo "cl_syntax: $n builds pass"
exit $fail
