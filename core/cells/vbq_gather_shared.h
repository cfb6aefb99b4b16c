/* The direction cover, shared with the kernels (part of vb_cover_shared.h,
 * which includes it after the neighbours, the patches and the rings; include
 * that header, never this one): the tuning and statuses of the cover, a
 * cell's environment (the tree of the centres) and arenas, and the one tree
 * walk every backend takes (vbq_walk) through a fetching patch's parts. */
#ifndef VBQ_GATHER_SHARED_H
#define VBQ_GATHER_SHARED_H

/* ---- the cover of one cell ---------------------------------------------- */

/* Tuning (speed only; every value keeps the cover complete). */
#define VBQ_LEAF 8u            /* spheres per leaf of the tree */
#define VBQ_FETCH_LEVEL 2u     /* unclosed patches from this level fetch rings */
#define VBQ_STALL 4u           /* levels without an exclusion before enumerating */
#define VBQ_STALL_ENUM 14u     /* ... when at most this many owned labels */
#define VBQ_DOM_MAX 12u        /* patches with at most this many labels test pairs */
#define VBQ_STACK 64u          /* tree traversal stack (depth <= 33) */
/* Statuses of vbq_cover_cell: 0, or which arena ran out (the host reruns the
 * cell with larger arenas). */
#define VBQ_OK 0u
#define VBQ_OVER_NB 1u
#define VBQ_OVER_LAB 2u
#define VBQ_OVER_ST 3u
#define VBQ_OVER_Q 4u
/* 5 is the kernels' VBQ_OVER_OUT. A patch that looks like a tie cluster (vbq_tie_cluster):
 * the cell is covered again on the host, which decides it exactly (vbq_host_cluster). */
#define VBQ_CLUSTER 6u
/* A cell that took more steps (patches popped) than the group kernel's
 * budget (gpu/cover_wg.cl): nothing of it is kept, and the driver covers it
 * again on the host threads, or on the work-item kernel as root-patch tasks
 * (gpu/cover_ocl.c). Only the group kernel returns it. */
#define VBQ_BUDGET 7u
/* The budget's top bit (the group kernel's budget argument): a cell past
 * its steps hands the patches left on its stack (vbq_hand_patch, each with
 * its list) and keeps what it did, status VBQ_OK; the host resumes them as
 * it resumes the kernel's other handed patches. Where the buffer has no
 * room for all of them, the cell is VBQ_BUDGET, as without the bit. */
#define VBQ_BUDGET_HAND 0x80000000u

/* A closed patch to enumerate or subdivide with more owned labels than this
 * that look flat is a tie cluster, decided exactly before any of its
 * C(owned, 3) quadruples is written or its children are made (speed only:
 * both ways are complete). */
#define VBQ_CLUSTER_OWNED 5u

/* A stalled chain decided exactly (vbq_envelope_due): after this many levels without an
 * exclusion (1: a list that did not shrink), with at most this many owned labels (C(owned, 3)
 * triples) and labels in all. Measured (cover alone, 1 thread, loaded 2 cores): jittered fcc
 * 10,976 4.86 s without, 4.73 s with; exact 5.88 s either way; no owned minimum 4.68 s jittered,
 * 6.37 s exact. 32 owned as the host skips pairs tying off the
 * patch: sc 2,744 jittered 1e-12 4.61 -> 4.29 s, sc 1,000 0.48 -> 0.48-0.53 (48: 3.8, 0.65).
 * Off a GPU the hull decision (core/cells/cover_env_hull.c) takes 96 owned labels, and up to
 * VBQ_ENV_OWNED and VBQ_ENV_KEEP at deep patches (VBQ_ENV_DEEP, past VBQ_ENV_DEEP_LEVEL: a
 * near-tie chain of ~140 labels went on to level 47 on sc 2,744 jittered 1e-12; taking such
 * lists at every stalled level cost fcc 1,372 exact 0.25 -> 0.34 s, its exact ties many zero
 * signs). */
#define VBQ_ENV_STALL 1u
#define VBQ_ENV_OWNED_SHALLOW 96u
#define VBQ_ENV_OWNED 1024u
#define VBQ_ENV_KEEP 1024u
#define VBQ_ENV_KEEP_SHALLOW 96u
/* The kernels decide a due patch in doubles by testing every owned triple
 * (vbq_envelope_filter), cubic in the owned labels: a CPU device's kernel
 * hands a cell with a due patch of more owned labels than this to the host
 * (status VBQ_CLUSTER), whose hull decision takes the rest; a GPU's limit
 * is lower (VBQ_ENV_OWNED). */
#define VBQ_ENV_FILTER_OWNED 32u

/* The bits of a frame's combo field. */
#define VBQ_FR_COMBO 1u
#define VBQ_FR_NOTFLAT 2u

