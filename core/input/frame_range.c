/* The frames a run takes, `--frames A:B:S` (vb_frames.h): one parser for
 * every command that reads trajectories. */
#include <string.h>

#include "vb_frames.h"
#include "vb_numtext.h"

int vb_frame_range_parse(const char *s, vb_frame_range *out)
{
    char buf[96];
    if (strlen(s) >= sizeof buf)
        return -1;
    strcpy(buf, s);
    char *parts[3] = {buf, NULL, NULL};
    char *c1 = strchr(buf, ':');
    if (c1) {
        *c1 = '\0';
        parts[1] = c1 + 1;
        char *c2 = strchr(parts[1], ':');
        if (c2) {
            *c2 = '\0';
            parts[2] = c2 + 1;
        }
    }
    long v[3] = {0, -1, 1};
    for (int i = 0; i < 3; i++) {
        if (!parts[i] || !*parts[i])
            continue;
        size_t x;
        if (vb_parse_size(parts[i], &x) != 0 || x > (size_t)1e9)
            return -1;
        v[i] = (long)x;
    }
    if (!c1)
        v[1] = v[0] + 1; /* a single number is one frame */
    if (v[2] < 1 || (v[1] >= 0 && v[1] <= v[0]))
        return -1;
    out->first = v[0];
    out->end = v[1];
    out->step = v[2];
    return 0;
}

int vb_frame_range_has(const vb_frame_range *r, long index)
{
    return index >= r->first && (r->end < 0 || index < r->end) &&
           (index - r->first) % r->step == 0;
}
