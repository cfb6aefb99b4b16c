#!/bin/sh
# Packs what strong_scaling.sh needs on a host with no build tools, no Open
# MPI and no package registry: CARRY/vorball (a -DVORBALL_WITH_MPI=ON build),
# CARRY/lib/ (its shared libraries outside glibc) and CARRY/openmpi/
# (carry_openmpi.sh). Then, on that host, from the repository root:
#   sh papers/mpi-scaling/strong_scaling.sh CARRY OUTDIR
# usage: sh papers/mpi-scaling/prepare_carry.sh BUILD_DIR CARRY
set -eu
build=$1 carry=$2
[ -x "$build/cli/vorball" ] || { echo "prepare_carry.sh: no $build/cli/vorball" >&2; exit 2; }
ldd "$build/cli/vorball" | grep -q libmpi ||
    { echo "prepare_carry.sh: $build is not an MPI build (-DVORBALL_WITH_MPI=ON)" >&2; exit 2; }
mkdir -p "$carry/lib"
cp "$build/cli/vorball" "$carry/"
ldd "$build/cli/vorball" | awk '$3 ~ /^\// { print $3 }' | while read -r lib; do
    case $(basename "$lib") in
        libc.so*|libm.so*|libdl.so*|libpthread.so*|librt.so*|ld-linux*|libresolv.so*) continue ;;
    esac
    cp -L "$lib" "$carry/lib/"
done
sh "$(dirname "$0")/carry_openmpi.sh" "$carry/openmpi"
echo "carry: $(du -sh "$carry" | cut -f1) in $carry"
