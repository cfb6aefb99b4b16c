/* Test helper: every case of the corpus (corpus/inputs/CASE.xyzr beside
 * corpus/golden/CASE.tsv, under $VORBALL_SOURCE_DIR, else "."). */
#ifndef VT_CORPUS_H
#define VT_CORPUS_H

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Calls fn(name, input path, golden path) for each corpus input, in the
 * folder's order; returns how many, or -1 when the folder cannot be read. */
static inline int vt_each_golden(void (*fn)(const char *name, const char *in, const char *gold))
{
    const char *src = getenv("VORBALL_SOURCE_DIR");
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/corpus/inputs", src ? src : ".");
    DIR *d = opendir(dir);
    if (!d)
        return -1;
    int cases = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        size_t len = strlen(e->d_name);
        if (len < 6 || strcmp(e->d_name + len - 5, ".xyzr") != 0)
            continue;
        char in[2048], gold[2048];
        snprintf(in, sizeof in, "%s/%s", dir, e->d_name);
        snprintf(gold, sizeof gold, "%s/corpus/golden/%.*s.tsv", src ? src : ".", (int)(len - 5),
                 e->d_name);
        fn(e->d_name, in, gold);
        cases++;
    }
    closedir(d);
    return cases;
}

#endif
