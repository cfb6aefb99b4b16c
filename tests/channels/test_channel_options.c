/* The channel options' one table (vbc_channels_config.h): every default
 * lies in its own range and reads back as the documented value, values are
 * checked by type and range with messages naming the option, the rules
 * between options, and --help lists every option. */
#include <stdlib.h>
#include <string.h>

#include "vb_test.h"
#include "vbc_channels_config.h"

static int set(vbc_channels_config *c, const char *name, const char *v, char *err)
{
    const vbc_opt_spec *o = vbc_channels_option(name);
    CHECK(o != NULL);
    return o ? vbc_channels_set(c, o, v, err, 256) : -2;
}

static void test_defaults(void)
{
    size_t n;
    const vbc_opt_spec *t = vbc_channels_options(&n);
    CHECK(n >= 30);
    char err[256];
    for (size_t k = 0; k < n; k++) {
        vbc_channels_config c;
        vbc_channels_defaults(&c);
        err[0] = '\0';
        if (t[k].def)
            CHECK_INT(vbc_channels_set(&c, &t[k], t[k].def, err, sizeof err), 0);
        CHECK_STR(err, "");
        /* Names are unique, aliases included. */
        CHECK(vbc_channels_option(t[k].name) == &t[k]);
        if (t[k].py)
            CHECK(vbc_channels_option_py(t[k].py) == &t[k]);
    }
    vbc_channels_config c;
    vbc_channels_defaults(&c);
    CHECK(c.probe == 1.4);
    CHECK_INT(c.grid, 128);
    CHECK(c.opt.min_length == 5.0 && c.opt.min_radius == 0.0 && c.opt.lining_tol == 1.0);
    CHECK(c.pore.enabled == 1 && c.pore.sweep.step == 0.25 && c.pore.sweep.end_radius == 0.0);
    CHECK_INT(c.repeat, 1);
    CHECK(c.f0 == 0 && c.f1 == -1 && c.fstep == 1);
    CHECK_INT((int)c.volume_bit, VBC_F_CHANNEL);
    CHECK_INT((int)c.variant, VBJ_EXACT);
    CHECK_INT((int)c.device, VB_DEVICE_AUTO);
    CHECK(vbc_channels_option("--centrelines") == vbc_channels_option("--centerlines"));
    CHECK(vbc_channels_option("--dcd") == vbc_channels_option("--traj"));
    CHECK(vbc_channels_option("--cavity") == NULL);
}

