#!/usr/bin/env python3
"""CPU ms per frame of every host stage of `vorball channels` (issue 33), from
`perf script` of a cpu-clock recording with DWARF call graphs:

    perf record -F 4000 --call-graph dwarf,32768 -o p.data vorball channels ... --repeat R
    perf script -i p.data > p.txt
    latency_stages.py p.txt 0.25 RUNS FRAMES     (0.25: the sample period in ms at 4000 Hz)

A sample counts for the first stage function met walking its stack up from
the leaf (the pore's steps before the pore stage itself). RUNS = frames x R
divides the stages run per run; FRAMES divides reading (once per frame) and
the first frame's opening. Each line: stage, CPU ms, its four largest leaf
functions. Needs python3 (standard library)."""
import re, sys, collections
STAGES = [  # innermost first
    ("pore.verdict", {"vbc_pore_judge", "judge_plane", "vbc_pore_judge_on"}),
    ("pore.sweep", {"vbc_pore_find", "pore_find"}),
    ("pore.refine", {"vbc_refine_bottlenecks", "refine_channel"}),
    ("pore.cells", {"vbc_cells_build"}),
    ("pore.lining", {"vbc_result_add_pore", "vbc_rank"}),
    ("pore.other", {"vbc_pore_stage"}),
    ("analysis", {"vbc_frame_components", "vbc_analyse_paths", "comp_worker"}),
    ("jfa", {"vbj_tiles_ref_run", "vbj_ref_exact_need", "tile"}),
    ("masks", {"vbc_frame_masks", "vbc_masks_shape", "atomic_mask"}),
    ("read.traj", {"next_traj", "vb_frame_source_next", "fetch"}),
    ("read.first", {"open_traj", "vb_frame_source_open"}),
    ("validate", {"vbi_spheres_validate"}),
]
# Leaves whose stack did not unwind (no stage above them) that only a stage calls.
LOST = [
    ("pore.unwound", {"vbc_cells_nearest_among", "ascend", "clearance_near", "near_min", "min_norm_point"}),
    ("analysis", {"vbc_radix_sort", "radix_sweep", "link_slice"}),
]
path, period_ms, nruns = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
nframes = float(sys.argv[4]) if len(sys.argv) > 4 else nruns
ONCE = {"read.traj", "read.first", "validate"}
cnt = collections.Counter(); leaf = collections.defaultdict(collections.Counter); total = 0; stack = []
def flush():
    global total
    if not stack: return
    total += 1
    for f in stack:
        for s, fs in STAGES:
            if f in fs:
                cnt[s] += 1; leaf[s][stack[0]] += 1; return
    for s, fs in LOST:
        if stack[0] in fs:
            cnt[s] += 1; leaf[s][stack[0]] += 1; return
    cnt["other"] += 1; leaf["other"][stack[0]] += 1
for line in open(path, errors="replace"):
    if not line.strip():
        flush(); stack = []; continue
    m = re.match(r"\s+[0-9a-f]+ (\S+)", line)
    if m: stack.append(re.sub(r"\+0x[0-9a-f]+$", "", m.group(1)).split(".")[0])
flush()
for s in [s for s, _ in STAGES] + ["pore.unwound", "other"]:
    n = nframes if s in ONCE else nruns
    top = ", ".join("%s %.2f" % (f, c * period_ms / n) for f, c in leaf[s].most_common(4))
    print("%s\t%.2f\t%s" % (s, cnt[s] * period_ms / n, top))
print("whole/run\t%.2f" % (total * period_ms / nruns))
