/* The pore of a channel protein as HOLE and CHAP users know it: a path along
 * an axis, one point per plane normal to the axis, each point the centre of
 * the largest sphere in its plane that overlaps no atom (Smart et al. 1993,
 * 1996: R(p) = min_i |X_i - p| - vdW_i, maximised with p kept on the plane).
 * The path passes constrictions of any radius, narrower than the probe too,
 * and closed gates (radius <= 0 there): the probe only defines the molecular
 * surface, i.e. where the path leaves the molecule (its mouths).
 *
 * The radii are doubles, not certified quantities. Each R(p) is a minimum
 * of sqrt(dx^2 + dy^2 + dz^2) - r evaluated in double: with coordinates
 * below 1e4 A its rounding error is below 1e-11 A (each term: relative error
 * 3u of a length < 3e4 A, plus u of r); the in-plane maximisation stops
 * when no direction gains more than 1e-7 A. Both are far below the voxel
 * edges (0.1-0.6 A) that the comparison with HOLE is judged against.
 *
 * Axis: given (--axis, --through: HOLE's cvect/cpoint), or found: the
 * symmetry axis of three or more chains of equal size (normal of the plane
 * of their centroids, through their mean), the line through the centroids
 * of two stacked chains (a head-to-head dimer as gramicidin A), else the
 * direction of the widest through channel of the discrete analysis, else
 * the principal axis of the molecule whose sweep is open and widest. When
 * the symmetry axis of three or more chains is nearly closed (below
 * VBC_SUBUNIT_CENTRAL_MAX) and a sweep parallel to it through one chain's
 * centroid is open at both ends and clearly wider (above
 * VBC_SUBUNIT_MIN_RADIUS and twice the central radius) and a pore by the
 * verdict below, that subunit's pore is the pore (a porin trimer; a closed
 * gate on the axis of a tetrameric channel stays the pore, its subunits
 * hold no open pore: a path through a voltage sensor's crevice or along
 * the outside is walled too little to count). */
#ifndef VBC_PORE_H
#define VBC_PORE_H

#include "vbc_channel.h"

enum vbc_axis_source {
    VBC_AXIS_NONE = 0,
    VBC_AXIS_GIVEN,     /* --axis (and --through) */
    VBC_AXIS_CHAINS,    /* symmetry of the chains */
    VBC_AXIS_CHANNEL,   /* a through channel of the discrete analysis */
    VBC_AXIS_PRINCIPAL, /* a principal axis of the atom centres */
    VBC_AXIS_SUBUNIT,   /* the chains' symmetry axis moved to one chain's centroid (or its barrel) */
    VBC_AXIS_SYMMETRY,  /* the C_n axis of n >= 3 equal chains, by superposition */
    VBC_AXIS_BARREL,    /* the cylinder of a beta-barrel's strands */
    VBC_AXIS_MEMBRANE   /* the normal of the membrane left out (channel_membrane.c) */
};

/* The subunit rule above, in A. */
#define VBC_SUBUNIT_CENTRAL_MAX 1.0
#define VBC_SUBUNIT_MIN_RADIUS 1.0
#define VBC_SUBUNIT_REACH 12.0 /* a subunit's sweep starts at its widest place this near its centroid */

typedef struct vbc_axis {
    double u[3];   /* unit direction; the axial coordinate is s = p . u */
    double c[3];   /* where the sweep starts */
    int source;    /* enum vbc_axis_source */
    int chains;    /* chains used (VBC_AXIS_CHAINS); the chain's rank (VBC_AXIS_SUBUNIT) */
    char why[128];  /* how it was found, in words (the channels JSON's axis_why, note W810) */
} vbc_axis;

