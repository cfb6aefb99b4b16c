/* `channels --pymol`: a PyMOL script beside the centreline PDB that loads
 * the molecule (the input, or its first frame written as PDB where PyMOL
 * cannot read the input's coordinates), its trajectory and the centrelines
 * by paths relative to the script. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>
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

static int ends_with_ci(const char *s, const char *suffix)
{
    size_t a = strlen(s), b = strlen(suffix);
    return a >= b && strcasecmp(s + a - b, suffix) == 0;
}

int vbc_pymol_needs_frame0(const char *input, const char *traj)
{
    if (strcmp(input, "-") == 0)
        return 0;
    /* PyMOL reads these itself, coordinates included. A topology of a
     * trajectory is written too: it may be a PDB of other coordinates. */
    static const char *const own[] = {".pdb", ".ent", ".cif", ".mmcif", ".pqr"};
    for (size_t k = 0; k < sizeof own / sizeof own[0]; k++)
        if (ends_with_ci(input, own[k]))
            return traj != NULL && !ends_with_ci(input, ".pdb");
    return 1;
}

void vbc_write_molecule_pdb(FILE *f, const vb_sphere_set *s)
{
    for (size_t i = 0; i < s->n; i++) {
        const vb_atom_info *a = s->info ? &s->info[i] : NULL;
        char name[8];
        /* Column 13 holds the second letter of a two-letter element. */
        const char *n = a ? a->name : "X";
        if (strlen(n) < 4 && (!a || strlen(a->element) < 2))
            snprintf(name, sizeof name, " %.3s", n);
        else
            snprintf(name, sizeof name, "%.4s", n);
        fprintf(f, "%-6s%5zu %-4s%c%-4.4s%c%4d%c   %8.3f%8.3f%8.3f  1.00%6.2f          %2.2s\n",
                a && a->hetatm ? "HETATM" : "ATOM", (i + 1) % 100000, name, ' ',
                a ? a->resname : "UNK", a && a->chain[0] ? a->chain[0] : 'A',
                a ? a->resseq % 10000 : (int)((i + 1) % 10000), a && a->icode ? a->icode : ' ',
                s->x[i], s->y[i], s->z[i], fmin(s->r[i], 99.99), a ? a->element : "X");
    }
    fprintf(f, "END\n");
}

void vbc_write_pymol(FILE *f, const char *script, const char *molecule_file,
                     const char *centrelines_pdb, const char *traj)
{
    char molecule[8192], centrelines[8192], trajectory[8192];
    relative_to(script, molecule_file, molecule, sizeof molecule);
    relative_to(script, centrelines_pdb, centrelines, sizeof centrelines);
    fprintf(f, "# vorball channels: centrelines with the clearance radius in the B-factor.\n"
               "# Paths are relative to this script's folder: run it there (pymol NAME.pml).\n");
    if (strcmp(molecule_file, "-") != 0) { /* stdin: no file to load */
        fprintf(f, "load %s, molecule\nhide everything, molecule\nshow cartoon, molecule\n"
                   "show lines, molecule\n", molecule);
        if (traj) {
            relative_to(script, traj, trajectory, sizeof trajectory);
            fprintf(f, "load_traj %s, molecule\n", trajectory);
        }
    }
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

