/* Test helper for the channel tests that run the CLI: the vorball binary,
 * the source tree and a private temporary directory, from the environment
 * that ctest sets (VORBALL_BINARY_DIR, VORBALL_SOURCE_DIR; TMPDIR). */
#ifndef VBC_TEST_CLI_ENV_H
#define VBC_TEST_CLI_ENV_H

#include <stdio.h>
#include <stdlib.h>

#include "vb_test.h"

static char bin[1024], src[1024], dir[256];

/* Fills bin, src and dir, a fresh directory "<TMPDIR or /tmp>/<stem>_XXXXXX".
 * Returns 0, or 1 when the environment is missing (said on stderr) or the
 * directory cannot be made. */
static inline int cli_env_open(const char *stem)
{
    const char *b = getenv("VORBALL_BINARY_DIR"), *s = getenv("VORBALL_SOURCE_DIR");
    if (!b || !s) {
        fprintf(stderr, "VORBALL_BINARY_DIR and VORBALL_SOURCE_DIR must be set\n");
        return 1;
    }
    snprintf(bin, sizeof bin, "%s/cli/vorball", b);
    snprintf(src, sizeof src, "%s", s);
    const char *t = getenv("TMPDIR");
    snprintf(dir, sizeof dir, "%s/%s_XXXXXX", t && *t ? t : "/tmp", stem);
    return mkdtemp(dir) ? 0 : 1;
}

/* Removes dir when every check passed; after a failure it stays to be looked at. */
static inline void cli_env_close(void)
{
    char cmd[512];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (vb_test_failed == 0 && system(cmd) != 0)
        fprintf(stderr, "could not remove %s\n", dir);
}

#endif
