/* The periodic box of a trajectory frame: XTC and TRR store three box
 * vectors in nm as floats (or doubles), DCD a CHARMM unit cell (A, gamma,
 * B, beta, alpha, C: lengths in Angstrom, angles in degrees or, in newer
 * files, their cosines). Both become exact decimal boxes (vb_periodic.h):
 * each stored number as the shortest decimal that reads back to it (so a
 * box written as 5.65806 nm is 56.5806 A), angles other than right ones
 * through vb_box_from_cell's 6 decimals. */
#include "vb_frames.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_box.h"

/* The shortest decimal (up to 17 digits) that reads back to v; as_float:
 * to the float v is. 0, or -1 for a number out of range. */
static int shortest(double v, int as_float, vb_decimal *out)
{
    char buf[64];
    for (int p = 1; p <= 17; p++) {
        snprintf(buf, sizeof buf, "%.*g", p, v);
        double back = strtod(buf, NULL);
        if (as_float ? (float)back == (float)v : back == v)
            break;
    }
    return vb_decimal_parse(buf, strlen(buf), out, NULL) == VB_OK ? 0 : -1;
}

int vb_frame_box_xdr(const double nm[9], int is_double, vb_box *out)
{
    vb_decimal ev[9];
    for (int k = 0; k < 9; k++) {
        if (!isfinite(nm[k]) || shortest(nm[k], !is_double, &ev[k]) != 0)
            return 0;
        if (ev[k].mant != 0)
            ev[k].exp10 += 1; /* nm to Angstrom, exactly */
    }
    return vb_box_try(ev, out);
}

int vb_frame_box_dcd(const double cell[6], vb_box *out)
{
    const double len[3] = {cell[0], cell[2], cell[5]};
    double ang[3] = {cell[4], cell[3], cell[1]}; /* alpha, beta, gamma */
    int cosines = 1;
    for (int k = 0; k < 3; k++) {
        if (!isfinite(len[k]) || !isfinite(ang[k]) || !(len[k] > 0.0))
            return 0;
        cosines &= fabs(ang[k]) <= 1.0;
    }
    vb_decimal dl[3], da[3];
    for (int k = 0; k < 3; k++) {
        if (shortest(len[k], 0, &dl[k]) != 0)
            return 0;
        double deg = ang[k];
        if (cosines)
            deg = ang[k] == 0.0 ? 90.0 : acos(ang[k]) * (180.0 / 3.14159265358979323846);
        char buf[64];
        snprintf(buf, sizeof buf, "%.6f", deg);
        if (vb_decimal_parse(buf, strlen(buf), &da[k], NULL) != VB_OK)
            return 0;
    }
    return vb_box_from_cell(NULL, dl, da, NULL, 0, out) == VB_OK;
}
