/* The channel frame pipeline: atoms -> discrete Voronoi labels -> masks ->
 * the compact list of channel voxels, behind one engine table whatever runs
 * it: OpenCL (gpu/channel_gpu.c, the device layer's channels_open) or the
 * plain-C reference (the JFA reference, vbc_masks_ref, vbc_flags_compact;
 * clearances left to the host analysis). Both give the same channel voxel
 * set, so the same tables and centrelines.
 *
 * The pipe opens the engine by the device layer's one fallback rule
 * (vb_device.h) and drops a device that fails in the middle of a run:
 *   W804  no usable OpenCL device: the reference backend runs every frame
 *   W806  OpenCL failed during a frame: that frame and the rest on the reference */
#ifndef VBC_CHANNEL_PIPE_H
#define VBC_CHANNEL_PIPE_H

#include "vb_device.h"
#include "vbc_channel.h"
#include "vbj_jfa.h"

/* What a frame run returns besides the voxel list. */
enum {
    VBC_WANT_FLAGS = 1, /* the flag volume (VBC_F_* per voxel) on the host */
    VBC_WANT_LABELS = 2, /* the Voronoi labels on the host */
    /* The edge bit of every voxel in the flags. Without it (and without
     * VBC_WANT_LABELS) the reference engine of an exact variant computes
     * labels only where the interior's classification reads them
     * (vbc_masks_need) and leaves the edge bit clear on voxels that are
     * not interior; every other bit, and so the channel voxels, are the
     * same (vbc_masks_shape). */
    VBC_WANT_EDGES = 4
};

typedef struct vbc_frame_out {
    uint32_t *voxels;   /* channel voxels, index | VBC_MOUTH_BIT, device order */
    size_t nvoxels;
    uint8_t *flags;     /* nx*ny*nz, when VBC_WANT_FLAGS (else NULL) */
    uint32_t *labels;   /* nx*ny*nz, when VBC_WANT_LABELS (else NULL) */
    float *clearance;   /* per listed voxel, Å (GPU devices only; NULL on CPU
                           devices, where the host's cell list is faster) */
    uint32_t *comp;     /* per listed voxel, the smallest voxel index of its
                           26-connected component (the device's components,
                           GPU devices only; NULL: the host's union-find) */
    double ms_upload;   /* atoms to the device */
    double ms_jfa;      /* vbj_run wall time (seed upload, algorithm, fill) */
    double ms_masks;    /* atomic mask, rays, classification, list download */
    vbj_counts jfa;     /* the JFA run's work counts */
} vbc_frame_out;

void vbc_frame_out_free(vbc_frame_out *o);

/* The JFA seeds of a frame (every engine places them alike): atom a at
 * atoms4's centre minus half a voxel (JFA puts pixel p's centre at p, the
 * channel grid puts voxel i's at i + 0.5). Checks the grid: the sides must
 * be one power of two. Allocates *out (vbj_seeds_free). VB_EMISUSE /
 * VB_EINPUT_EMPTY / VB_ENOMEM. */
int vbc_frame_seeds(vb_ctx *ctx, const vbc_grid *g, const float *atoms4, size_t natoms,
                    vbj_seeds *out);

/* The engines table. */
typedef struct vbc_engine vbc_engine;
struct vbc_engine {
    const char *name;        /* "ref", "opencl" */
    char device[160];        /* "reference (C)" or the OpenCL device name */
    void *state;
    /* Runs one frame: g a vbc_grid_fit grid (sides one power of two),
     * atoms4 the vbc_atoms_pack output for `probe`. Fills *out (zeroed
     * first). VB_EDEVICE / VB_ENOMEM / VB_EMISUSE. */
    int (*frame)(vb_ctx *ctx, vbc_engine *e, const vbc_grid *g, const float *atoms4,
                 size_t natoms, double probe, unsigned want, vbc_frame_out *out);
    void (*close)(vbc_engine *e);
    /* The engine of the analysis's batch sweeps (vbc_paths.h) on this
     * device; NULL: the twin's. */
    const struct vbc_paths_engine *paths;
    /* The engine of the pore verdict's rasters (vbc_walls.h) on this
     * device; NULL: the host floods alone. */
    const struct vbc_walls_engine *walls;
};

/* Opens the plain-C reference engine for a JFA variant. */
int vbc_engine_ref_open(vb_ctx *ctx, vbj_variant variant, vbc_engine **out);
/* Closes any engine; NULL is allowed. */
void vbc_engine_close(vbc_engine *e);

typedef struct vbc_pipe vbc_pipe;

/* The device kind the channel pipeline of --device `kind` uses: `kind`,
 * except that VB_DEVICE_AUTO on a host that shows no GPU (layer NULL or
 * layer->gpu_present() false; nothing opened, no OpenCL call) is
 * VB_DEVICE_REF: the plain-C twin on host threads, not the CPU OpenCL
 * device. On the 2-core build machine PoCL cost 0.46 s of CPU per frame of
 * 1chb against the twin's 0.27 s, and its set-up 0.2-0.4 s more (issue 32,
 * papers/facet-jfa-and-channels/channels/axis_2core.md). The output bytes
 * never depend on it. */
vb_device_kind vbc_channels_device(vb_device_kind kind, const vb_device_layer *layer);

/* Opens the pipeline for device `kind` with JFA `variant` by the one
 * fallback rule (W804). layer may be NULL (reference only). VB_ENOMEM, or
 * VB_EDEVICE only if even the reference cannot open. */
int vbc_pipe_open(vb_ctx *ctx, const vb_device_layer *layer, vb_device_kind kind,
                  vbj_variant variant, vbc_pipe **out);
void vbc_pipe_close(vbc_pipe *p);

/* Runs one frame on the engine (same arguments and contract as its frame
 * function). When the OpenCL engine fails with VB_EDEVICE, warns W806,
 * releases OpenCL and reruns the frame on the reference, which then serves
 * every later frame. out->clearance is NULL on the reference. */
int vbc_pipe_frame(vb_ctx *ctx, vbc_pipe *p, const vbc_grid *g, const float *atoms4, size_t natoms,
                   double probe, unsigned want, vbc_frame_out *out);

/* The engine that runs the analysis's batch sweeps for the device running
 * the frames now: the OpenCL engine's, else the twin's (vbc_paths.h). */
const struct vbc_paths_engine *vbc_pipe_paths(const vbc_pipe *p);

/* The engine of the pore verdict's rasters for the device running the
 * frames now (vbc_walls.h): the OpenCL engine's, else NULL (the host's
 * flood alone, the same verdict). Held until vbc_pipe_walls_release: a
 * device that fails meanwhile (W806) is closed only after it. */
const struct vbc_walls_engine *vbc_pipe_walls_hold(vbc_pipe *p);
void vbc_pipe_walls_release(vbc_pipe *p);

/* The device running the frames now: the OpenCL name or "reference (C)". */
const char *vbc_pipe_device_name(const vbc_pipe *p);
/* Nonzero while frames run on the reference backend. */
int vbc_pipe_is_ref(const vbc_pipe *p);

/* Fault injection (tests, as SQLite's *fault.test): the OpenCL engine fails
 * with VB_EDEVICE on its frame number `frame` (counted from 0 over this
 * pipe's OpenCL frames); -1 (the default) never. */
void vbc_pipe_inject_device_fault(vbc_pipe *p, long frame);

#endif
