/* The OpenCL backend of the JFA module (gpu/jfa*.c behind vbj_backend). */
#ifndef VBG_JFA_H
#define VBG_JFA_H

#include "vbg_runtime.h"
#include "vbj_jfa.h"

/* Opens the backend on a runtime (borrowed: close it after the backend).
 * VB_EDEVICE with the build log in the context when a kernel does not
 * build; VB_ENOMEM. Close with vbj_backend_close. */
int vbg_jfa_open(vb_ctx *ctx, vbg_runtime *rt, vbj_backend **out);

#endif