/* The order in which the axis sources are tried when the user gives none
 * (vbc_pore_find; the first whose sweep is open wins, the symmetry axis in
 * any case):
 *   0. membrane  when --membrane left membrane atoms out of the frame, the
 *                normal of their planes (vbc_membrane_normal), through the
 *                centroid of the atoms kept; a symmetry axis of three or
 *                more chains or a barrel axis within VBC_MEMBRANE_AGREE
 *                degrees of it takes its place (the same direction fitted
 *                to the channel, with its subunits' or cone's search);
 *                then only the symmetry, chains and barrel axes follow, an
 *                open one (a closed normal) or the symmetry axis replacing
 *                it; no channel or principal axis (a pore across a
 *                membrane runs along its normal, a closed one stays there:
 *                the pore is closed; an open path the verdict rejects is
 *                no pore, W808);
 *   1. symmetry  n >= 3 chains of the same sequence whose C-alpha atoms
 *                superpose onto their neighbours' by one rotation of 360/n
 *                degrees about one axis (vbc_axis_symmetry); when its sweep
 *                is nearly closed, each subunit's own pore (its barrel axis
 *                when it is a barrel, else the symmetry direction through its
 *                centroid; the rule below), source subunit;
 *   2. chains    the centroid rule of vbc_axis_from_chains (two stacked
 *                chains; three or more of equal size that did not superpose);
 *   3. barrel    the cylinder fitted to the extended C-alpha atoms of the
 *                largest chain, when they make a barrel (vbc_axis_barrel);
 *   4. channel   the widest through channel of the discrete analysis;
 *   5. principal the three principal axes of the atom centres, the open one
 *                with the widest constriction.
 * `axis_why` in the channels JSON and note W810 say which, in words. */

/* Eigenvalues (descending) and unit eigenvectors (columns of v) of the
 * symmetric 3x3 matrix a, by cyclic Jacobi rotations. */
void vbc_eigen3(const double a[3][3], double w[3], double v[3][3]);

/* Flips u so that its largest component is positive (a stable orientation). */
void vbc_axis_orient(double u[3]);

/* The axis of the source that found `first` (its source; for a subunit its
 * chain's rank, for a principal axis the one nearest first's direction)
 * fitted again on s (a later frame of a trajectory), oriented along
 * first's direction. Returns 1 with *out filled; 0 for a source that is
 * not refitted (given, channel) or that s no longer shows. */
int vbc_axis_refit(const vb_sphere_set *s, const vbc_axis *first, vbc_axis *out);

/* The C_n symmetry axis (core/discrete/channel_symmetry.c): the largest set
 * of n >= 3 chains with the same C-alpha residue sequence (at least
 * VBC_SYM_MIN_CA of them each), ordered around the normal of their
 * centroids' plane; the axis direction is the one that the displacements of
 * corresponding C-alpha atoms from each chain to the next are all normal to
 * (the least eigenvector of their scatter), through the mean of the
 * chains' centroids. Accepted when rotating each chain by 360/n degrees
 * about that axis lands on the next with an rms below VBC_SYM_MAX_RMS A.
 * Returns 1 with *out filled (source SYMMETRY, chains n, why), else 0. */
int vbc_axis_symmetry(const vb_sphere_set *s, vbc_axis *out);
#define VBC_SYM_MIN_CA 8
#define VBC_SYM_MAX_RMS 3.0
/* Chains resolved over different stretches still count as one protein
 * when this share of the longer one's C-alpha atoms match the other's by
 * residue number and name; the fit then uses the residues all of them hold
 * (a tetrameric channel whose subunits miss different loop residues). */
#define VBC_SYM_MIN_SHARED 0.75

/* The axis of a beta-barrel (core/discrete/channel_barrel.c) made by the
 * chain `chain` of s (NULL: the chain with most C-alpha atoms): its
 * extended C-alpha atoms (the i-1 to i+1 distance above VBC_BARREL_EXTENDED
 * A, as in a strand, in runs of VBC_BARREL_MIN_RUN or more: strands, not
 * turns; at least VBC_BARREL_MIN_CA of them) are fitted by a
 * cylinder: the direction (a deterministic search over the hemisphere, then
 * refined) along which their projections lie closest to a circle (algebraic
 * circle fit; relative rms of the radii below VBC_BARREL_MAX_SPREAD, a
 * radius of 5-40 A, the atoms around all eight 45-degree sectors). The axis
 * passes through the circle's centre at the atoms' mean height. Returns 1
 * with *out filled (source BARREL, why), else 0. */
int vbc_axis_barrel(const vb_sphere_set *s, const char *chain, vbc_axis *out);
#define VBC_BARREL_EXTENDED 6.0
#define VBC_BARREL_MIN_RUN 5
#define VBC_BARREL_MIN_CA 24
#define VBC_BARREL_MAX_SPREAD 0.2
/* The pore of a barrel (channel_pore_frame.c: the fitted axis and a cone
 * of directions around it, the widest open pore taken). */
