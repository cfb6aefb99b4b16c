/* The growing sphere set that every reader fills, and its release. */
#include "vbi_input.h"

#include <stdlib.h>
#include <string.h>

#include "vb_array.h"

void vb_spheres_free(vb_sphere_set *s)
{
    if (!s)
        return;
    free(s->x);
    free(s->y);
    free(s->z);
    free(s->r);
    free(s->ex);
    free(s->ey);
    free(s->ez);
    free(s->er);
    free(s->info);
    free(s->line);
    free(s->contained);
    free(s->source);
    free(s->box);
    free(s);
}

int vb_spheres_new(vb_ctx *ctx, const char *name, size_t n, int with_info, vb_sphere_set **out)
{
    *out = NULL;
    vb_sphere_set *s = calloc(1, sizeof *s);
    size_t m = n ? n : 1;
    if (s) {
        s->n = n;
        s->x = calloc(m, sizeof *s->x);
        s->y = calloc(m, sizeof *s->y);
        s->z = calloc(m, sizeof *s->z);
        s->r = calloc(m, sizeof *s->r);
        s->line = calloc(m, sizeof *s->line);
        s->info = with_info ? calloc(m, sizeof *s->info) : NULL;
        s->source = strdup(name ? name : "<spheres>");
    }
    if (!s || !s->x || !s->y || !s->z || !s->r || !s->line || (with_info && !s->info) ||
        !s->source) {
        vb_spheres_free(s);
        return vb_error(ctx, VB_ENOMEM, name, 0, "out of memory for %zu spheres", n);
    }
    *out = s;
    return VB_OK;
}

int vbi_builder_init(vbi_builder *b, vb_ctx *ctx, const char *name, size_t max, int with_info)
{
    memset(b, 0, sizeof *b);
    b->ctx = ctx;
    b->name = name;
    b->max = max ? max : VBI_DEFAULT_MAX_SPHERES;
    b->set = calloc(1, sizeof *b->set);
    if (!b->set)
        return vb_error(ctx, VB_ENOMEM, name, 0, "out of memory");
    b->set->source = strdup(name);
    /* A one-record placeholder marks "wants atom records" until the first grow. */
    if (!b->set->source || (with_info && !(b->set->info = malloc(sizeof *b->set->info)))) {
        vbi_builder_discard(b);
        return vb_error(ctx, VB_ENOMEM, name, 0, "out of memory");
    }
    return VB_OK;
}

static int builder_grow(vbi_builder *b)
{
    vb_sphere_set *s = b->set;
    size_t cap = vb_array_capacity(b->cap, b->cap + 1, 256);
    int bad = 0;
    bad |= vb_array_resize((void **)&s->x, cap, sizeof *s->x);
    bad |= vb_array_resize((void **)&s->y, cap, sizeof *s->y);
    bad |= vb_array_resize((void **)&s->z, cap, sizeof *s->z);
    bad |= vb_array_resize((void **)&s->r, cap, sizeof *s->r);
    bad |= vb_array_resize((void **)&s->ex, cap, sizeof *s->ex);
    bad |= vb_array_resize((void **)&s->ey, cap, sizeof *s->ey);
    bad |= vb_array_resize((void **)&s->ez, cap, sizeof *s->ez);
    bad |= vb_array_resize((void **)&s->er, cap, sizeof *s->er);
    bad |= vb_array_resize((void **)&s->line, cap, sizeof *s->line);
    if (s->info)
        bad |= vb_array_resize((void **)&s->info, cap, sizeof *s->info);
    if (bad)
        return vb_error(b->ctx, VB_ENOMEM, b->name, 0, "out of memory at %zu spheres", s->n);
    b->cap = cap;
    return VB_OK;
}

int vbi_builder_push(vbi_builder *b, const vb_decimal e[4], const double d[4],
                     const vb_atom_info *info, long line)
{
    vb_sphere_set *s = b->set;
    if (s->n >= b->max)
        return vb_error(b->ctx, VB_EINPUT_TOOLARGE, b->name, line,
                        "more than %zu spheres (the sphere limit)", b->max);
    if (s->n == b->cap) {
        int rc = builder_grow(b);
        if (rc != VB_OK)
            return rc;
    }
    size_t i = s->n++;
    s->x[i] = d[0];
    s->y[i] = d[1];
    s->z[i] = d[2];
    s->r[i] = d[3];
    s->ex[i] = e[0];
    s->ey[i] = e[1];
    s->ez[i] = e[2];
    s->er[i] = e[3];
    s->line[i] = line;
    if (s->info) {
        if (info)
            s->info[i] = *info;
        else
            memset(&s->info[i], 0, sizeof s->info[i]);
    }
    return VB_OK;
}

void vbi_builder_finish(vbi_builder *b, int keep_info, vb_sphere_set **out)
{
    vb_sphere_set *s = b->set;
    if (!keep_info) {
        free(s->info);
        s->info = NULL;
    }
    b->set = NULL;
    *out = s;
}

void vbi_builder_discard(vbi_builder *b)
{
    vb_spheres_free(b->set);
    b->set = NULL;
}
