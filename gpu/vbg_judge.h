/* The certification filter on an OpenCL device (gpu/cert_filter.cl behind
 * vb_cover_backend.judge): the spheres and their grid uploaded once per
 * filter, then a launch per list of quadruples on a queue of its own. */
#ifndef VBG_JUDGE_H
#define VBG_JUDGE_H

#include "vb_cert_filter.h"
#include "vb_cover.h"
#include "vbg_runtime.h"

typedef struct vbg_judge vbg_judge;

/* Builds the filter's program on rt's device (borrowed: it must outlive the
 * judge) and opens a queue for it. VB_OK, VB_ENOMEM, or VB_EDEVICE with the
 * reason (the build log) in ctx. Close with vbg_judge_close. */
int vbg_judge_open(vb_ctx *ctx, vbg_runtime *rt, vbg_judge **out);

/* The most bytes of device buffers the judge held at once (0 for NULL). */
size_t vbg_judge_bytes_peak(const vbg_judge *j);

/* Frees the judge and its device buffers; NULL is allowed. */
void vbg_judge_close(vbg_judge *j);

/* verdict[k] = vbd_judge of q[k] over f (f->ok), k < n, on the device:
 * f's arrays are uploaded when f->serial differs from the last one's.
 * Blocks until the verdicts are read back. VB_OK, VB_ENOMEM, VB_EDEVICE. */
int vbg_judge_run(vb_ctx *ctx, vbg_judge *j, const vb_cert_filter *f, const uint32_t (*q)[4],
                  size_t n, uint8_t *verdict);

/* Gives the cover backend be its judge (vb_cover_backend.judge, freed by
 * vb_cover_backend_close through judge_close) on rt's device: on a GPU, or
 * on any device with VORBALL_DEVICE_CERT=1 (vb_cert_filter_mode). Its
 * program is built here, on the thread that opens the cover, as the
 * runtime's program cache requires; a failure is kept and reported by each
 * judge call (W767 from the proposer), and the cover goes on. Never fails. */
void vbg_judge_attach(vb_ctx *ctx, vbg_runtime *rt, vb_cover_backend *be);

#endif
