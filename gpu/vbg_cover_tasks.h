/* A cell covered again as root-patch tasks (gpu/cover_tasks.c): the split
 * that the OpenCL driver uses for the cells its first launch left (arenas
 * run out, or the group kernel's step budget passed) and the join of the
 * tasks' results back into one result per cell. Plain C, no OpenCL: the
 * group kernel's emulation in tests/gpu uses the same two steps. */
#ifndef VBG_COVER_TASKS_H
#define VBG_COVER_TASKS_H

#include <stddef.h>
#include <stdint.h>

#include "vb_cover_shared.h"

/* Which cells a pass takes: 1 for a status to cover again. */
typedef int (*vbg_task_pick)(uint32_t status);

/* Tasks per cell with T root squares per face side, split `split` levels
 * below the 6 T^2 root patches: 1, one per child, 24 T^2 (VBQ_TASK); 2 (any
 * other value), one per grandchild, 96 T^2 (VBQ_TASK2). */
size_t vbg_tasks_per_cell(uint32_t T, unsigned split);

/* Writes the tasks of every cell k < ncells whose out[k].status pick
 * takes, in cell order, per = vbg_tasks_per_cell(T, split) tasks each:
 * cells2[j] = cells[k], roots2[j] = VBQ_TASK(root, child) (split 1) or
 * VBQ_TASK2(root, child, grandchild). cells2 and roots2 hold per * (the
 * cells picked); returns the count of tasks written. */
size_t vbg_tasks_make(const uint32_t *cells, const vbq_cell_out *out, size_t ncells,
                      vbg_task_pick pick, size_t per, unsigned split, uint32_t *cells2,
                      uint32_t *roots2);

/* Quadruples the tasks' results t[0 .. ntasks) hold in all: room that
 * vbg_tasks_join may append. */
size_t vbg_tasks_quads(const vbq_cell_out *t, size_t ntasks);

/* Joins the results t of the tasks vbg_tasks_make wrote for out (same
 * ncells, pick, per, and out unchanged since): each picked cell gets the
 * status of its last task that failed, else VBQ_OK with the tasks'
 * counters summed (maxlev their largest) and their quadruples, read from
 * q + 4 t[j].qoff, copied one task after the other to q + 4 *nq (its qoff;
 * *nq grows by their count). q must have room for vbg_tasks_quads(t, ...)
 * more quadruples past *nq, and every t[j].qoff + t[j].nq <= *nq on entry.
 * Repeats between tasks are kept (the cover's driver drops them). Returns
 * the count of cells picked. */
size_t vbg_tasks_join(const vbq_cell_out *t, vbq_cell_out *out, size_t ncells, vbg_task_pick pick,
                      size_t per, uint32_t *q, size_t *nq);

/* The cells of out[0 .. ncells) that pick takes, costliest first: their
 * indices in order[] (room for ncells), by the patches their first launch
 * walked before it stopped (out[c].patches), most first, ties in index
 * order. A launch of tasks lasts as long as its slowest slice, and its
 * slices take tasks in order: a cell that walked far before it ran out
 * tends to have the longest tasks, which then start first (the capsid's
 * 288 cells past the fitted arenas, host covers: results/kern52_stop52.md).
 * Returns the count, or SIZE_MAX when out of memory. */
size_t vbg_tasks_order(const vbq_cell_out *out, size_t ncells, vbg_task_pick pick,
                       uint32_t *order);

/* Tiers of at most VBG_ORDER_CELLS picked cells run costliest first
 * (vbg_tasks_ordered). Measured on an H100 (stop 52, run 1b, three rounds,
 * papers/gpu-voronoi-cells-of-spheres/results/h100_stop52.txt): the capsid's large tier, 288 cells, 0.0836-
 * 0.0840 s costliest first against 0.0923-0.0940 in cell order; the
 * 211,440-atom tiling's, 2,260 cells, 0.390-0.391 s against 0.373-0.375
 * (there the tail is a small share and cell order keeps neighbouring cells'
 * data together). */
#define VBG_ORDER_CELLS 1024u

/* Whether a tier of np picked cells runs its tasks costliest first:
 * order 0 never (VORBALL_COVER_TASK_ORDER=0), 2 always (=2), 1 where np <=
 * VBG_ORDER_CELLS (the default). */
int vbg_tasks_ordered(int order, size_t np);

#endif