/* A patch waiting in the depth-first stack. */
typedef struct vbq_frame {
    vbs_u32 f, level;
    vbs_u64 iu, iv;    /* 64 bits: near-ties need levels past 31 */
    vbs_u32 off, len;  /* labels in lab[off .. off + len): indices into nb */
    vbs_u32 stall;     /* consecutive levels that excluded no label */
    vbs_u32 combo;     /* bit 0 (VBQ_FR_COMBO): the parent tried combinations on this
                          list; bit 1 (VBQ_FR_NOTFLAT): the parent found it no tie
                          cluster (vbq_looks_flat 0) */
    double rq;         /* every sphere centred within rq of c_i is in the list or was
                          excluded by an ancestor (INFINITY: every sphere) */
} vbq_frame;
VBS_ASSERT_LAYOUT(sizeof(vbq_frame) == 48, "vbq_frame layout shared with OpenCL");

/* What one cell's cover did (counters for --stats; nq quadruples written). */
typedef struct vbq_cell_out {
    vbs_u32 status, nq, nnb, far;
    vbs_u32 patches, evals_k, leaves, deep, maxlev;
    vbs_u32 lab_hw, st_hw;  /* high-water marks of the label and frame stacks */
    vbs_u32 qoff;           /* where a backend stored the quadruples */
} vbq_cell_out;
VBS_ASSERT_LAYOUT(sizeof(vbq_cell_out) == 48, "vbq_cell_out layout shared with OpenCL");

/* The input of every cell: the spheres, and a tree over the centres of the
 * spheres that no other sphere contains: their ids along a Morton curve,
 * in leaves of VBQ_LEAF, a complete binary tree over the leaves (heap
 * order: node 1 the root, leaves from `first`), each node with the box of
 * its centres (lo xyz, hi xyz) and the largest radius below it. */
typedef struct vbq_env {
    const VBS_GLOBAL double *x, *y, *z, *r;
    const VBS_GLOBAL double *box;
    const VBS_GLOBAL double *rmax;
    const VBS_GLOBAL vbs_u32 *ids;
    vbs_u32 first, m;
    double rmax_all;   /* largest radius of the tree's spheres */
    double near;       /* first guess of a near list's radius, beyond 2 rmax_all */
    double tmax;       /* only vertices of tangent radius <= tmax are sought (periodic
                          boxes' proven bound); INFINITY: every vertex */
    vbs_u32 T, min_level, max_level, enum_max;
#ifndef __OPENCL_C_VERSION__
    const void *host;  /* the host's exact input for vbq_host_cluster (NULL: none) */
    /* Host copies of the same doubles laid out for the walk's reads (NULL:
     * none; the walk then reads the arrays above, as the kernels do):
     * node8 8 per node (box lo xyz, hi xyz, rmax, 0), one cache line each;
     * kx, ky, kz, kr: x, y, z, r of sphere ids[k] at tree position k (a
     * whole leaf's more past m, so a leaf's eight can be read at once). */
    const double *node8, *kx, *ky, *kz, *kr;
#endif
} vbq_env;

/* An environment from the kernels' arguments (the host's `host` is left
 * unset: the kernels never decide tie clusters). */
VBS_FN void vbq_env_make(vbq_env *e, const VBS_GLOBAL double *x, const VBS_GLOBAL double *y,
                         const VBS_GLOBAL double *z, const VBS_GLOBAL double *r,
                         const VBS_GLOBAL double *box, const VBS_GLOBAL double *rmax,
                         const VBS_GLOBAL vbs_u32 *ids, vbs_u32 first, vbs_u32 m,
                         double rmax_all, double near, double tmax, vbs_u32 T,
                         vbs_u32 min_level, vbs_u32 max_level, vbs_u32 enum_max)
{
    e->x = x;
    e->y = y;
    e->z = z;
    e->r = r;
    e->box = box;
    e->rmax = rmax;
    e->ids = ids;
    e->first = first;
    e->m = m;
    e->rmax_all = rmax_all;
    e->near = near;
    e->tmax = tmax;
    e->T = T;
    e->min_level = min_level;
    e->max_level = max_level;
    e->enum_max = enum_max;
#ifndef __OPENCL_C_VERSION__
    e->node8 = e->kx = e->ky = e->kz = e->kr = 0; /* the group kernel emulator's arrays */
#endif
}

/* The host's two caches (speed only, the same doubles) are also kept by
 * the work-item kernel where its build defines VBQ_CACHES_CL (CPU devices,
 * gpu/cover_ocl.c); GPU kernels keep neither and evaluate again. */
#if !defined(__OPENCL_C_VERSION__) || defined(VBQ_CACHES_CL)
#define VBQ_CACHES 1
#endif

/* A CPU device's work-item kernel (VBQ_WALK_V4_CL) hands a patch it does
 * not decide (a tie cluster, an envelope past its filter) to the host and
 * goes on with the rest of its cell (vbq_hand_patch); the host then covers
 * that patch alone (root VBQ_RESUME, core/cells/cover_resume.c), not the
 * whole cell again. A GPU's group kernel (gpu/cover_wg.cl) does so where
 * its build defines VBQ_HANDOFF (gpu/cover_ocl.c); a GPU's work-item
 * kernel hands the whole cell (VBQ_CLUSTER). */
