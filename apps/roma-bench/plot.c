/* Error-against-time plots of roma-bench --accuracy, drawn by gnuplot (a Debian package;
 * install-deps.sh installs gnuplot-nox): the script and its data go down a pipe, so no
 * temporary files are left behind. */
#include "plot.h"

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static double error_of(const roma_bench_point *p, int use_flip)
{
    return use_flip ? p->flip : p->mae;
}

static int plottable(const roma_bench_point *p, int use_flip)
{
    double e = error_of(p, use_flip);
    return isfinite(e) && e > 0.0 && isfinite(p->ms) && p->ms > 0.0;
}

void roma_bench_pareto(const roma_bench_point *points, int count, int use_flip, int *on_front)
{
    for (int i = 0; i < count; ++i) {
        on_front[i] = plottable(&points[i], use_flip);
        for (int j = 0; j < count && on_front[i]; ++j) {
            if (j == i || !plottable(&points[j], use_flip))
                continue;
            double ei = error_of(&points[i], use_flip), ej = error_of(&points[j], use_flip);
            if ((points[j].ms <= points[i].ms && ej < ei) || (points[j].ms < points[i].ms && ej <= ei))
                on_front[i] = 0;
        }
    }
}

/* Indices of the front, fastest first; returns how many. */
static int front_order(const roma_bench_point *points, int count, int use_flip, int *order)
{
    int *on = calloc((size_t)count, sizeof *on), n = 0;
    if (!on)
        return 0;
    roma_bench_pareto(points, count, use_flip, on);
    for (int i = 0; i < count; ++i)
        if (on[i]) {
            int k = n++;
            while (k > 0 && points[order[k - 1]].ms > points[i].ms) {
                order[k] = order[k - 1];
                --k;
            }
            order[k] = i;
        }
    free(on);
    return n;
}

void roma_bench_print_fronts(const roma_bench_point *points, int count)
{
    int *order = malloc((size_t)(count ? count : 1) * sizeof *order);
    if (!order)
        return;
    printf("\nPareto fronts (no other setting is as fast with a lower error), fastest first; then the\n"
           "same among the GPU methods alone (without Embree):\n\n"
           "| front | by | method | setting | ms for the image | error |\n|---|---|---|---|---|---|\n");
    for (int gpu = 0; gpu < 2; ++gpu) {
        /* The GPU methods alone: the same points, Embree's made unplottable. */
        roma_bench_point *own = malloc((size_t)(count ? count : 1) * sizeof *own);
        if (!own)
            break;
        for (int i = 0; i < count; ++i) {
            own[i] = points[i];
            if (gpu && strncmp(own[i].series, "Embree", 6) == 0)
                own[i].mae = own[i].flip = NAN;
        }
        for (int use_flip = 0; use_flip < 2; ++use_flip) {
            int n = front_order(own, count, use_flip, order);
            for (int k = 0; k < n; ++k) {
                const roma_bench_point *p = &own[order[k]];
                printf("| front | %s%s | %s | %s | %.1f | %.4f |\n", use_flip ? "FLIP" : "MAE", gpu ? ", GPU" : "",
                       p->series, p->label, p->ms, error_of(p, use_flip));
            }
        }
        free(own);
    }
    free(order);
}

void roma_bench_print_equal(const roma_bench_point *points, int count, int anchor)
{
    if (anchor < 0 || anchor >= count)
        return;
    const roma_bench_point *a = &points[anchor];
    printf("\nAgainst %s at %s (%.1f ms for the image, MAE %.4f, FLIP %.4f): each method's best setting\n"
           "in that time (equal time) and its fastest setting with that error or less (equal error):\n\n"
           "| method | equal time: MAE | setting | equal time: FLIP | setting | equal MAE: ms | setting "
           "| equal FLIP: ms | setting |\n|---|---|---|---|---|---|---|---|---|\n",
           a->series, a->label, a->ms, a->mae, a->flip);
    for (int i = 0; i < count; ++i) {
        int first = 1; /* one row per series, at its first point */
        for (int j = 0; j < i; ++j)
            first &= strcmp(points[j].series, points[i].series) != 0;
        if (!first)
            continue;
        printf("| %s ", points[i].series);
        for (int kind = 0; kind < 4; ++kind) {
            int use_flip = kind & 1, equal_error = kind >> 1, best = -1;
            for (int j = 0; j < count; ++j) {
                const roma_bench_point *p = &points[j];
                if (strcmp(p->series, points[i].series) != 0 || !plottable(p, use_flip))
                    continue;
                if (!equal_error && p->ms <= a->ms &&
                    (best < 0 || error_of(p, use_flip) < error_of(&points[best], use_flip)))
                    best = j;
                if (equal_error && error_of(p, use_flip) <= error_of(a, use_flip) &&
                    (best < 0 || p->ms < points[best].ms))
                    best = j;
            }
            if (best < 0)
                printf("| - | - ");
            else if (!equal_error)
                printf("| %.4f | %s ", error_of(&points[best], use_flip), points[best].label);
            else
                printf("| %.1f | %s ", points[best].ms, points[best].label);
        }
        printf("|\n");
    }
}

