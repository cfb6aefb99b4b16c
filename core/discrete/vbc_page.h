/* The channels of a frame on the results page (core/page/vb_page.h). */
#ifndef VBC_PAGE_H
#define VBC_PAGE_H

#include "vb_page.h"
#include "vbc_channel.h"

/* Adds frame `label` to page p: the atoms of s where the frame has them
 * (s has the page's atom count), every kept channel, pore and cavity of res
 * as a path named as the table's rows ("pore 1", "channel 2", ...), the
 * pore's radius profile along its axis when there is a pore, and the
 * frame's figures: the counts of pores, channels and cavities and each
 * row's bottleneck radius and length, written as the CSV table writes them
 * (%.3f). VB_OK, VB_ENOMEM (message in the page's context). */
int vbc_page_add(vb_page *p, const char *label, const vb_sphere_set *s, const vbc_result *res);

#endif
