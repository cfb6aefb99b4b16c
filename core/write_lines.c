/* vb_write_lines: formatting 17 digits is most of the cost of writing a
 * vertex file, so blocks of items are formatted on the threads. */
#include "vb_write_lines.h"

#include <stdlib.h>

#include "vb.h"
#include "vb_parallel.h"

#define WRITE_BLOCK 4096u

typedef struct blocks {
    vb_line_fn fn;
    const void *arg;
    size_t n, k0;
    char **buf;
    size_t *len;
} blocks;

static void format_block(void *ctx, size_t i, int tid)
{
    (void)tid;
    blocks *b = ctx;
    FILE *m = open_memstream(&b->buf[i], &b->len[i]);
    if (!m) {
        b->buf[i] = NULL;
        return;
    }
    size_t k0 = b->k0 + i * WRITE_BLOCK, k1 = k0 + WRITE_BLOCK;
    for (size_t k = k0; k < k1 && k < b->n; k++)
        b->fn(m, b->arg, k);
    if (fclose(m) != 0) {
        free(b->buf[i]);
        b->buf[i] = NULL;
    }
}

int vb_write_lines(FILE *f, size_t n, vb_line_fn fn, const void *arg)
{
    int nt = vb_threads(0);
    if (nt == 1 || n <= WRITE_BLOCK) {
        for (size_t k = 0; k < n; k++)
            fn(f, arg, k);
        return VB_OK;
    }
    size_t round = 4u * (size_t)nt;
    char **buf = calloc(round, sizeof *buf);
    size_t *len = calloc(round, sizeof *len);
    int rc = buf && len ? VB_OK : VB_ENOMEM;
    for (size_t k0 = 0; rc == VB_OK && k0 < n; k0 += round * WRITE_BLOCK) {
        size_t nb = (n - k0 + WRITE_BLOCK - 1) / WRITE_BLOCK;
        nb = nb < round ? nb : round;
        blocks b = {fn, arg, n, k0, buf, len};
        vb_parallel_for(format_block, &b, nb, nt);
        for (size_t i = 0; i < nb; i++) {
            if (!buf[i])
                rc = VB_ENOMEM;
            else if (rc == VB_OK)
                fwrite(buf[i], 1, len[i], f);
            free(buf[i]);
            buf[i] = NULL;
        }
    }
    free(buf);
    free(len);
    return rc;
}