#if defined(__OPENCL_C_VERSION__) && defined(VBQ_WALK_V4_CL) && !defined(VBQ_HANDOFF)
#define VBQ_HANDOFF 1
#endif
/* The root of a cover that resumes handed patches (vbq_task_root takes no
 * root patch for it, vbq_task_child every child: its selectors, the low six
 * bits, are 0). */
#define VBQ_RESUME 0xffffffc0u
/* A handed patch's words: its frame (vbq_frame, 12 words; off holds the
 * cell, len the length of its list), then the sphere ids of the list in
 * order, padded to an even count (frames stay 8-byte aligned). */
#define VBQ_HAND_HEAD 12u
#define VBQ_HAND_WORDS(len) (VBQ_HAND_HEAD + (((len) + 1u) & ~1u))

/* Scratch of one cell, fixed capacities. */
typedef struct vbq_arena {
    VBS_GLOBAL vbq_nb *nb;
    VBS_GLOBAL vbs_u32 *lab;
    VBS_GLOBAL vbq_frame *st;
    VBS_GLOBAL vbs_u32 *q;      /* 4 per quadruple */
    vbs_u32 nb_cap, lab_cap, st_cap, q_cap;
#ifdef VBQ_CACHES
    VBS_GLOBAL double *hi;        /* a patch's label enclosures' upper ends (NULL: none) */
    VBS_GLOBAL vbq_nb *memo;      /* the cell's records by tree position (NULL: none) */
    VBS_GLOBAL vbs_u32 *memo_tag; /* per slot: its tree position and cell + 1 (0: none) */
#endif
#if defined(VBQ_HANDOFF) || !defined(__OPENCL_C_VERSION__)
    /* On the host always: one layout for the library and the group
     * kernel's C emulation (tests/gpu/cover_wg_emu.c, with VBQ_HANDOFF). */
    VBS_GLOBAL vbs_u32 *hand;      /* the launch's handed patches (NULL: none, hand cells) */
    VBS_GLOBAL vbs_u32 *hand_used; /* [0] words taken, [1] words written */
    vbs_u32 hand_cap;              /* words of hand */
    vbs_u32 hand_cell;             /* the cell's index in the launch (the entries' off) */
#endif
#ifndef __OPENCL_C_VERSION__
    struct vbq_cluster_memo *cmemo; /* the cell's tie-cluster answers (NULL: none) */
    const vbs_u32 *resume;          /* root VBQ_RESUME: the cell's handed patches */
    vbs_u32 resume_n;               /* ... in words */
#endif
} vbq_arena;

/* Slots of the host's record memo (a power of two): a cell's fetches ask
 * for about 160 distinct spheres on proteins, 84 % of the records the
 * walks make are made again for the same cell (4yvs, first 14,070). */
#define VBQ_MEMO 2048u

/* Squared distance from c to node nd's box (0 inside), and to its farthest
 * corner. */
VBS_FN double vbq_box_dist2(const vbq_env *e, vbs_u32 nd, const double c[3])
{
    double d2 = 0.0;
    for (int a = 0; a < 3; a++) {
        double l = e->box[6u * nd + (vbs_u32)a], h = e->box[6u * nd + 3u + (vbs_u32)a];
        double dn = c[a] < l ? l - c[a] : (c[a] > h ? c[a] - h : 0.0);
        d2 += dn * dn;
    }
    return d2;
}

VBS_FN double vbq_box_far2(const vbq_env *e, vbs_u32 nd, const double c[3])
{
    double d2 = 0.0;
    for (int a = 0; a < 3; a++) {
        double l = VBS_FABS(e->box[6u * nd + (vbs_u32)a] - c[a]);
        double h = VBS_FABS(e->box[6u * nd + 3u + (vbs_u32)a] - c[a]);
        double f = l > h ? l : h;
        d2 += f * f;
    }
    return d2;
}

/* ---- the tree walk --------------------------------------------------------
 * One walk of the tree serves every backend: the work-item walk below
 * (vbq_walk_gather, depth first) and the work-group walk of gpu/cover_wg.cl
 * (breadth first over the lanes) take the same decisions from
 * vbq_walk_node and vbq_walk_sphere, and differ only in where they keep
 * the nodes to visit and how they append what passes.
 *
 * A walk asks for the spheres centred in (rq0, rq1] from c_i (rq0 < 0:
 * from 0): all of them (the near list, nsub = 0), or those that can be
 * labels in some part g of a fetching patch (box m_g, h_g, lower envelope
 * LO_g). Where f_j >= LO at u: u.d + delta >= LO N >= 0, so the sphere
 * reaches the half-space u.(x - c_i) >= R_i - R_j; and for LO > 0 the
 * bisector along u is at most s = 1/(2 LO) from c_i, so the tangent sphere
 * there, centre c_i + s u and radius s - R_i, must reach sphere j:
 * |c_i + s u - c_j| <= s - R_i + R_j. A node is pruned when its box lies
 * within rq0 or beyond rq1, or when for every part one of these fails for
 * every u of the part's box and every centre of the node's box (R_j <= its
 * R_max); the bounds carry a relative margin of 1e-9, far above the
 * rounding errors of these few operations. */
