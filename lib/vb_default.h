/* The library with its default backends wired: the OpenCL device layer of
 * gpu/ (a GPU, else PoCL, else the plain-C twins) and the exact certifier
 * of verify/, for callers that want the pipelines as the command runs them
 * (the command itself, a binding).
 *
 * Why here: core/ must not include gpu/ or verify/ (its drivers take them
 * through tables), and gpu/ and verify/ never touch each other, so the one
 * place that names all three is above them: the front door (lib/), whose
 * target vb_default the command and the bindings link as peers. */
#ifndef VB_DEFAULT_H
#define VB_DEFAULT_H

#include <stdio.h>

#include "vb_vertices.h"

/* The default tables: devices = gpu/'s vbg_device_layer, certifier =
 * verify/'s vb_exact_certifier. Static; never NULL. */
const vb_vertices_backends *vb_default_backends(void);

/* The device layer alone, for the discrete pipelines (vbj_backend_open,
 * vbc_pipe_open). */
const vb_device_layer *vb_default_devices(void);

/* vb_vertices_run with the default backends. */
int vb_vertices_run_default(vb_ctx *ctx, const vb_sphere_set *set, const vb_vertices_config *cfg,
                            vb_vertices_result *res);

/* The table of `vorball devices`: every OpenCL platform and device, one
 * tab-separated line each, then "#auto<TAB>" and the device that --device
 * auto takes (or "reference backend (why)" when none can be used). VB_OK
 * or vbg_list_devices' error; a failed write is the caller's to find
 * (ferror, as for any output file). */
int vb_devices_write(vb_ctx *ctx, FILE *f);

/* The line `vorball --version` gives the device --device auto takes:
 * "device (--device auto): GPU|CPU NAME (versions)", or the reference
 * backend and why no OpenCL device, with a newline. Cannot fail. */
void vb_devices_write_auto(vb_ctx *ctx, FILE *f);

#endif
