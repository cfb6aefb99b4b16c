/* The direction cover, shared with the kernels (part of vb_cover_shared.h,
 * which includes it after the neighbours and the patches, before the tree
 * walk of vbq_gather_shared.h; include that header, never this one): the
 * ring a fetching patch asks for and the parts it asks through. */
#ifndef VBQ_RING_SHARED_H
#define VBQ_RING_SHARED_H

/* ---- ring fetches resolved by sub-patch --------------------------------
 * A fetching patch is split VBQ_SUB x VBQ_SUB; each part g gets its own box
 * and lower envelope LO_g from the list. A sphere can be a label somewhere
 * in the patch only if it can be one somewhere in some part, i.e. only if
 * it passes the query of some part: a far sharper test than the patch's
 * single LO where the cell's reach varies across the patch (exposed cells
 * facing a cavity). The address space of the parts' array is VBQ_SQ
 * (private by default; the group kernel keeps them in local memory). */
#ifndef VBQ_SUB
#define VBQ_SUB 2u
#endif
#define VBQ_NSUB (VBQ_SUB * VBQ_SUB)
#ifndef VBQ_SQ
#define VBQ_SQ
#endif

typedef struct vbq_sub {
    double m[3], h[3];
    double LO, sdist;
} vbq_sub;

/* Part g (row-major) of the square [u0,u1] x [v0,v1] on face f. */
VBS_FN void vbq_sub_box(vbs_u32 f, double u0, double u1, double v0, double v1, vbs_u32 g,
                        double m[3], double h[3])
{
    double du = (u1 - u0) / (double)VBQ_SUB, dv = (v1 - v0) / (double)VBQ_SUB;
    vbs_u32 a = g % VBQ_SUB, b = g / VBQ_SUB;
    /* The parts' edges are the patch's dyadic grid refined VBQ_SUB times:
     * exact doubles, and the outer ones equal the patch's edges. */
    double a0 = a == 0u ? u0 : u0 + du * (double)a, a1 = a + 1u == VBQ_SUB ? u1 : u0 + du * (double)(a + 1u);
    double b0 = b == 0u ? v0 : v0 + dv * (double)b, b1 = b + 1u == VBQ_SUB ? v1 : v0 + dv * (double)(b + 1u);
    vbq_patch_box(f, a0, a1, b0, b1, m, h);
}

/* A near-tie: LO > 0 reaching beyond VBQ_RING_JUMP times the farthest
 * centre (a jittered face ball at its normal, LO ~ 1e-10) closes at no
 * finite ring. On the host and CPU devices (not the GPU form) its ring goes
 * to infinity at once (four doubling walks before, the same labels) and its
 * fetch waits a level (vbq_cover_cell: the children off the tie close on
 * small rings, the one at it takes the half-space of a part half as wide).
 * Speed only: a ring takes whatever can reach its parts' LO. */
#define VBQ_RING_JUMP 1e3
VBS_FN vbs_u32 vbq_near_tie(double LO, double far)
{
    return LO > 0.0 && 1.0 / LO > VBQ_RING_JUMP * far ? 1u : 0u;
}

/* The outer radius of the next ring a patch fetches: out to the reach LO
 * asks for, at most twice the present radius (LO grows with what is
 * found); infinite past the farthest centre or at a near-tie. */
VBS_FN double vbq_ring_radius(double rq, double LO, double slack_i, double far)
{
    double want = LO > 0.0 ? (1.0 / LO) * (1.0 + 1e-8) + slack_i + 1e-9 * rq : (double)INFINITY;
    double rq1 = want < 2.0 * rq ? want : 2.0 * rq;
    return rq1 >= far || vbq_near_tie(LO, far) ? (double)INFINITY : rq1;
}

/* Part g's lower envelope LO and the reach 1/(2 LO) of its bisectors. */
VBS_FN void vbq_sub_set_lo(VBQ_SQ vbq_sub *sub, double LO)
{
    sub->LO = LO;
    sub->sdist = LO > 0.0 ? 0.5 / LO : (double)INFINITY;
}

#endif