/* The node and sphere tests over the four parts in one pass
 * (vbq_walk_node4, vbq_walk_parts4) instead of one part after the other:
 * on the host with GCC's and Clang's vectors (AVX2 in cover_cell_avx2.c,
 * two SSE2 halves in the plain build), where __attribute__ is not defined
 * away (the group kernel's emulator, tests/gpu/cover_wg_emu.c, compiles
 * the kernels' code as C and takes the scalar loops); in OpenCL with
 * double4 where the build defines VBQ_WALK_V4_CL (the work-item kernel on
 * CPU devices, gpu/cover_ocl.c; a GPU lane would do four parts' work).
 * Lane g computes what the scalar code computes for part g, operation by
 * operation (no contraction on either side), and a node or sphere passes
 * when some lane passes: the same answers. */
#if VBQ_NSUB == 4 && (defined(__OPENCL_C_VERSION__) ? defined(VBQ_WALK_V4_CL)              \
                                                   : defined(__GNUC__) && !defined(__attribute__))
#define VBQ_WALK_V4 1
#ifdef __OPENCL_C_VERSION__
typedef double4 vbq_v4;
typedef long4 vbq_m4;
#define VBQ_V4(a, b, c, d) ((double4)((a), (b), (c), (d)))
#define VBQ_AS_V4(m) as_double4(m)
#define VBQ_AS_M4(x) as_long4(x)
/* The lanes or'ed and and'ed as on the host (a lane is all ones or all
 * zeros): PoCL's any() and all() took six instructions through a general
 * register. */
#define VBQ_M4_ANY(m) (((m).s0 | (m).s1 | (m).s2 | (m).s3) != 0)
#define VBQ_M4_ALL(m) (((m).s0 & (m).s1 & (m).s2 & (m).s3) != 0)
#else
typedef double vbq_v4 __attribute__((vector_size(32)));
typedef long long vbq_m4 __attribute__((vector_size(32)));
#define VBQ_V4(a, b, c, d) ((vbq_v4){(a), (b), (c), (d)})
#define VBQ_AS_V4(m) ((vbq_v4)(m))
#define VBQ_AS_M4(x) ((vbq_m4)(x))
#define VBQ_M4_ANY(m) (((m)[0] | (m)[1] | (m)[2] | (m)[3]) != 0)
#define VBQ_M4_ALL(m) (((m)[0] & (m)[1] & (m)[2] & (m)[3]) != 0)
#endif
#define VBQ_V4_ALL(x) VBQ_V4((x), (x), (x), (x))
/* x where m is set, else y (a lane's mask: all ones or all zeros; a macro,
 * as a host function returning a vector would change the ABI between
 * builds). */
#define VBQ_V4_PICK(m, x, y) VBQ_AS_V4((VBQ_AS_M4(x) & (m)) | (VBQ_AS_M4(y) & ~(m)))
/* |x|: the sign bits cleared. */
#define VBQ_V4_ABS(x) VBQ_AS_V4(VBQ_AS_M4(x) & VBQ_V4M_ALL(0x7fffffffffffffffLL))
#ifdef __OPENCL_C_VERSION__
#define VBQ_V4M_ALL(k) ((long4)(k))
#else
#define VBQ_V4M_ALL(k) ((vbq_m4){(k), (k), (k), (k)})
#endif
#endif

typedef struct vbq_walk {
    double c[3], ri;
    double rq0, rq1;
    double in2, out2;            /* node boxes: inside rq0, beyond rq1 */
    const VBQ_SQ vbq_sub *sub;   /* the parts (nsub of them) */
    vbs_u32 i, nsub;
    vbs_u32 ord[VBQ_NSUB];       /* the parts by increasing LO (ties by index) */
#ifdef VBQ_WALK_V4
    /* The parts side by side for vbq_walk_node4, made once per walk
     * (vbq_walk_make) from part g's box and sdist: the ends of the box on
     * each axis, sdist times them, sdist. */
    vbq_v4 pu0[3], pu1[3], pt0[3], pt1[3], psd;
    /* ... and for vbq_walk_parts4: the centre of its box, its magnitude,
     * the box's half-widths, LO. */
    vbq_v4 pm[3], pam[3], ph[3], plo;
#endif
} vbq_walk;

/* A walk from base sphere i over the ring (rq0, rq1], through the nsub
 * parts sub[] (nsub = 0: every sphere of the ring passes; sub unused). */
