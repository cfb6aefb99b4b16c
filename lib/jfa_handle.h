/* The jfa handle's insides (lib/vb_jfa.h), shared by its two files:
 * jfa_options.c (the option table, setting and checking) and jfa.c (the
 * run, the results and their writers). Not installed. */
#ifndef VB_JFA_HANDLE_H
#define VB_JFA_HANDLE_H

#include "vb_device.h"
#include "vb_jfa.h"
#include "vbj_runs.h"

struct vb_jfa {
    vb_ctx *ctx;
    /* the options */
    vbj_setup set;
    vbj_distribution dist;
    vbj_variant v[VBJ_MAX_VARIANTS];
    int nv, dim_given, check, json;
    vb_device_kind kind;
    const char *device, *protein, *png, *out, *slices;
    /* the seeds' source */
    const char *path, *spheres_name;
    const vb_sphere_set *spheres;
    double *points;
    size_t npoints;
    /* the run */
    int ran;
    vbj_seeds s;
    char source[512];
    vbj_backend *e;
    vb_device *dev;
    vbj_runs runs;
};

#endif
