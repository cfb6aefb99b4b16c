/* `vorball devices`: list OpenCL platforms and devices, and which one
 * `--device auto` would take. */
#include <stdio.h>
#include <string.h>

#include "cli_common.h"
#include "commands.h"
#include "vb_default.h"

void vb_cmd_devices_help(FILE *f)
{
    fprintf(f,
            "usage: vorball devices [-o FILE]\n\n"
            "Lists OpenCL platforms and devices (tab-separated, '#' header) and the device\n"
            "that --device auto selects: a GPU with double precision if present, else a\n"
            "CPU device (PoCL). Without OpenCL, the reference backend (--device ref) is used.\n\n"
            "  -o FILE   write the table to FILE instead of stdout\n");
}

int vb_cmd_devices(int argc, char **argv)
{
    const char *outpath = NULL;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "-o") == 0 && i + 1 < argc) {
            outpath = argv[++i];
        } else {
            return vb_cli_usage_error("devices", "unexpected argument '%s'", argv[i]);
        }
    }
    vb_ctx *ctx;
    if (vb_open(&ctx, NULL))
        return vb_cli_fail(NULL, VB_ENOMEM);
    FILE *out = vb_cli_open_output(ctx, outpath);
    int rc = out ? vb_devices_write(ctx, out) : vb_errcode(ctx);
    rc = vb_cli_finish_output(ctx, out, outpath, rc);
    int code = rc ? vb_cli_fail(ctx, rc) : VB_EXIT_OK;
    vb_close(ctx);
    return code;
}