VBS_FN void vbq_walk_make(const vbq_env *e, vbs_u32 i, double rq0, double rq1,
                          const VBQ_SQ vbq_sub *sub, vbs_u32 nsub, vbq_walk *w)
{
    w->c[0] = e->x[i];
    w->c[1] = e->y[i];
    w->c[2] = e->z[i];
    w->ri = e->r[i];
    w->rq0 = rq0;
    w->rq1 = rq1;
    w->in2 = rq0 > 0.0 ? rq0 * rq0 * (1.0 - 1e-9) : -1.0;
    w->out2 = rq1 * rq1 * (1.0 + 1e-9);
    w->sub = sub;
    w->i = i;
    w->nsub = nsub;
    /* A sphere or node passes when it passes some part: the part with the
     * lowest LO passes the most, so it is asked first (speed only: the
     * same answers). */
    for (vbs_u32 g = 0u; g < nsub; g++) {
        vbs_u32 p = g;
        while (p > 0u && sub[w->ord[p - 1u]].LO > sub[g].LO) {
            w->ord[p] = w->ord[p - 1u];
            p--;
        }
        w->ord[p] = g;
    }
#ifdef VBQ_WALK_V4
    if (nsub == VBQ_NSUB) {
        double u0[3][4], u1[3][4], t0[3][4], t1[3][4], sd[4];
        for (vbs_u32 g = 0u; g < 4u; g++) {
            sd[g] = sub[g].sdist;
            for (int a = 0; a < 3; a++) {
                u0[a][g] = sub[g].m[a] - sub[g].h[a];
                u1[a][g] = sub[g].m[a] + sub[g].h[a];
                t0[a][g] = sd[g] < (double)INFINITY ? sd[g] * u0[a][g] : 0.0;
                t1[a][g] = sd[g] < (double)INFINITY ? sd[g] * u1[a][g] : 0.0;
            }
        }
        for (int a = 0; a < 3; a++) {
            w->pu0[a] = VBQ_V4(u0[a][0], u0[a][1], u0[a][2], u0[a][3]);
            w->pu1[a] = VBQ_V4(u1[a][0], u1[a][1], u1[a][2], u1[a][3]);
            w->pt0[a] = VBQ_V4(t0[a][0], t0[a][1], t0[a][2], t0[a][3]);
            w->pt1[a] = VBQ_V4(t1[a][0], t1[a][1], t1[a][2], t1[a][3]);
            w->pm[a] = VBQ_V4(sub[0].m[a], sub[1].m[a], sub[2].m[a], sub[3].m[a]);
            w->ph[a] = VBQ_V4(sub[0].h[a], sub[1].h[a], sub[2].h[a], sub[3].h[a]);
            w->pam[a] = VBQ_V4_ABS(w->pm[a]);
        }
        w->psd = VBQ_V4(sd[0], sd[1], sd[2], sd[3]);
        w->plo = VBQ_V4(sub[0].LO, sub[1].LO, sub[2].LO, sub[3].LO);
    }
#endif
}

#ifdef VBQ_WALK_V4
/* The parts' half of vbq_walk_node on the host: the four parts in the
 * lanes of one pass instead of one after the other, with no branch per
 * part. Each lane rounds exactly as the loop below does for its part (the
 * same operations in the same order, -ffp-contract=off), and the node
 * passes when some lane passes: the same answer, whatever the order the
 * loop asks the parts in. */
VBS_FN int vbq_walk_node4(const vbq_walk *w, const double b0[3], const double b1[3],
                          double slack, double mag)
{
    vbq_v4 zero = VBQ_V4_ALL(0.0), best = zero, bb2 = zero;
    for (int a = 0; a < 3; a++) {
        vbq_v4 c0 = VBQ_V4_ALL(b0[a]), c1 = VBQ_V4_ALL(b1[a]);
        vbq_v4 p0 = w->pu0[a] * c0, p1 = w->pu0[a] * c1, p2 = w->pu1[a] * c0,
               p3 = w->pu1[a] * c1;
        vbq_v4 mx = VBQ_V4_PICK(p0 > p1, p0, p1);
        mx = VBQ_V4_PICK(p2 > mx, p2, mx);
        mx = VBQ_V4_PICK(p3 > mx, p3, mx);
        best += mx;
        vbq_v4 gp = VBQ_V4_PICK(c0 > w->pt1[a], c0 - w->pt1[a],
                                VBQ_V4_PICK(w->pt0[a] > c1, w->pt0[a] - c1, zero));
        bb2 += gp * gp;
    }
    double lim = -1e-9 * (mag + VBS_FABS(slack) + 1e-300);
    vbq_v4 s4 = VBQ_V4_ALL(slack), m4 = VBQ_V4_ALL(mag), inf = VBQ_V4_ALL((double)INFINITY);
    vbq_v4 reach = (w->psd + s4) * (1.0 + 1e-9) + 1e-9 * (m4 + w->psd);
    /* The scalar loop's own comparisons (a NaN of an unbounded walk fails
     * each of them alike). */
    vbq_m4 fail = (best + s4 < VBQ_V4_ALL(lim)) |
                  ((w->psd < inf) & ((reach < zero) | (bb2 > reach * reach)));
    return !VBQ_M4_ALL(fail);
}
#endif