static void test_values(void)
{
    vbc_channels_config c;
    vbc_channels_defaults(&c);
    char err[256];
    CHECK_INT(set(&c, "--probe", "1.0", err), 0);
    CHECK(c.probe == 1.0);
    CHECK_INT(set(&c, "--probe", "-1", err), -1);
    CHECK_STR(err, "--probe needs a number in 0..20 (A), not '-1'");
    CHECK_INT(set(&c, "--probe", "1x", err), -1);
    CHECK_INT(set(&c, "--grid", "100", err), -1);
    CHECK_STR(err, "--grid needs a power of two in 16..1024, not '100'");
    CHECK_INT(set(&c, "--grid", "2048", err), -1);
    CHECK_INT(set(&c, "--grid", "64", err), 0);
    CHECK_INT(c.grid, 64);
    CHECK_INT(set(&c, "--repeat", "0", err), -1);
    CHECK_INT(set(&c, "--sample", "9", err), -1);
    CHECK_INT(set(&c, "--volume-mask", "foo", err), -1);
    CHECK_STR(err, "--volume-mask: channel, interior, molecular, atomic or edge, not 'foo'");
    CHECK_INT(set(&c, "--volume-mask", "interior", err), 0);
    CHECK_INT((int)c.volume_bit, VBC_F_INTERIOR);
    CHECK_INT(set(&c, "--jfa", "facet-full", err), -1); /* a variant channels does not take */
    CHECK_INT(set(&c, "--jfa", "jfa+1", err), 0);
    CHECK_INT((int)c.variant, VBJ_JFA1);
    CHECK_INT(set(&c, "--device", "ref", err), 0);
    CHECK_INT((int)c.device, VB_DEVICE_REF);
    CHECK_INT(set(&c, "--png-normal", "y", err), 0);
    CHECK_INT(c.png_axis, 1);
    CHECK_INT(set(&c, "--axis", "0,0", err), -1);
    CHECK_INT(set(&c, "--axis", "0,0,0", err), -1);
    CHECK_STR(err, "--axis needs a nonzero vector, not '0,0,0'");
    CHECK_INT(set(&c, "--axis", "0,3,4", err), 0);
    CHECK(c.pore.have_axis && c.pore.u[0] == 0.0 && c.pore.u[1] == 0.6 && c.pore.u[2] == 0.8);
    CHECK_INT(set(&c, "--frames", "5:2", err), -1);
    CHECK_INT(set(&c, "--frames", "2:40:3", err), 0);
    CHECK(c.f0 == 2 && c.f1 == 40 && c.fstep == 3);
    CHECK_INT(set(&c, "--frames", "7", err), 0);
    CHECK(c.f0 == 7 && c.f1 == 8);
    CHECK_INT(set(&c, "--ignore", ",", err), -1);
    CHECK_INT(set(&c, "--ignore", "DUM,POPC", err), 0);
    CHECK(c.nignore == 2 && strcmp(c.ignore[0], "DUM") == 0 && strcmp(c.ignore[1], "POPC") == 0);
    CHECK_INT(set(&c, "--grid", NULL, err), -1);
    CHECK_STR(err, "--grid needs a value");
    CHECK_INT(set(&c, "--no-pore", NULL, err), 0);
    CHECK_INT(c.pore.enabled, 0);
}

static void test_rules(void)
{
    vbc_channels_config c;
    char err[256];
    vbc_channels_defaults(&c);
    CHECK_INT(vbc_channels_check(&c, err, sizeof err), 0);
    CHECK(c.opt.pore == &c.pore);
    set(&c, "--pymol", "x.pml", err);
    CHECK_INT(vbc_channels_check(&c, err, sizeof err), -1);
    CHECK_STR(err, "--pymol draws the --centerlines file: give both");
    vbc_channels_defaults(&c);
    set(&c, "--no-pore", NULL, err);
    set(&c, "--through", "1,2,3", err);
    CHECK_INT(vbc_channels_check(&c, err, sizeof err), -1);
    vbc_channels_defaults(&c);
    set(&c, "--occupancy", "o.mrc", err);
    CHECK_INT(vbc_channels_check(&c, err, sizeof err), -1);
    set(&c, "--fixed-grid", NULL, err);
    CHECK_INT(vbc_channels_check(&c, err, sizeof err), 0);
}

static void test_help(void)
{
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    CHECK(f != NULL);
    if (!f)
        return;
    vbc_channels_help(f, VBC_SECT_MAIN);
    vbc_channels_help(f, VBC_SECT_PORE);
    fclose(f);
    size_t n;
    const vbc_opt_spec *t = vbc_channels_options(&n);
    for (size_t k = 0; k < n; k++) {
        char want[64];
        snprintf(want, sizeof want, "\n  %s", t[k].name);
        CHECK(strstr(text, want) != NULL || strncmp(text, want + 1, strlen(want + 1)) == 0);
    }
    CHECK(strstr(text, "(range 0..20; default 1.4)") != NULL);
    CHECK(strstr(text, "(range 16..1024; default 128)") != NULL);
    /* No line wider than 80 columns. */
    for (const char *p = text; *p;) {
        const char *e = strchr(p, '\n');
        size_t w = e ? (size_t)(e - p) : strlen(p);
        CHECK(w <= 80);
        p = e ? e + 1 : p + w;
    }
    free(text);
}

int main(void)
{
    test_defaults();
    test_values();
    test_rules();
    test_help();
    VB_TEST_END();
}
