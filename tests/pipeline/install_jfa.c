/* A jfa program outside the tree, compiled against the installed headers
 * and libvorball (tests/pipeline/install.sh), through the public handle of
 * vb_jfa.h alone: the options of `vorball jfa -n 64 -k 50 --device ref
 * -V all --check` set by name (command-line spellings and Python
 * keywords), the run, its JSON document on stdout (the command's bytes
 * with --json, but the times) and, on stderr, "runs R wrong W" (the runs
 * and the wrong pixels of the last, exact, one) and the message of a
 * refused size. Exit 0, or 1 with a message. */
#include <stdio.h>

#include "vorball.h"

int main(void)
{
    vb_config cfg = {0, NULL}; /* quiet */
    vb_ctx *ctx;
    if (vb_open(&ctx, &cfg) != VB_OK)
        return 1;
    vb_jfa *j = NULL;
    char err[512];
    int rc = vb_jfa_new(ctx, &j);
    if (rc == VB_OK && (vb_jfa_set(j, "-n", "64", err, sizeof err) != 0 ||
                        vb_jfa_set(j, "k", "50", err, sizeof err) != 0 ||
                        vb_jfa_set(j, "device", "ref", err, sizeof err) != 0 ||
                        vb_jfa_set(j, "--variant", "all", err, sizeof err) != 0 ||
                        vb_jfa_set(j, "--check", NULL, err, sizeof err) != 0 ||
                        vb_jfa_check(j, err, sizeof err) != 0))
        rc = vb_error(ctx, VB_EMISUSE, NULL, 0, "%s", err);
    if (rc == VB_OK)
        rc = vb_jfa_run(ctx, j);
    vb_jfa_info info;
    vb_jfa_figures last;
    if (rc == VB_OK && (vb_jfa_info_get(j, &info) != 0 ||
                        vb_jfa_figures_get(j, info.runs - 1, &last) != 0))
        rc = vb_error(ctx, VB_EMISUSE, NULL, 0, "no figures after a run");
    if (rc == VB_OK) {
        vb_jfa_write(j, stdout, 1);
        fprintf(stderr, "runs %d wrong %zu\n", info.runs, last.wrong);
        if (vb_jfa_set(j, "size", "32768", err, sizeof err) == 0)
            rc = vb_error(ctx, VB_EMISUSE, NULL, 0, "size 32768 accepted");
        else
            fprintf(stderr, "%s\n", err);
    }
    if (rc != VB_OK)
        fprintf(stderr, "install_jfa: %s\n", vb_errmsg(ctx));
    vb_jfa_free(j);
    vb_close(ctx);
    return rc == VB_OK ? 0 : 1;
}