/* The parts' half of the node test, one part after the other (the parts
 * by increasing LO): box offsets b0, b1 of the node from c_i on each axis,
 * slack = its R_max - R_i, mag = the sum of the offsets' magnitudes. */
VBS_FN int vbq_walk_node1(const vbq_walk *w, const double b0[3], const double b1[3],
                          double slack, double mag)
{
    for (vbs_u32 q = 0u; q < w->nsub; q++) {
        const VBQ_SQ vbq_sub *sg = &w->sub[w->ord[q]];
        double best = 0.0, bb2 = 0.0;
        double sd = sg->sdist;
        for (int a = 0; a < 3; a++) {
            double u0 = sg->m[a] - sg->h[a], u1 = sg->m[a] + sg->h[a];
            double p0 = u0 * b0[a], p1 = u0 * b1[a], p2 = u1 * b0[a], p3 = u1 * b1[a];
            double mx = p0 > p1 ? p0 : p1;
            mx = p2 > mx ? p2 : mx;
            mx = p3 > mx ? p3 : mx;
            best += mx;
            if (sd < (double)INFINITY) {
                double t0 = sd * u0, t1 = sd * u1;
                double gp = b0[a] > t1 ? b0[a] - t1 : (t0 > b1[a] ? t0 - b1[a] : 0.0);
                bb2 += gp * gp;
            }
        }
        if (best + slack < -1e-9 * (mag + VBS_FABS(slack) + 1e-300))
            continue;
        if (sd < (double)INFINITY) {
            double reach = (sd + slack) * (1.0 + 1e-9) + 1e-9 * (mag + sd);
            if (reach < 0.0 || bb2 > reach * reach)
                continue;
        }
        return 1;
    }
    return 0;
}

/* Can node nd hold a sphere that passes the walk? */
VBS_FN int vbq_walk_node(const vbq_env *e, const vbq_walk *w, vbs_u32 nd)
{
#ifndef __OPENCL_C_VERSION__
    const double *bx = e->node8 ? e->node8 + 8u * nd : e->box + 6u * nd;
    double slack = (e->node8 ? bx[6] : e->rmax[nd]) - w->ri;
#else
    const VBS_GLOBAL double *bx = e->box + 6u * nd;
    double slack = e->rmax[nd] - w->ri;
#endif
    double b0[3], b1[3], mag = 0.0, dmax2 = 0.0, dmin2 = 0.0;
    for (int a = 0; a < 3; a++) {
        b0[a] = bx[a] - w->c[a];
        b1[a] = bx[3 + a] - w->c[a];
        mag += VBS_FABS(b0[a]) + VBS_FABS(b1[a]);
        double f = VBS_FABS(b0[a]) > VBS_FABS(b1[a]) ? VBS_FABS(b0[a]) : VBS_FABS(b1[a]);
        dmax2 += f * f;
        double dn = b0[a] > 0.0 ? b0[a] : (b1[a] < 0.0 ? -b1[a] : 0.0);
        dmin2 += dn * dn;
    }
    if (dmax2 < w->in2 || dmin2 > w->out2)
        return 0;
    if (w->nsub == 0u)
        return 1;
#ifdef VBQ_WALK_V4
    if (w->nsub == VBQ_NSUB)
        return vbq_walk_node4(w, b0, b1, slack, mag);
#endif
    return vbq_walk_node1(w, b0, b1, slack, mag);
}

/* Is the sphere at tree position k (id *j) in the walk's ring? 0 when it
 * is the base, within rq0 (in the list or excluded) or beyond rq1 (a
 * later ring's). */
VBS_FN int vbq_walk_ring(const vbq_env *e, const vbq_walk *w, vbs_u32 k, vbs_u32 *j)
{
    *j = e->ids[k];
    if (*j == w->i)
        return 0;
#ifndef __OPENCL_C_VERSION__
    if (e->kx) {
        double dx = e->kx[k] - w->c[0], dy = e->ky[k] - w->c[1], dz = e->kz[k] - w->c[2];
        double d2 = dx * dx + dy * dy + dz * dz;
        return !((w->rq0 > 0.0 && !(d2 > w->rq0 * w->rq0)) || d2 > w->rq1 * w->rq1);
    }
#endif
    double dx = e->x[*j] - w->c[0], dy = e->y[*j] - w->c[1], dz = e->z[*j] - w->c[2];
    double d2 = dx * dx + dy * dy + dz * dz;
    return !((w->rq0 > 0.0 && !(d2 > w->rq0 * w->rq0)) || d2 > w->rq1 * w->rq1);
}