#define VBC_BARREL_CONE 8
#define VBC_BARREL_TILT 4.0

/* The normal of a membrane (core/discrete/channel_membrane.c): the atoms of
 * s whose residue names are among names (n of them; --membrane's), of them
 * OPM's dummy atoms (DUM) when there are VBC_MEMBRANE_MIN_ATOMS, else the
 * lipids' head-group phosphorus (atom name P), else all. Each principal
 * axis of those atoms splits them in two halves (the leaflets, or OPM's two
 * planes) through their mean; the least eigenvector of the halves' scatter,
 * each about its own mean, is the normal of that split, and the split whose
 * least eigenvalue is smallest wins. Accepted when that eigenvalue is below
 * VBC_MEMBRANE_FLAT times the middle one (the leaflets are flat) and the
 * middle one's rms is VBC_MEMBRANE_MIN_RMS A or more (a membrane patch, not
 * a few lipids or detergents bound to a protein). Returns 1
 * with out->u (oriented by vbc_axis_orient), source MEMBRANE and why filled
 * (out->c is the caller's to set), 0 when they are not flat or fewer
 * than VBC_MEMBRANE_MIN_ATOMS, -1 out of memory. A lattice of OPM dummy
 * atoms 32 A wide has an rms of 9.8 A; YiiP's bilayer (MDAnalysis) 28 A. */
int vbc_membrane_normal(const vb_sphere_set *s, const char *const *names, size_t n, vbc_axis *out);
#define VBC_MEMBRANE_MIN_ATOMS 3
/* A symmetry axis (three or more chains) or a barrel axis within this many
 * degrees of the membrane's normal takes its place (vbc_pore_find). */
#define VBC_MEMBRANE_AGREE 30.0
#define VBC_MEMBRANE_FLAT 0.25
#define VBC_MEMBRANE_MIN_RMS 8.0

/* A short name of the axis source ("given", "chains", "channel",
 * "principal", "subunit", "symmetry", "barrel", "membrane", "none"). */
const char *vbc_axis_source_name(int source);

/* The axis from the chains of s (s->info): three or more chains of at
 * least 8 atoms whose sizes differ by at most 25% and whose centroids lie
 * at similar distances (within 35%) from their mean give the normal of the
 * centroids' best plane (through the mean; oriented so that the largest
 * component is positive); two such chains whose centroids are farther
 * apart than 40% of the molecule's extent along that line give the line
 * through them. Returns 1 with *out filled, 0 when the chains say nothing. */
int vbc_axis_from_chains(const vb_sphere_set *s, vbc_axis *out);

/* One pore per subunit (porins, aquaporins: the pores run through the
 * monomers, parallel to the symmetry axis, and the axis itself is the
 * closed interface between them): the direction of sym (an axis from
 * vbc_axis_from_chains with three or more chains) through the centroid of
 * each of those chains, in the order of their first atoms, source SUBUNIT
 * and `chains` the chain's rank (1-based). Writes at most max axes to out
 * and returns how many. */
int vbc_axis_subunits(const vb_sphere_set *s, const vbc_axis *sym, vbc_axis *out, int max);

/* The principal axes of the atom centres (eigenvectors of their covariance,
 * largest variance first), through the centroid, source PRINCIPAL. */
void vbc_axis_principal(const vb_sphere_set *s, vbc_axis out[3]);

/* One plane of the sweep. */
typedef struct vbc_pore_point {
    double s;          /* axial coordinate p . u, A */
    double x, y, z;    /* the sphere centre */
    double r;          /* its radius, A: distance to the nearest atom surface */
    int32_t atom;      /* the nearest atom */
} vbc_pore_point;

typedef struct vbc_pore_options {
    double step;        /* A between planes (HOLE's sample: 0.25) */
    double end_radius;  /* a side ends where the radius exceeds this (HOLE's endrad); 0: none */
    double max_half;    /* A from the start on each side at most; 0: the molecule's extent */
} vbc_pore_options;

