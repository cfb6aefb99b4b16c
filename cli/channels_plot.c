/* `channels --plot`: the pore's radius profile as a gnuplot script (data
 * inline, kept beside the picture) and the PNG gnuplot draws from it. */
#include <math.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "channels_plot.h"
#include "cli_common.h"
#include "vb_diag.h"

extern char **environ;

/* Runs `gnuplot script`; returns its exit status, or -1 when it cannot start. */
static int run_gnuplot(const char *script)
{
    pid_t pid;
    char *argv[] = {"gnuplot", (char *)script, NULL};
    if (posix_spawnp(&pid, "gnuplot", NULL, NULL, argv, environ) != 0)
        return -1;
    int st;
    if (waitpid(pid, &st, 0) < 0)
        return -1;
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* Writes a gnuplot string literal (single quotes doubled). */
static void gp_string(FILE *f, const char *s)
{
    fputc('\'', f);
    for (; *s; s++) {
        if (*s == '\'')
            fputc('\'', f);
        fputc(*s, f);
    }
    fputc('\'', f);
}

/* The gnuplot script drawing res's pore profile (and the series) into
 * `output`. */
static void write_script(FILE *f, const char *output, const char *title, const vb_channels *ch)
{
    const vb_channels_result *res = vb_channels_first(ch);
    vb_channel_row c;
    vb_channel_point p;
    vb_channels_pore pore;
    vb_channels_result_row(res, 0, &c);
    vb_channels_result_pore(res, &pore);
    const double *u = pore.u;
    size_t nseries = vb_channels_series(ch, 0, NULL, NULL, NULL);
    int multi = nseries > 1;
    fprintf(f, "# vorball channels --plot: the pore's radius profile (HOLE's colours: red\n"
               "# below 1.15 A, too tight for a water molecule; green up to 2.30 A, one\n"
               "# water; blue above). Rerun with: gnuplot THIS_FILE\n");
    fprintf(f, "$profile << EOD\n# s_A radius_A\n");
    for (size_t k = 0; k < c.npoints; k++) {
        vb_channels_result_point(res, c.first_point + k, &p);
        fprintf(f, "%.4f %.4f\n", p.x * u[0] + p.y * u[1] + p.z * u[2], p.r);
    }
    fprintf(f, "EOD\n");
    if (multi) {
        fprintf(f, "$series << EOD\n# frame rmin_A s_A\n");
        for (size_t k = 0; k < nseries; k++) {
            long frame;
            double rmin, s;
            vb_channels_series(ch, k, &frame, &rmin, &s);
            fprintf(f, "%ld %.4f %.4f\n", frame, rmin, s);
        }
        fprintf(f, "EOD\n");
    }
    fprintf(f, "set terminal pngcairo size %d,600 font ',11'\nset output ", multi ? 1400 : 800);
    gp_string(f, output);
    fprintf(f, "\nset grid\n");
    if (multi)
        fprintf(f, "set multiplot layout 1,2\n");
    fprintf(f, "set title ");
    gp_string(f, title);
    fprintf(f, " noenhanced\nset xlabel 'axial coordinate s (A) along (%.3f, %.3f, %.3f)'\n"
               "set ylabel 'pore radius (A)'\nset yrange [0:*]\n"
               "set style rect fc rgb '#ffdddd' fs solid 0.5 noborder\n"
               "set object 1 rect from graph 0, first 0 to graph 1, first 1.15 behind\n"
               "set style rect fc rgb '#ddffdd' fs solid 0.5 noborder\n"
               "set object 2 rect from graph 0, first 1.15 to graph 1, first 2.30 behind\n"
               "plot $profile using 1:2 with lines lw 2 lc rgb '#1f4e9a' title 'vorball pore'\n",
            u[0], u[1], u[2]);
    if (multi)
        fprintf(f, "unset object 1\nunset object 2\nset title 'smallest pore radius per frame'\n"
                   "set xlabel 'frame'\nset ylabel 'radius (A) / position s (A)'\nset yrange [*:*]\n"
                   "plot $series using 1:2 with linespoints title 'smallest radius',"
                   " $series using 1:3 with lines axes x1y1 title 's of the smallest radius'\n"
                   "unset multiplot\n");
}

/* Copies the file `from` into the output `to` (vb_cli_open_output: it
 * appears with the command's other outputs). VB_EIO when from cannot be
 * read. */
static int copy_into_output(vb_ctx *ctx, const char *from, const char *to)
{
    FILE *in = fopen(from, "rb");
    if (!in)
        return vb_error(ctx, VB_EIO, to, 0, "cannot read the plot gnuplot drew");
    FILE *out = vb_cli_open_output(ctx, to);
    if (!out) {
        fclose(in);
        return vb_errcode(ctx);
    }
    char buf[65536];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, in)) > 0)
        fwrite(buf, 1, n, out);
    int bad = ferror(in);
    fclose(in);
    return vb_cli_finish_output(ctx, out, to, bad ? vb_error(ctx, VB_EIO, from, 0, "read failed") : VB_OK);
}

int vb_cli_channels_plot(vb_ctx *ctx, const char *png, const char *title, const vb_channels *ch)
{
    const vb_channels_result *res = vb_channels_first(ch);
    vb_channels_pore pore;
    if (!res || !vb_channels_result_pore(res, &pore))
        return vb_warn(ctx, VB_W_PORE_NOT_FOUND, png, 0, "no pore in the first frame: nothing to plot"), VB_OK;
    char script[4200], run[4200], tmp[4200];
    if (snprintf(script, sizeof script, "%s.gp", png) >= (int)sizeof script ||
        snprintf(run, sizeof run, "%s.tmp%ld.gp", png, (long)getpid()) >= (int)sizeof run ||
        snprintf(tmp, sizeof tmp, "%s.tmp%ld.png", png, (long)getpid()) >= (int)sizeof tmp)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "plot file name too long");
    /* The kept script draws `png` when rerun; it appears with the other
     * outputs, after this command succeeds (vb_output.h defers the
     * renames). gnuplot runs now, on a private copy that draws into a
     * temporary picture, which then becomes an output like the others. */
    FILE *f = vb_cli_open_output(ctx, script);
    if (!f)
        return vb_errcode(ctx);
    write_script(f, png, title, ch);
    int rc = vb_cli_close_output(ctx, f, script);
    if (rc != VB_OK)
        return rc;
    FILE *r = fopen(run, "w");
    if (!r)
        return vb_error(ctx, VB_EIO, run, 0, "cannot write the plot script gnuplot runs");
    write_script(r, tmp, title, ch);
    if (fclose(r) != 0) {
        remove(run);
        return vb_error(ctx, VB_EIO, run, 0, "cannot write the plot script gnuplot runs");
    }
    int st = run_gnuplot(run);
    remove(run);
    if (st != 0) {
        remove(tmp);
        vb_warn(ctx, VB_W_PLOT_NO_GNUPLOT, script, 0,
                "gnuplot %s: the script is kept, run 'gnuplot %s' for %s",
                st < 0 ? "not found" : "failed", script, png);
        return VB_OK;
    }
    rc = copy_into_output(ctx, tmp, png);
    remove(tmp);
    return rc;
}