/* vbq_walk_parts one part after the other (by increasing LO; nsub > 0). */
VBQ_FN int vbq_walk_parts1(const vbq_walk *w, const vbq_nb *rec)
{
    for (vbs_u32 q = 0u; q < w->nsub; q++) {
        vbs_u32 g = w->ord[q];
        double m[3] = {w->sub[g].m[0], w->sub[g].m[1], w->sub[g].m[2]};
        double h[3] = {w->sub[g].h[0], w->sub[g].h[1], w->sub[g].h[2]};
        double lo, hi;
        vbq_eval(rec, m, h, &lo, &hi);
        if (hi >= w->sub[g].LO)
            return 1;
    }
    return 0;
}

/* Does a sphere of the ring with record rec pass the walk's parts? With
 * parts, it is kept when its enclosure reaches LO_g in some part g. */
#ifdef VBQ_WALK_V4
/* vbq_walk_parts on the host: vbq_eval of the record over the four parts
 * in the lanes of one pass, each lane the same operations in the same
 * order as vbq_eval for its part; kept when some lane's upper end reaches
 * its part's LO. */
VBQ_FN int vbq_walk_parts4(const vbq_walk *w, const vbq_nb *rec)
{
    vbq_v4 ax = VBQ_V4_ALL(rec->ax), ay = VBQ_V4_ALL(rec->ay), az = VBQ_V4_ALL(rec->az);
    vbq_v4 aax = VBQ_V4_ABS(ax), aay = VBQ_V4_ABS(ay), aaz = VBQ_V4_ABS(az);
    vbq_v4 b = VBQ_V4_ALL(rec->b), err = VBQ_V4_ALL(rec->err);
    vbq_v4 F = ((ax * w->pm[0] + ay * w->pm[1]) + az * w->pm[2]) + b;
    vbq_v4 G = ((aax * w->pam[0] + aay * w->pam[1]) + aaz * w->pam[2]) + VBQ_V4_ABS(b);
    vbq_v4 R = (((aax * w->ph[0] + aay * w->ph[1]) + aaz * w->ph[2]) + err) +
               VBQ_C * (G + VBQ_V4_ABS(F));
    R = R * (1.0 + VBQ_C) + VBQ_TINY;
    return VBQ_M4_ANY(F + R >= w->plo);
}
#endif

VBQ_FN int vbq_walk_parts(const vbq_walk *w, const vbq_nb *rec)
{
    if (w->nsub == 0u)
        return 1;
#ifdef VBQ_WALK_V4
    if (w->nsub == VBQ_NSUB)
        return vbq_walk_parts4(w, rec);
#endif
    return vbq_walk_parts1(w, rec);
}

/* Does the sphere at tree position k (not the base) pass the walk? Fills
 * its record when so. Spheres within rq0 are in the list or were excluded;
 * those beyond rq1 belong to a later ring; with parts, a sphere is kept
 * when its enclosure reaches LO_g in some part g. */
VBS_FN int vbq_walk_sphere(const vbq_env *e, const vbq_walk *w, vbs_u32 k, vbq_nb *rec)
{
    vbs_u32 j;
    if (!vbq_walk_ring(e, w, k, &j))
        return 0;
    vbq_nb_make(w->c[0], w->c[1], w->c[2], w->ri, e->x[j], e->y[j], e->z[j], e->r[j], j, rec);
    return vbq_walk_parts(w, rec);
}

#ifdef VBQ_CACHES
/* vbq_walk_sphere with the memo: the record of (cell, sphere) depends on
 * nothing else, so one made at an earlier fetch of the cell is the same
 * double for double (speed only). */
VBS_FN int vbq_walk_sphere_known(const vbq_env *e, const vbq_arena *ar, const vbq_walk *w,
                                 vbs_u32 k, vbs_u32 j, vbq_nb *rec)
{
    vbs_u32 s = k & (VBQ_MEMO - 1u);
    VBS_GLOBAL vbs_u32 *tag = ar->memo_tag + 2u * s;
    if (tag[0] == k && tag[1] == w->i + 1u) {
        *rec = ar->memo[s];
#ifndef __OPENCL_C_VERSION__
    } else if (e->kx) {
        vbq_nb_make(w->c[0], w->c[1], w->c[2], w->ri, e->kx[k], e->ky[k], e->kz[k], e->kr[k], j,
                    rec);
        ar->memo[s] = *rec;
        tag[0] = k;
        tag[1] = w->i + 1u;
#endif
    } else {
        vbq_nb_make(w->c[0], w->c[1], w->c[2], w->ri, e->x[j], e->y[j], e->z[j], e->r[j], j,
                    rec);
        ar->memo[s] = *rec;
        tag[0] = k;
        tag[1] = w->i + 1u;
    }
    return vbq_walk_parts(w, rec);
}