/* One panel: a curve per series with its settings written beside the points, and the front
 * as the staircase of the best error reachable in a given time. */
static void write_panel(FILE *gp, const roma_bench_point *points, int count, int use_flip, const char *x_label,
                        int show_front, int *order)
{
    const char *name = use_flip ? "FLIP" : "MAE";
    fprintf(gp, "set xlabel \"%s\"\nset ylabel \"%s against the reference\"\n", x_label, name);
    /* Series in order of first appearance, each an inline data block. */
    char seen[16][32];
    int series = 0;
    for (int i = 0; i < count && series < 16; ++i) {
        int known = 0;
        for (int s = 0; s < series; ++s)
            known |= strcmp(seen[s], points[i].series) == 0;
        if (known)
            continue;
        snprintf(seen[series], sizeof seen[series], "%s", points[i].series);
        fprintf(gp, "$%s%d << EOD\n", name, series);
        for (int j = 0; j < count; ++j)
            if (strcmp(points[j].series, seen[series]) == 0 && plottable(&points[j], use_flip))
                fprintf(gp, "%.6g %.6g \"%s\"\n", points[j].ms, error_of(&points[j], use_flip), points[j].label);
        fprintf(gp, "EOD\n");
        ++series;
    }
    int n = show_front ? front_order(points, count, use_flip, order) : 0;
    fprintf(gp, "$%sfront << EOD\n", name);
    for (int k = 0; k < n; ++k)
        fprintf(gp, "%.6g %.6g\n", points[order[k]].ms, error_of(&points[order[k]], use_flip));
    fprintf(gp, "EOD\nplot ");
    /* gnuplot's default colours repeat after 8 series: one of 12 each, then a new point shape. */
    static const char *const colours[12] = {"#9400d3", "#009e73", "#56b4e9", "#e69f00", "#f0e442", "#0072b2",
                                            "#e51e10", "#000000", "#cc79a7", "#8b4513", "#808000", "#ff69b4"};
    for (int s = 0; s < series; ++s)
        fprintf(gp, "$%s%d using 1:2 with linespoints lc rgb \"%s\" lw 2 pt %d title \"%s\", "
                    "$%s%d using 1:2:3 with labels offset char 0.9,0.6 font \",8\" tc rgb \"gray30\" notitle, ",
                name, s, colours[s % 12], s < 12 ? 7 : 5, seen[s], name, s);
    if (show_front)
        fprintf(gp, "$%sfront using 1:2 with steps dt 2 lw 1.5 lc rgb \"black\" title \"Pareto front\", "
                    "$%sfront using 1:2 with points pt 6 ps 2 lc rgb \"black\" notitle\n",
                name, name);
    else
        fprintf(gp, "NaN notitle\n");
}

/* Starts gnuplot writing a PNG of two panels side by side, log-log; NULL (a message on
 * stderr) when a text would break its quoting or gnuplot does not start. */
