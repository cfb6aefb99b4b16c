/* The bits of the channel masks' per-voxel flag byte and of the compacted
 * channel voxels: what a caller reads in a flag volume (vbc_channel_pipe.h,
 * --volume-mask), and what the mask stage writes on either side
 * (channel_math.h, compiled as C11 and as OpenCL C). Plain constants only. */
#ifndef VBC_FLAGS_H
#define VBC_FLAGS_H

/* Bits of the per-voxel flag byte written by the mask stage. */
#define VBC_F_ATOMIC 1u   /* inside a ball of radius r_atom + r_solvent (AM) */
#define VBC_F_MOLECULAR 2u /* between the first and last AM hit of some axis ray (MM) */
#define VBC_F_EDGE 4u     /* Voronoi edge: enough distinct labels around (VE) */
#define VBC_F_INTERIOR 8u /* AM xor MM */
#define VBC_F_CHANNEL 16u /* VE and interior */
#define VBC_F_MOUTH 32u   /* channel voxel with a face neighbour outside MM */

/* Compacted channel voxels carry the mouth flag in the top bit of the index. */
#define VBC_MOUTH_BIT 0x80000000u

#endif
