/* The step kernel of jfa.cl for one dimension, included twice by jfa.cl
 * (OpenCL C only): with VBJ_D 2 it defines jfa_step_2d, with VBJ_D 3
 * jfa_step_3d. A 2D block is the 3D block with one plane (VBJ_SBZ 1, z = 0),
 * and every test on the dimension is a constant, so each kernel compiles to
 * what its own copy did.
 *
 * One step of length l on a q^d grid of cells of f fine pixels: work-item
 * (wx, wy[, wz]) owns a VBJ_BX x VBJ_SBY x VBJ_SBZ block of pixels spaced l
 * (2D: VBJ_BX x VBJ_BY2); global size VBJ_ITEMS(q, l, B) along each axis.
 * seeds: in the build's coordinate type; iseeds: the 16.16 integers (the
 * exact fallback). The seed terms are x^2 + y^2 per column and row (txy) and,
 * in 3D, z^2 per plane (tz), so an offer is one add (none in 2D). */
#if VBJ_D == 3
#define VBJ_SBY VBJ_BY
#define VBJ_SBZ VBJ_BZ
#define VBJ_SEED vbj_seed3
#define VBJ_ISEED int4
#define VBJ_TZ(c) +tz[c]
#define VBJ_EXACT(x, y, z) vbj_exact_step3(src, iseeds, q, f, l, x, y, z)
kernel void jfa_step_3d(
#else
#define VBJ_SBY VBJ_BY2
#define VBJ_SBZ 1
#define VBJ_SEED vbj_seed2
#define VBJ_ISEED int2
#define VBJ_TZ(c)
#define VBJ_EXACT(x, y, z) vbj_exact_step2(src, iseeds, q, f, l, x, y)
kernel void jfa_step_2d(
#endif
    global const vbj_label *src, global vbj_label *dst, global const VBJ_SEED *seeds,
    global const VBJ_ISEED *iseeds, uint q, uint f, uint l)
{
    uint wx = get_global_id(0), wy = get_global_id(1), wz = VBJ_D == 3 ? get_global_id(2) : 0;
    if (wx >= VBJ_ITEMS(q, l, VBJ_BX) || wy >= VBJ_ITEMS(q, l, VBJ_SBY) ||
        (VBJ_D == 3 && wz >= VBJ_ITEMS(q, l, VBJ_SBZ)))
        return;
    uint x0 = VBJ_FIRST(wx, l, VBJ_BX), y0 = VBJ_FIRST(wy, l, VBJ_SBY);
    uint z0 = VBJ_D == 3 ? VBJ_FIRST(wz, l, VBJ_SBZ) : 0;
    vbj_coord cx[VBJ_BX], cy[VBJ_SBY], cz[VBJ_SBZ];
#pragma unroll
    for (int a = 0; a < VBJ_BX; a++)
        cx[a] = VBJ_CENTRE(x0 + (uint)a * l < q ? x0 + (uint)a * l : x0, f);
#pragma unroll
    for (int b = 0; b < VBJ_SBY; b++)
        cy[b] = VBJ_CENTRE(y0 + (uint)b * l < q ? y0 + (uint)b * l : y0, f);
#pragma unroll
    for (int c = 0; c < VBJ_SBZ; c++)
        cz[c] = VBJ_D == 3 ? VBJ_CENTRE(z0 + (uint)c * l < q ? z0 + (uint)c * l : z0, f) : 0;
    vbj_d key[VBJ_BX][VBJ_SBY][VBJ_SBZ], txy[VBJ_BX][VBJ_SBY], tz[VBJ_SBZ];
    uint lab[VBJ_BX][VBJ_SBY][VBJ_SBZ], near = 0;
#pragma unroll
    for (int a = 0; a < VBJ_BX; a++)
#pragma unroll
        for (int b = 0; b < VBJ_SBY; b++) {
            txy[a][b] = 0;
#pragma unroll
            for (int c = 0; c < VBJ_SBZ; c++) {
                key[a][b][c] = VBJ_DINIT;
                lab[a][b][c] = VBJ_LNONE;
            }
        }
#pragma unroll
    for (int c = 0; c < VBJ_SBZ; c++)
        tz[c] = 0;
    uint cv = VBJ_NOCACHE;
    /* 3D reads VBJ_BZ + 2 planes; 2D its one plane as jz = 0 (which
     * concerns plane c = 0, the only one). */
#pragma unroll
    for (int jz = 0; jz < (VBJ_D == 3 ? VBJ_SBZ + 2 : 1); jz++)
#pragma unroll
        for (int jy = 0; jy < VBJ_SBY + 2; jy++) {
            uint yy = y0 + (uint)jy * l - l, zz = VBJ_D == 3 ? z0 + (uint)jz * l - l : 0;
            uint vr[VBJ_BX + 2];
            vbj_row(src, vr, yy < q && (VBJ_D == 2 || zz < q), (zz * q + yy) * q, x0, l, q);
#pragma unroll
            for (int jx = 0; jx < VBJ_BX + 2; jx++) {
                uint v = vr[jx];
                if (!vbj_wanted(vr, jx))
                    continue;
                if (v != cv) {
                    cv = v;
                    VBJ_SEED s = seeds[v];
#pragma unroll
                    for (int a = 0; a < VBJ_BX; a++)
#pragma unroll
                        for (int b = 0; b < VBJ_SBY; b++)
                            txy[a][b] = VBJ_SQ(cx[a] - s.x) + VBJ_SQ(cy[b] - s.y);
#if VBJ_D == 3
#pragma unroll
                    for (int c = 0; c < VBJ_SBZ; c++)
                        tz[c] = VBJ_SQ(cz[c] - s.z);
#endif
                }
#pragma unroll
                for (int a = 0; a < VBJ_BX; a++)
#pragma unroll
                    for (int b = 0; b < VBJ_SBY; b++)
#pragma unroll
                        for (int c = 0; c < VBJ_SBZ; c++)
                            if (a >= VBJ_LO(jx) && a <= VBJ_HI(jx, VBJ_BX) &&
                                b >= VBJ_LO(jy) && b <= VBJ_HI(jy, VBJ_SBY) &&
                                c >= VBJ_LO(jz) && c <= VBJ_HI(jz, VBJ_SBZ))
                                VBJ_OFFER(key[a][b][c], lab[a][b][c], txy[a][b] VBJ_TZ(c),
                                          1u << ((a * VBJ_SBY + b) * VBJ_SBZ + c))
            }
        }
#pragma unroll
    for (int a = 0; a < VBJ_BX; a++)
#pragma unroll
        for (int b = 0; b < VBJ_SBY; b++)
#pragma unroll
            for (int c = 0; c < VBJ_SBZ; c++) {
                uint x = x0 + (uint)a * l, y = y0 + (uint)b * l, z = z0 + (uint)c * l;
                if (x < q && y < q && (VBJ_D == 2 || z < q))
                    dst[(z * q + y) * q + x] =
                        (vbj_label)(near & 1u << ((a * VBJ_SBY + b) * VBJ_SBZ + c)
                                        ? VBJ_EXACT(x, y, z)
                                        : lab[a][b][c]);
            }
}
#undef VBJ_SBY
#undef VBJ_SBZ
#undef VBJ_SEED
#undef VBJ_ISEED
#undef VBJ_TZ
#undef VBJ_EXACT
