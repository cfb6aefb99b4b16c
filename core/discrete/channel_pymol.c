/* `channels --pymol`: a PyMOL script beside the centreline PDB that loads
 * the molecule and the centrelines by paths relative to the script. */
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "vbc_channel.h"

/* An absolute, normalised form of path (".", ".." and repeated '/' removed). */
static void abs_path(const char *path, char *out, size_t len)
{
    char buf[8192];
    if (path[0] == '/' || !getcwd(buf, sizeof buf - 2))
        snprintf(buf, sizeof buf, "%s", path);
    else
        snprintf(buf + strlen(buf), sizeof buf - strlen(buf), "/%s", path);
    char *parts[1024];
    int n = 0;
    for (char *t = strtok(buf, "/"); t && n < 1024; t = strtok(NULL, "/")) {
        if (strcmp(t, ".") == 0)
            continue;
        if (strcmp(t, "..") == 0) {
            n -= n > 0;
            continue;
        }
        parts[n++] = t;
    }
    size_t o = 0;
    out[0] = '\0';
    for (int k = 0; k < n && o + 1 < len; k++)
        o += (size_t)snprintf(out + o, len - o, "/%s", parts[k]);
    if (n == 0)
        snprintf(out, len, "/");
}

/* target as a path relative to the folder of `from` (both as given, taken
 * from the working directory), so a script finds its files wherever the
 * folder moves. */
static void relative_to(const char *from, const char *target, char *out, size_t len)
{
    char a[8192], b[8192];
    abs_path(from, a, sizeof a);
    abs_path(target, b, sizeof b);
    char *slash = strrchr(a, '/');
    if (slash)
        slash[1] = '\0'; /* the folder of `from`, with its '/' */
    size_t common = 0;
    for (size_t k = 0; a[k] && a[k] == b[k]; k++)
        if (a[k] == '/')
            common = k + 1;
    size_t o = 0;
    out[0] = '\0';
    for (size_t k = common; a[k]; k++)
        if (a[k] == '/' && o + 4 < len)
            o += (size_t)snprintf(out + o, len - o, "../");
    snprintf(out + o, len - o, "%s", b + common);
}

void vbc_write_pymol(FILE *f, const char *script, const char *input, const char *centrelines_pdb)
{
    char molecule[8192], centrelines[8192];
    relative_to(script, input, molecule, sizeof molecule);
    relative_to(script, centrelines_pdb, centrelines, sizeof centrelines);
    fprintf(f, "# vorball channels: centrelines with the clearance radius in the B-factor.\n"
               "# Paths are relative to this script's folder: run it there (pymol NAME.pml).\n");
    if (strcmp(input, "-") != 0) /* stdin: no file to load */
        fprintf(f, "load %s, molecule\nhide everything, molecule\nshow cartoon, molecule\n"
                   "show lines, molecule\n", molecule);
    fprintf(f, "load %s, channels\n", centrelines);
    fprintf(f, "hide everything, channels\n"
               "alter channels, vdw=b\n"
               "rebuild\n"
               "show spheres, channels\n"
               "show sticks, channels\n"
               "set sphere_transparency, 0.4, channels\n"
               "spectrum b, red_yellow_blue, channels, minimum=0.5, maximum=4.0\n"
               "set all_states, off\n"
               "zoom channels\n");
}

