/* The cover's group kernel run on host threads (cover_wg_emu.c). */
#ifndef COVER_WG_EMU_H
#define COVER_WG_EMU_H

#include "vb_cover_shared.h"

#define EMU_NB 8192u
#define EMU_LAB 32768u
#define EMU_Q 512u

/* Runs vbq_cover_wg as one work-group over the tasks (cells[k], roots[k]),
 * k < ncells, with the step budget `budget` per cell (0: none): outs[k] per
 * task, quadruples in qout (4 per quadruple, at most qout_cap), *nquads of
 * them. The patches it does not decide go to hand (hand_cap words,
 * vbq_hand_patch's entries; NULL: whole cells, VBQ_CLUSTER), hand_words[0]
 * the words they asked, hand_words[1] those written. 0, or -1 when the
 * threads could not be made. */
int vb_cover_wg_emulate(const vbq_env *e, const uint32_t *cells, const uint32_t *roots,
                        uint32_t ncells, uint32_t budget, vbq_cell_out *outs, uint32_t *qout,
                        uint32_t qout_cap, uint32_t *nquads, uint32_t *hand, uint32_t hand_cap,
                        uint32_t hand_words[2]);

#endif