/* Whether a point lies outside the molecule (the probe's molecular mask):
 * the sweep ends there. user is the caller's. */
typedef int (*vbc_outside_fn)(void *user, const double p[3]);

typedef struct vbc_pore {
    vbc_axis axis;
    vbc_pore_point *pts;   /* increasing s */
    size_t n;
    size_t min_at;         /* index of the smallest radius */
    int open_lo, open_hi;  /* that end left the molecule (else: end radius, length) */
    double F;              /* sum ds / (pi r^2) over the points, 1/A (HOLE's geometric factor) */
    double g_macro_pS;     /* 100 / (rho F) with rho = 1/12 ohm m (1 M KCl): HOLE's Gmacro */
    int judged;            /* the verdict (enough VBC_PORE_MIN_BURIED) was taken already: */
    int is_pore;           /* its is_pore */
    double buried;         /* and buried */
} vbc_pore;

/* HOLE's resistivity of 1 M KCl, ohm m. */
#define VBC_RHO_KCL (1.0 / 12.0)

/* Maximises R over the plane through p normal to u (unit), moving p, and
 * returns R with the nearest atom in *atom; `travel` > 0 keeps p within
 * that distance of where it started. Deterministic: steepest ascent of the
 * max-min on the eps-active atoms (min-norm point of their in-plane
 * gradients), eps shrinking to 1e-7 A. */
double vbc_plane_maximise(const vbc_cells *c, const double u[3], double travel, double p[3],
                          int32_t *atom);

/* The widest place inside the molecule in the plane through p normal to u
 * within `reach` A of p: the best of a 0.5 A lattice on that disc without
 * the points where outside(user, q) (scan order breaks ties; p itself
 * when none is wider), then vbc_plane_maximise from there within reach,
 * kept when it stays inside. Moves p there, returns R and the nearest atom
 * in *atom. For a start point that the local ascent alone would not find
 * (a pore beside a loop that fills the middle of a subunit). outside may
 * be NULL (every point inside). */
double vbc_plane_widest(const vbc_cells *c, const double u[3], double reach, vbc_outside_fn outside,
                        void *user, double p[3], int32_t *atom);

/* How far the sweep looks around the previous plane's centre in each plane
 * (vbc_plane_widest) besides the local ascent, A. */
#define VBC_PLANE_LOOK 1.5

/* The sweep: from ax->c both ways along ax->u, one plane every opt->step,
 * each started from the previous plane's centre (the local ascent from it
 * or from the widest lattice point within VBC_PLANE_LOOK, the wider); a side stops at the first
 * point outside the molecule (outside(user, p), when outside is not NULL),
 * beyond opt->end_radius, or beyond opt->max_half. Fills *out (free with
 * vbc_pore_free), its points sorted by s, F and Gmacro over them.
 * VB_ENOMEM, VB_EMISUSE for a bad axis or step. */
int vbc_pore_sweep(vb_ctx *ctx, const vbc_cells *c, const vb_sphere_set *s, const vbc_axis *ax,
                   const vbc_pore_options *opt, vbc_outside_fn outside, void *user, vbc_pore *out);

/* vbc_pore_sweep for a caller that only wants a pore wider than floor (the
 * best of several candidates so far): it gives up as soon as a plane's
 * radius is at or below floor, such a pore's bottleneck being no wider,
 * and then returns VB_OK with out->n == 0 (nothing to free). floor
 * -INFINITY: vbc_pore_sweep. */
int vbc_pore_sweep_above(vb_ctx *ctx, const vbc_cells *c, const vb_sphere_set *s,
                         const vbc_axis *ax, const vbc_pore_options *opt, vbc_outside_fn outside,
                         void *user, double floor, vbc_pore *out);

/* HOLE's macroscopic conductance of a profile (Smart et al. 1996: the pore
 * as a stack of slabs of electrolyte of resistivity rho, G^-1 = rho sum
 * ds / A(s)): F = sum over the points of ds / (pi r^2), each point the
 * middle of a slab reaching half way to its neighbours (the end points: the
 * whole gap to their one neighbour); a point with r <= 0 closes the pore (F
 * infinite, G 0). G = 100 / (rho F) pS for rho in ohm m and F in 1/A
 * (1/(rho F) with F in 1/m is 1e-10/(rho F) S). */
