/* The world of one process (vb_world.h): the build without MPI. Every
 * collective is the identity; errors are printed as every command prints
 * them (vb_cli_fail). */
#include "vb_world.h"

#include <stdlib.h>
#include <string.h>

#include "cli_common.h"

int vb_world_init(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    return 0;
}

int vb_world_finish(int exit_code)
{
    return exit_code;
}

int vb_world_rank(void)
{
    return 0;
}

int vb_world_size(void)
{
    return 1;
}

int vb_world_check_command(const char *cmd)
{
    (void)cmd;
    return 0;
}

int vb_world_check_input(const char *cmd, const char *path)
{
    (void)cmd;
    (void)path;
    return 0;
}

int vb_world_open_ctx(vb_ctx **ctx)
{
    return vb_open(ctx, NULL);
}

int vb_world_quiet(vb_ctx *ctx)
{
    (void)ctx;
    return -1;
}

void vb_world_loud(vb_ctx *ctx, int saved)
{
    (void)ctx;
    (void)saved;
}

int vb_world_agree(vb_ctx *ctx, int rc)
{
    (void)ctx;
    return rc;
}

int vb_world_end(vb_ctx *ctx, int rc)
{
    return rc == VB_OK ? VB_EXIT_OK : vb_cli_fail(ctx, rc);
}

int vb_world_gather(vb_ctx *ctx, const void *buf, size_t len, unsigned char ***parts,
                    size_t **lens)
{
    *parts = calloc(1, sizeof **parts);
    *lens = calloc(1, sizeof **lens);
    if (!*parts || !*lens || !((*parts)[0] = malloc(len ? len : 1))) {
        free(*parts);
        free(*lens);
        *parts = NULL;
        *lens = NULL;
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    }
    if (len)
        memcpy((*parts)[0], buf, len);
    (*lens)[0] = len;
    return VB_OK;
}

int vb_world_sum_u64(vb_ctx *ctx, uint64_t *v, int n)
{
    (void)ctx;
    (void)v;
    (void)n;
    return VB_OK;
}

int vb_world_sum_double(vb_ctx *ctx, double *v, int n)
{
    (void)ctx;
    (void)v;
    (void)n;
    return VB_OK;
}

int vb_world_max_double(vb_ctx *ctx, double *v, int n)
{
    (void)ctx;
    (void)v;
    (void)n;
    return VB_OK;
}

void vb_world_barrier(void)
{
}
