/* Atom selections (--select EXPR, Python select=): a small grammar over the
 * atom records, in the spirit of VMD's and MDAnalysis' selections.
 *
 *   expr    := term { "or" term }
 *   term    := factor { "and" factor }
 *   factor  := "not" factor | "(" expr ")" | "all" | "protein" | "water"
 *            | KEYWORD value { value }
 *   KEYWORD := chain | segid | resname | resid | name | element
 *
 * Several values after a keyword mean any of them ("resname FRU GLC").
 * resid takes numbers and ranges a:b (inclusive; negative numbers allowed);
 * name and resname take '?' (one character) and '*' (any run) wildcards.
 * chain and segid compare exactly; resname, name and element ignore case.
 * Keywords and operators ignore case. protein: the 20 amino acids and the
 * force fields' variants of them (HSD, HIE, CYX, ...); water: the residue
 * names vorball drops as water (HOH, WAT, ...). Spheres without atom
 * records (XYZR) match nothing but "all". */
#ifndef VB_SELECT_H
#define VB_SELECT_H

#include "vb_spheres.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct vb_select vb_select;

/* Parses expr. On success *out owns the selection (free with
 * vb_select_free). A malformed expression is VB_EINPUT_SELECT (E118) with
 * its 1-based character position in the message; VB_ENOMEM. */
int vb_select_parse(vb_ctx *ctx, const char *expr, vb_select **out);

/* 1 when the atom record a (NULL: a sphere without one) matches. */
int vb_select_match(const vb_select *sel, const vb_atom_info *a);

void vb_select_free(vb_select *sel);

/* The spheres i of s with keep[i] != 0, in their order, as a new set (*out,
 * free with vb_spheres_free; exact decimals, lines, atom records and box
 * kept). VB_ENOMEM. */
int vb_spheres_subset(vb_ctx *ctx, const vb_sphere_set *s, const uint8_t *keep, vb_sphere_set **out);

/* The spheres of s that expr selects, in their order, as a new set (*out,
 * free with vb_spheres_free; exact decimals, lines, box and flags kept).
 * VB_EINPUT_SELECT when expr is malformed or selects no sphere; VB_ENOMEM. */
int vb_spheres_select(vb_ctx *ctx, const vb_sphere_set *s, const char *expr, vb_sphere_set **out);

#ifdef __cplusplus
}
#endif

#endif