VBS_FN int vbq_walk_sphere_memo(const vbq_env *e, const vbq_arena *ar, const vbq_walk *w,
                                vbs_u32 k, vbq_nb *rec)
{
    vbs_u32 j;
    return vbq_walk_ring(e, w, k, &j) && vbq_walk_sphere_known(e, ar, w, k, j, rec);
}
#endif

#if defined(VBQ_WALK_V4) && !defined(__OPENCL_C_VERSION__)
/* vbq_walk_ring's distance test for the leaf's positions k0 .. k0 + 7 at
 * once (the kx arrays run a leaf past m): bit k - k0 set where the sphere
 * is in the ring by the same comparisons (the base itself is left to the
 * caller). */
static inline unsigned vbq_walk_ring8(const vbq_env *e, const vbq_walk *w, vbs_u32 k0)
{
    unsigned bits = 0u;
    double r0 = w->rq0 * w->rq0, r1 = w->rq1 * w->rq1;
    vbq_v4 in0 = VBQ_V4_ALL(r0), out1 = VBQ_V4_ALL(r1);
    vbq_m4 near = VBQ_V4M_ALL(w->rq0 > 0.0 ? -1LL : 0LL);
    for (vbs_u32 h = 0u; h < 8u; h += 4u) {
        const double *px = e->kx + k0 + h, *py = e->ky + k0 + h, *pz = e->kz + k0 + h;
        vbq_v4 x = VBQ_V4(px[0], px[1], px[2], px[3]), y = VBQ_V4(py[0], py[1], py[2], py[3]);
        vbq_v4 z = VBQ_V4(pz[0], pz[1], pz[2], pz[3]);
        vbq_v4 dx = x - VBQ_V4_ALL(w->c[0]), dy = y - VBQ_V4_ALL(w->c[1]),
               dz = z - VBQ_V4_ALL(w->c[2]);
        vbq_v4 d2 = dx * dx + dy * dy + dz * dz;
        vbq_m4 out = (near & ~(d2 > in0)) | (d2 > out1);
        for (int l = 0; l < 4; l++)
            bits |= (out[l] ? 0u : 1u) << (h + (unsigned)l);
    }
    return bits;
}
#endif

/* The tree positions [*k0, *k1) of leaf node nd's spheres. */
VBS_FN void vbq_walk_leaf(const vbq_env *e, vbs_u32 nd, vbs_u32 *k0, vbs_u32 *k1)
{
    *k0 = (nd - e->first) * VBQ_LEAF;
    *k1 = *k0 + VBQ_LEAF < e->m ? *k0 + VBQ_LEAF : e->m;
}

#ifndef VBQ_GROUP_ONLY
/* The walk on one work-item, depth first: passing spheres appended to nb
 * and to the list at lab[off + *len ...]; those of a ring fetched through
 * parts count as far. Returns 0 when an arena is full. */
VBS_FN int vbq_walk_gather(const vbq_env *e, const vbq_arena *ar, vbq_cell_out *o,
                           const vbq_walk *w, vbs_u32 off, vbs_u32 *len)
{
    vbs_u32 stack[VBQ_STACK], ns = 0;
    if (e->m)
        stack[ns++] = 1u;
    while (ns) {
        vbs_u32 nd = stack[--ns];
        if (!vbq_walk_node(e, w, nd))
            continue;
        if (nd < e->first) {
            stack[ns++] = 2u * nd + 1u;
            stack[ns++] = 2u * nd;
            continue;
        }
        vbs_u32 k0, k1;
        vbq_walk_leaf(e, nd, &k0, &k1);
#if defined(VBQ_WALK_V4) && !defined(__OPENCL_C_VERSION__)
        unsigned ring = e->kx && ar->memo ? vbq_walk_ring8(e, w, k0) : 0u;
#endif
        for (vbs_u32 k = k0; k < k1; k++) {
            vbq_nb rec;
#if defined(VBQ_WALK_V4) && !defined(__OPENCL_C_VERSION__)
            if (e->kx && ar->memo) {
                vbs_u32 j = e->ids[k];
                if (!((ring >> (k - k0)) & 1u) || j == w->i ||
                    !vbq_walk_sphere_known(e, ar, w, k, j, &rec))
                    continue;
            } else
#endif
#ifdef VBQ_CACHES
            if (ar->memo ? !vbq_walk_sphere_memo(e, ar, w, k, &rec)
                         : !vbq_walk_sphere(e, w, k, &rec))
                continue;
#else
            if (!vbq_walk_sphere(e, w, k, &rec))
                continue;
#endif
            if (w->nsub)
                o->far++;
            if (o->nnb >= ar->nb_cap) {
                o->status = VBQ_OVER_NB;
                return 0;
            }
            ar->nb[o->nnb++] = rec;
            if (off + *len >= ar->lab_cap) {
                o->status = VBQ_OVER_LAB;
                return 0;
            }
            ar->lab[off + (*len)++] = o->nnb - 1u;
        }
    }
    return 1;
}
#endif

#endif
