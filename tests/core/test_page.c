/* The results page (core/page): one self-contained HTML file with the
 * viewer and the page's script embedded, the command's data as JSON that
 * cannot end the <script> element early, every frame with its coordinates
 * when there is a slider, and no file left behind when the write fails. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "vb.h"
#include "vb_page.h"
#include "vbp_assets.h"
#include "vb_test.h"

static int count(const char *hay, const char *needle)
{
    int k = 0;
    for (const char *p = hay; (p = strstr(p, needle)); p++)
        k++;
    return k;
}

int main(void)
{
    vb_ctx *ctx = NULL;
    CHECK_INT(vb_open(&ctx, NULL), VB_OK);
    double x[] = {1, 4.25, -2}, y[] = {2, 0, 0.5}, z[] = {3, 0, 7}, r[] = {1.7, 1.52, 1.8};
    vb_atom_info info[3];
    memset(info, 0, sizeof info);
    const char *names[] = {"CA", "O", "N"}, *els[] = {"C", "O", "N"};
    for (int i = 0; i < 3; i++) {
        strcpy(info[i].name, names[i]);
        strcpy(info[i].resname, "GLY");
        strcpy(info[i].chain, "B");
        strcpy(info[i].element, els[i]);
        info[i].resseq = 7 + i;
        info[i].icode = ' ';
        info[i].altloc = ' ';
    }
    vb_sphere_set s = {.n = 3, .x = x, .y = y, .z = z, .r = r, .info = info, .source = "in.pdb"};
    vb_page *p = vb_page_new(ctx, "channels </script><b>x</b> & co", &s);
    CHECK(p != NULL);
    int k0 = -2, k1 = -2;
    CHECK_INT(vb_page_frame(p, "frame 0", NULL, &k0), VB_OK);
    CHECK_INT(k0, 0);
    double moved[9] = {1.5, 2, 3, 4.25, 0, 0, -2, 0.5, 7.125};
    CHECK_INT(vb_page_frame(p, "frame 1", moved, &k1), VB_OK);
    CHECK_INT(k1, 1);
    double cx[6] = {0, 0, -1, 0, 0, 1}, cr[2] = {0.9, 2.5}, cs[2] = {-1, 1};
    CHECK_INT(vb_page_path(p, 1, "channel 1", 2, cx, cr), VB_OK);
    CHECK_INT(vb_page_profile(p, 1, "pore", 2, cs, cr), VB_OK);
    CHECK_INT(vb_page_fact(p, 1, "bottleneck radius (Å)", "0.900"), VB_OK);
    CHECK_INT(vb_page_fact(p, 0, "channels", "0"), VB_OK);
    CHECK_INT(vb_page_fact_count(p, 0, "atoms", 3), VB_OK);
    double vals[3] = {10.5, NAN, 30};
    CHECK_INT(vb_page_atom_values(p, 0, "volume", vals), VB_OK);
    double sas[3] = {1, 2, 3}, vx[3] = {0, 0, 0.5}, vr[1] = {1.25};
    CHECK_INT(vb_page_atom_values(p, 0, "sas", sas), VB_OK);
    CHECK_INT(vb_page_points(p, 0, "vertices", 1, vx, vr), VB_OK);
    CHECK_INT(vb_page_points(p, 3, "vertices", 1, vx, vr), VB_EMISUSE);
    /* A frame that does not exist is misuse, not a crash. */
    CHECK_INT(vb_page_fact(p, 2, "k", "v"), VB_EMISUSE);

    char dir[] = "/tmp/vb-page-XXXXXX";
    CHECK(mkdtemp(dir) != NULL);
    char path[256], bad[256];
    snprintf(path, sizeof path, "%s/page.html", dir);
    snprintf(bad, sizeof bad, "%s/missing/page.html", dir);
    if (!vb_page_viewer_available()) {
        /* Built without NGL: refused with a message saying how to get it,
         * before the work (vb_page_check) and when writing. */
        CHECK_INT(vb_page_check(ctx, path), VB_EMISUSE);
        CHECK(strstr(vb_errmsg(ctx), ".ci/viewer") != NULL);
        CHECK_INT(vb_page_write(p, path), VB_EMISUSE);
        CHECK(strstr(vb_errmsg(ctx), ".ci/viewer") != NULL);
        CHECK(access(path, F_OK) != 0);
    } else {
        CHECK_INT(vb_page_check(ctx, path), VB_OK);
        CHECK_INT(vb_page_write(p, path), VB_OK);
        char *html = vb_test_slurp(path);
        CHECK(html != NULL);
        CHECK(strncmp(html, "<!DOCTYPE html>", 15) == 0);
        /* Title escaped in the markup and in the data. */
        CHECK(strstr(html, "<title>channels &lt;/script&gt;&lt;b&gt;x&lt;/b&gt; &amp; co</title>") != NULL);
        char *data = strstr(html, "<script type=\"application/json\" id=\"vb-data\">");
        CHECK(data != NULL);
        char *end = strstr(data + 10, "</script>");
        CHECK(end != NULL);
        *end = 0;
        CHECK(strstr(data, "\\u003c/script\\u003e") != NULL);
        CHECK(strstr(data, "\"atoms\":3,\"annotated\":true") != NULL);
        /* PDB records with the radius in the B-factor column. */
        CHECK(strstr(data, "ATOM      1  CA  GLY B   7       1.000   2.000   3.000  1.00  1.70           C") != NULL);
        CHECK(strstr(data, "ATOM      3  N   GLY B   9      -2.000   0.500   7.000  1.00  1.80           N") != NULL);
        /* Both frames carry coordinates (slider); frame 1's moved atoms. */
        CHECK(strstr(data, "\"label\":\"frame 0\",\"xyz\":[1.000,2.000,3.000,4.250,0.000,0.000,-2.000,0.500,7.000]") != NULL);
        CHECK(strstr(data, "\"xyz\":[1.500,2.000,3.000,4.250,0.000,0.000,-2.000,0.500,7.125]") != NULL);
        CHECK(strstr(data, "\"paths\":[{\"name\":\"channel 1\",\"xyz\":[0.000,0.000,-1.000,0.000,0.000,1.000],\"r\":[0.9,2.5]}]") != NULL);
        CHECK(strstr(data, "\"profiles\":[{\"name\":\"pore\",\"s\":[-1,1],\"r\":[0.9,2.5]}]") != NULL);
        CHECK(strstr(data, "\"facts\":[[\"bottleneck radius (Å)\",\"0.900\"]]") != NULL);
        CHECK(strstr(data, "\"facts\":[[\"channels\",\"0\"],[\"atoms\",\"3\"]]") != NULL);
        CHECK(strstr(data, "\"measures\":[{\"name\":\"volume\",\"v\":[10.5,null,30]},{\"name\":\"sas\",\"v\":[1,2,3]}]") != NULL);
        CHECK(strstr(data, "\"points\":[{\"name\":\"vertices\",\"xyz\":[0.000,0.000,0.500],\"r\":[1.25]}]") != NULL);
        *end = '<';
        /* One page: the data, the viewer and the page's script, nothing
         * fetched from elsewhere. */
        const char *ngl = vbp_viewer_js();
        CHECK(strstr(html, ngl) != NULL);
        CHECK(strstr(html, vbp_page_js()) != NULL);
        CHECK_INT(count(html, "<script") - count(ngl, "<script"), 3);
        CHECK_INT(count(html, "</script>"), 3);
        CHECK_INT(count(html, "src=\"http") - count(ngl, "src=\"http"), 0);
        CHECK_INT(count(html, "href=\"http") - count(ngl, "href=\"http"), 0);
        free(html);
        /* A page that cannot be written leaves nothing behind. */
        CHECK_INT(vb_page_write(p, bad), VB_EIO);
        CHECK(access(bad, F_OK) != 0);
        unlink(path);
    }
    rmdir(dir);
    vb_page_free(p);

    /* A page is bounded: past VB_PAGE_MAX_NUMBERS coordinates, frames are
     * left out (index -1, W829 once) and calls on them do nothing. */
    size_t n = VB_PAGE_MAX_NUMBERS / 3 / 4 + 1;
    double *big = calloc(n, sizeof *big);
    vb_sphere_set t = {.n = n, .x = big, .y = big, .z = big, .r = big, .source = "big.xyzr"};
    vb_page *q = vb_page_new(ctx, "big", &t);
    CHECK(q != NULL);
    uint64_t warned = vb_ctx_stats(ctx)->warnings;
    int idx[6];
    for (int k = 0; k < 6; k++)
        CHECK_INT(vb_page_frame(q, "f", NULL, &idx[k]), VB_OK);
    CHECK_INT(idx[0], 0);
    CHECK_INT(idx[2], 2);
    CHECK_INT(idx[3], -1);
    CHECK_INT(idx[5], -1);
    CHECK_INT((int)(vb_ctx_stats(ctx)->warnings - warned), 1);
    CHECK_INT(vb_page_fact(q, -1, "k", "v"), VB_OK);
    vb_page_free(q);
    free(big);
    vb_close(ctx);
    VB_TEST_END();
}