void vbc_pore_conductance(vbc_pore *p, double rho);

void vbc_pore_free(vbc_pore *p);

/* The pore verdict: a path found by the sweep is a pore only when it
 * crosses the molecule walled by the molecule's atoms. A plane's sphere is
 * walled when a disc of radius VBC_WALL_PROBE (a small solvent molecule)
 * cannot move in the plane from the sphere to VBC_WALL_REACH + 2 r from its
 * centre (at most VBC_WALL_MAX_REACH) without overlapping an atom: the
 * plane is rastered at VBC_WALL_PIXEL and flooded from the sphere, a pixel
 * free when no atom surface lies within the probe of it (so gaps between
 * the atoms of a helix or a barrel wall, narrower than the probe, are
 * wall). The buried length is the axial span of the longest run of walled
 * planes, open gaps up to VBC_WALL_GAP long bridged (a missing cap at the
 * junction of a dimer, a side window); a pore needs VBC_PORE_MIN_BURIED. A groove or
 * cleft on the surface of a soluble protein opens sideways within a few
 * planes; the tunnels of its packing stay short: measured on the 2-core
 * machine, crambin 8.8 A, 3njw 8.5 A, adenylate kinase 0 A; gramicidin A
 * 23.5 A, cholera toxin 28.2 A, maltoporin 27.5 A (their pores; papers/
 * facet-jfa-and-channels/channels/verdict_2core.md). */
#define VBC_WALL_PROBE 1.0
#define VBC_WALL_PIXEL 0.5
#define VBC_WALL_REACH 12.0
#define VBC_WALL_MAX_REACH 60.0
#define VBC_PORE_MIN_BURIED 15.0
#define VBC_WALL_GAP 3.0

typedef struct vbc_pore_verdict {
    size_t walled;          /* planes whose sphere is walled */
    double buried;          /* A: axial span of the longest walled run */
    size_t run_lo, run_hi;  /* that run's first and last points */
    int is_pore;            /* buried >= VBC_PORE_MIN_BURIED */
} vbc_pore_verdict;

/* The basis of the verdict's raster in the plane normal to u (unit): a
 * normal to u (u x x, or u x y when u is near x), then b = u x a. */
void vbc_plane_basis(const double u[3], double a[3], double b[3]);

/* Whether the sphere of radius r at p, in the plane normal to u (unit), is
 * walled (the rule above). *scratch (realloc'ed, *scratch_len bytes; start
 * with NULL, 0; free it) is reused between calls. Returns 1 walled, 0 not,
 * -1 out of memory. */
int vbc_plane_walled(const vbc_cells *c, const double u[3], const double p[3], double r,
                     void **scratch, size_t *scratch_len);

/* Threads for `items` independent pieces of a pore step, `per` a thread
 * at least (a thread's start and join cost tens of microseconds, about
 * what a plane or a channel does): vb_threads, at most items / per, and 1
 * on fewer than VBC_PORE_MIN_THREADS (on the 2-core machine, loaded by
 * other work, the starts cost milliseconds: adk_oplsaa's verdict 1.7 ->
 * 6.6 ms a frame on 2 threads; with the resident pool, stop 44, still
 * 1.7 -> 6.3 ms, and 1chb's 10.1 -> 11.4: papers/facet-jfa-and-channels/
 * channels/pool_2core_stop44.md). */
int vbc_pore_threads(size_t items, size_t per);
#define VBC_PORE_MIN_THREADS 4

/* Judges the pore p (its points, axis) against the atoms of c, plane by
 * plane from the first point; stops once a run's buried length reaches
 * `enough` (INFINITY: every plane, the longest run; VBC_PORE_MIN_BURIED:
 * the verdict alone, its planes past that unflooded, buried then that
 * run's length so far). The planes are flooded on vbc_pore_threads(n, 32)
 * threads, each taking the next run of 4 planes as it ends the last, and
 * scanned in order as they come; no plane is started once the scan has its
 * answer: the same verdict on any number of threads. Returns 0 with *v
 * filled, -1 out of memory. */
int vbc_pore_judge(const vbc_cells *c, const vbc_pore *p, double enough, vbc_pore_verdict *v);

#endif
