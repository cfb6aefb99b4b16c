#!/usr/bin/env python3
"""CPU ms per frame of the channel analysis's stages, from `perf script` of a
cpu-clock recording with DWARF call graphs of `vorball channels`:

    perf record -F 5000 --call-graph dwarf,8192 -o p.data vorball channels ... --repeat R
    perf script -i p.data > p.txt
    analysis_stages.py p.txt 0.2 FRAMES*R      (0.2: the sample period in ms at 5000 Hz)

Each sample counts for the first stage function met walking its stack up
from the leaf (a sweep called by the openings counts as a sweep)."""
import re
import sys

STAGES = [
    ("sweeps", {"vbc_sweep", "vbc_sweep_to", "sweep_until", "radix_sweep", "heap_sweep", "heap_down",
                "heap_up", "rh_pop", "rh_push"}),
    ("openings", {"widest_through", "vbc_channel_openings", "kruskal_order", "through_pair", "wider_than",
                  "width_along", "vbc_channel_ends", "vbc_graph_support", "support_atoms"}),
    ("csr", {"link_slice", "vbc_voxels_link", "slab_mark", "slab_range", "slab_entries"}),
    ("components", {"vbc_components_given", "groups_connected", "vbc_components_group"}),
    ("voxel load", {"vbc_voxels_load"}),
    ("clearances", {"clear_slice", "clear_members"}),
    ("analysis other", {"vbc_analyse_paths"}),
]


def main():
    path, period_ms, nframes = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
    count = {s: 0 for s, _ in STAGES}
    total = 0
    stack = []

    def flush():
        nonlocal total
        if not stack:
            return
        total += 1
        for f in stack:
            for s, fs in STAGES:
                if f in fs:
                    count[s] += 1
                    return

    for line in open(path, errors="replace"):
        if not line.strip():
            flush()
            stack = []
            continue
        m = re.match(r"\s+[0-9a-f]+ (\S+)", line)
        if m:
            stack.append(re.sub(r"\+0x[0-9a-f]+$", "", m.group(1)).split(".")[0])
    flush()
    for s, _ in STAGES:
        print("%s\t%.2f" % (s, count[s] * period_ms / nframes))
    print("analysis\t%.2f" % (sum(count.values()) * period_ms / nframes))
    print("whole process\t%.2f" % (total * period_ms / nframes))


if __name__ == "__main__":
    main()
