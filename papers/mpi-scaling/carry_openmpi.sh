#!/bin/sh
# Copies this machine's Open MPI runtime (Debian's openmpi-bin 4.1, with its
# PMIx) into DEST, relocatable, for a host that has no Open MPI and no
# package registry (the lead's device machine): mpirun (orterun), orted, the
# libraries, the MCA plugins of one host (shared memory, TCP, the launcher),
# the help texts, and every shared library they need that is not part of
# glibc. `. DEST/env.sh` there sets OPAL_PREFIX, PMIX_INSTALL_PREFIX, PATH,
# LD_LIBRARY_PATH and MPIRUN; strong_scaling.sh does it when BUILD_DIR has
# an openmpi/ folder. Plugins of network stacks (UCX, libfabric, verbs, PSM)
# are left out: one host needs none of them.
# usage: sh papers/mpi-scaling/carry_openmpi.sh DEST   (e.g. CARRY_DIR/openmpi)
set -eu
dest=$1
ompi=/usr/lib/x86_64-linux-gnu/openmpi
pmix=/usr/lib/x86_64-linux-gnu/pmix2
[ -x /usr/bin/orterun ] && [ -d "$ompi/lib/openmpi3" ] || {
    echo "carry_openmpi.sh: no Debian Open MPI here (apt-get install openmpi-bin)" >&2; exit 2; }
mkdir -p "$dest/usr/bin" "$dest/usr/lib/x86_64-linux-gnu/openmpi/lib/openmpi3" "$dest/usr/share" \
    "$dest/pmix2/lib/pmix" "$dest/pmix2/share" "$dest/lib"
cp /usr/bin/orterun /usr/bin/orted "$dest/usr/bin/"
cp -a "$ompi"/lib/*.so* "$dest/usr/lib/x86_64-linux-gnu/openmpi/lib/" 2> /dev/null || true
for p in "$ompi"/lib/openmpi3/*.so; do
    case $(basename "$p") in
        *ucx*|*ofi*|*openib*|*psm*|*verbs*|*java*) continue ;;
    esac
    cp "$p" "$dest/usr/lib/x86_64-linux-gnu/openmpi/lib/openmpi3/"
done
cp -a /usr/share/openmpi "$dest/usr/share/"
cp "$pmix"/lib/pmix/*.so "$dest/pmix2/lib/pmix/"
cp -a "$pmix/share/pmix" "$dest/pmix2/share/"
# The shared libraries of all of that, glibc's own left to the host.
for f in "$dest"/usr/bin/* "$dest"/usr/lib/x86_64-linux-gnu/openmpi/lib/openmpi3/*.so \
         "$dest"/pmix2/lib/pmix/*.so /usr/lib/x86_64-linux-gnu/libmpi.so.40; do
    ldd "$f" 2> /dev/null | awk '$3 ~ /^\// { print $3 }'
done | sort -u | while read -r lib; do
    case $(basename "$lib") in
        libc.so*|libm.so*|libdl.so*|libpthread.so*|librt.so*|ld-linux*|libresolv.so*) continue ;;
    esac
    cp -L "$lib" "$dest/lib/"
done
cat > "$dest/env.sh" <<'ENV'
# Sourced to run the carried Open MPI: ompi_dir=/path/to/openmpi . /path/to/openmpi/env.sh
export OPAL_PREFIX="$ompi_dir/usr"
export PMIX_INSTALL_PREFIX="$ompi_dir/pmix2"
export PATH="$ompi_dir/usr/bin:$PATH"
export LD_LIBRARY_PATH="$ompi_dir/lib:$ompi_dir/usr/lib/x86_64-linux-gnu/openmpi/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export OMPI_MCA_mca_base_component_show_load_errors=0
MPIRUN="$ompi_dir/usr/bin/orterun"
ENV
echo "carried Open MPI: $(du -sh "$dest" | cut -f1) in $dest"
