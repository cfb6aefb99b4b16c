/* --select (core/input/vb_select.h): the grammar on hand-made atom records,
 * the errors with their positions, and selections of corpus files as read
 * (1chb: five chains of the cholera toxin pentamer; 1af6: maltoporin). */
#include "vb_diag.h"
#include "vb_select.h"
#include "vb_test.h"
#include "input_test_util.h"

static vb_atom_info atom(const char *name, const char *resname, const char *chain, int resseq,
                         const char *element, const char *segid)
{
    vb_atom_info a;
    memset(&a, 0, sizeof a);
    snprintf(a.name, sizeof a.name, "%s", name);
    snprintf(a.resname, sizeof a.resname, "%s", resname);
    snprintf(a.chain, sizeof a.chain, "%s", chain);
    snprintf(a.element, sizeof a.element, "%s", element);
    snprintf(a.segid, sizeof a.segid, "%s", segid);
    a.resseq = resseq;
    a.icode = a.altloc = ' ';
    return a;
}

/* 1 when expr parses and matches a, 0 when it parses and does not, -1 when
 * it does not parse. */
static int sel(vb_ctx *ctx, const char *expr, const vb_atom_info *a)
{
    vb_select *s;
    if (vb_select_parse(ctx, expr, &s) != VB_OK)
        return -1;
    int m = vb_select_match(s, a);
    vb_select_free(s);
    return m;
}

/* The error of a malformed expression names this 1-based position. */
static void check_error_at(vb_ctx *ctx, const char *expr, int pos)
{
    vb_select *s = NULL;
    CHECK_INT(vb_select_parse(ctx, expr, &s), VB_EINPUT_SELECT);
    CHECK(s == NULL);
    char want[64];
    snprintf(want, sizeof want, "at character %d of", pos);
    const char *msg = vb_errmsg(ctx);
    CHECK(msg && strstr(msg, want) != NULL);
    if (!(msg && strstr(msg, want)))
        fprintf(stderr, "  message: %s (wanted '%s')\n", msg ? msg : "(null)", want);
}

static void grammar(vb_ctx *ctx)
{
    vb_atom_info ca = atom("CA", "ALA", "A", 12, "C", "PROA");
    vb_atom_info o = atom("O", "HOH", "W", 301, "O", "");
    vb_atom_info mg = atom("MG", "MG", "B", -3, "MG", "");
    CHECK_INT(sel(ctx, "chain A", &ca), 1);
    CHECK_INT(sel(ctx, "chain a", &ca), 0); /* chains compare exactly */
    CHECK_INT(sel(ctx, "CHAIN B A", &ca), 1);
    CHECK_INT(sel(ctx, "segid PROA", &ca), 1);
    CHECK_INT(sel(ctx, "resname ala", &ca), 1); /* residue names ignore case */
    CHECK_INT(sel(ctx, "resname A?A", &ca), 1);
    CHECK_INT(sel(ctx, "resname A*", &ca), 1);
    CHECK_INT(sel(ctx, "resname G*", &ca), 0);
    CHECK_INT(sel(ctx, "resid 12", &ca), 1);
    CHECK_INT(sel(ctx, "resid 1:11 13:20", &ca), 0);
    CHECK_INT(sel(ctx, "resid 10:12", &ca), 1);
    CHECK_INT(sel(ctx, "resid -5:-1", &mg), 1);
    CHECK_INT(sel(ctx, "name C?", &ca), 1);
    CHECK_INT(sel(ctx, "element c", &ca), 1);
    CHECK_INT(sel(ctx, "protein", &ca), 1);
    CHECK_INT(sel(ctx, "protein", &o), 0);
    CHECK_INT(sel(ctx, "water", &o), 1);
    CHECK_INT(sel(ctx, "not water", &o), 0);
    CHECK_INT(sel(ctx, "not not water", &o), 1);
    /* and binds tighter than or. */
    CHECK_INT(sel(ctx, "chain W or chain A and name N", &o), 1);
    CHECK_INT(sel(ctx, "(chain W or chain A) and name N", &o), 0);
    CHECK_INT(sel(ctx, "protein and not (resid 1:5 or name CB)", &ca), 1);
    CHECK_INT(sel(ctx, "all", NULL), 1);
    CHECK_INT(sel(ctx, "protein", NULL), 0); /* no atom record: only "all" */
    check_error_at(ctx, "chain", 1);              /* keyword without a value */
    check_error_at(ctx, "chain A and", 12);       /* ends where a selection is due */
    check_error_at(ctx, "chain A name", 9);       /* keyword without a value */
    check_error_at(ctx, "chain A (name CA)", 9);  /* a value list ends, then no operator */
    check_error_at(ctx, "(chain A", 1);           /* '(' not closed */
    check_error_at(ctx, "chain A)", 8);           /* ')' without '(' */
    check_error_at(ctx, "resid 5:2", 7);          /* an empty range */
    check_error_at(ctx, "resid 1:x", 7);
    check_error_at(ctx, "bogus", 1);
    check_error_at(ctx, "", 1);
    CHECK_INT(vb_diag_exit(VB_EINPUT_SELECT), 28);
}

/* Selections of a file as read: counts of atoms, order kept, exact values kept. */
static void files(vb_ctx *ctx)
{
    vb_read_options o;
    memset(&o, 0, sizeof o);
    vb_sphere_set *all = NULL, *d = NULL, *none = NULL;
    CHECK_INT(vb_spheres_read_file(ctx, corpus_path("data/1chb_hole2.pdb"), &o, &all), VB_OK);
    o.select = "chain D and resid 1:10";
    CHECK_INT(vb_spheres_read_file(ctx, corpus_path("data/1chb_hole2.pdb"), &o, &d), VB_OK);
    if (all && d) {
        size_t want = 0, first = (size_t)-1;
        for (size_t i = 0; i < all->n; i++)
            if (strcmp(all->info[i].chain, "D") == 0 && all->info[i].resseq >= 1 &&
                all->info[i].resseq <= 10) {
                want++;
                if (first == (size_t)-1)
                    first = i;
            }
        CHECK(want > 50);
        CHECK_INT(d->n, want);
        CHECK_INT(d->line[0], all->line[first]);
        CHECK_INT(d->ex[0].mant, all->ex[first].mant);
        CHECK_INT(d->er[0].exp10, all->er[first].exp10);
    }
    o.select = "chain Q";
    CHECK_INT(vb_spheres_read_file(ctx, corpus_path("data/1chb_hole2.pdb"), &o, &none),
              VB_EINPUT_SELECT);
    CHECK(none == NULL);
    vb_spheres_free(all);
    vb_spheres_free(d);
}

int main(void)
{
    FILE *diag;
    vb_ctx *ctx = open_ctx(&diag);
    grammar(ctx);
    files(ctx);
    vb_close(ctx);
    fclose(diag);
    VB_TEST_END();
}