static FILE *open_plot(const char *png_path, const char *title, const char *const *texts, int text_count,
                       void (**old_sigpipe)(int))
{
    /* The strings go into double-quoted gnuplot strings. */
    for (int t = -2; t < text_count; ++t) {
        const char *text = t == -2 ? png_path : t == -1 ? title : texts[t];
        if (!text || strpbrk(text, "\"\\\n`")) {
            fprintf(stderr, "roma-bench: cannot plot: quotes, backslashes or newlines in \"%s\"\n",
                    text ? text : "(null)");
            return NULL;
        }
    }
    /* gnuplot's messages go to our stdout; its own stdout (where it writes the image when the
     * output cannot be opened) goes nowhere. A gnuplot that exits early must not kill us with
     * SIGPIPE while the script is still being written. */
    *old_sigpipe = signal(SIGPIPE, SIG_IGN);
    FILE *gp = popen("gnuplot 2>&1 >/dev/null", "w");
    if (!gp) {
        fprintf(stderr, "roma-bench: cannot start gnuplot\n");
        signal(SIGPIPE, *old_sigpipe);
        return NULL;
    }
    fprintf(gp, "set terminal pngcairo noenhanced size 1400,560 font \",10\"\nset output \"%s\"\n"
                "set multiplot layout 1,2 title \"%s\"\nset logscale xy\nset grid\n"
                "set key bottom left font \",9\"\n",
            png_path, title);
    return gp;
}

/* Ends the plot; 0 when gnuplot drew it. */
static int close_plot(FILE *gp, void (*old_sigpipe)(int), const char *png_path)
{
    fprintf(gp, "unset multiplot\nset output\n");
    int write_failed = ferror(gp);
    int status = pclose(gp);
    signal(SIGPIPE, old_sigpipe);
    if (write_failed && status == 0)
        status = -1;
    if (status != 0) {
        fprintf(stderr, "roma-bench: gnuplot failed (status %d); install-deps.sh installs gnuplot-nox\n", status);
        return 1;
    }
    printf("\nplot: %s\n", png_path);
    return 0;
}

int roma_bench_plot(const roma_bench_point *points, int count, const char *title, const char *x_label,
                    int show_front, const char *png_path)
{
    int *order = malloc((size_t)(count ? count : 1) * sizeof *order);
    void (*old_sigpipe)(int) = SIG_DFL;
    FILE *gp = order ? open_plot(png_path, title, &x_label, 1, &old_sigpipe) : NULL;
    if (!gp) {
        free(order);
        return 1;
    }
    write_panel(gp, points, count, 0, x_label, show_front, order);
    write_panel(gp, points, count, 1, x_label, show_front, order);
    free(order);
    return close_plot(gp, old_sigpipe, png_path);
}

static void write_curves(FILE *gp, const roma_bench_curve *curves, int count, const char *x_label,
                         const char *y_label)
{
    fprintf(gp, "set xlabel \"%s\"\nset ylabel \"%s\"\n", x_label, y_label);
    for (int c = 0; c < count; ++c) {
        fprintf(gp, "$curve%d << EOD\n", c);
        for (int i = 0; i < curves[c].count && i < 16; ++i)
            if (curves[c].x[i] > 0.0 && curves[c].y[i] > 0.0) /* log axes */
                fprintf(gp, "%.6g %.6g\n", curves[c].x[i], curves[c].y[i]);
        fprintf(gp, "EOD\n");
    }
    fprintf(gp, "plot ");
    for (int c = 0; c < count; ++c)
        fprintf(gp, "$curve%d using 1:2 with linespoints lw 2 pt 7 title \"%s\"%s", c, curves[c].name,
                c + 1 < count ? ", " : "\n");
    if (count == 0)
        fprintf(gp, "NaN notitle\n");
}

int roma_bench_plot_curves(const roma_bench_curve *left, int left_count, const char *left_x,
                           const roma_bench_curve *right, int right_count, const char *right_x, const char *title,
                           const char *y_label, const char *png_path)
{
    const char *texts[3] = {left_x, right_x, y_label};
    for (int c = 0; c < left_count + right_count; ++c)
        if (strpbrk(c < left_count ? left[c].name : right[c - left_count].name, "\"\\\n`")) {
            fprintf(stderr, "roma-bench: cannot plot: quotes, backslashes or newlines in a curve's name\n");
            return 1;
        }
    void (*old_sigpipe)(int) = SIG_DFL;
    FILE *gp = open_plot(png_path, title, texts, 3, &old_sigpipe);
    if (!gp)
        return 1;
    write_curves(gp, left, left_count, left_x, y_label);
    write_curves(gp, right, right_count, right_x, y_label);
    return close_plot(gp, old_sigpipe, png_path);
}
