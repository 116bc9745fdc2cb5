#ifndef ROMA_BENCH_PLOT_H
#define ROMA_BENCH_PLOT_H

/* One measured setting of one method: what its image cost and how far it is from the
 * converged reference. */
typedef struct roma_bench_point {
    char series[32]; /* the curve it belongs to: "ROMA A 4", "voxel traversal", "Embree" */
    char label[16];  /* the setting along the curve: "128" (RES), "64" (spp) */
    double ms;       /* time for the whole image */
    double mae, flip; /* NAN where not measured */
} roma_bench_point;

/* on_front[i] = 1 where no other point is as fast or faster with a lower error
 * (error = MAE, or FLIP with use_flip); points without a positive finite error are off it. */
void roma_bench_pareto(const roma_bench_point *points, int count, int use_flip, int *on_front);

/* Prints the Pareto front of both errors as table rows ("| front | MAE | series | setting | ms
 * | error |"), fastest first; then those of the points whose series is not Embree's
 * ("| front | MAE, GPU | ..."). */
void roma_bench_print_fronts(const roma_bench_point *points, int count);

/* For each series, against the point `anchor` (ROMA at its defaults): the lowest error among
 * its settings that take no longer (equal time) and the shortest time among its settings
 * whose error is no higher (equal error), by MAE and by FLIP; "-" where none qualifies. */
void roma_bench_print_equal(const roma_bench_point *points, int count, int anchor);

/* Error against time (the points' ms), one curve per series, log-log, MAE and FLIP side
 * by side, each with its Pareto front when show_front, drawn by gnuplot into a PNG. Returns 0 on success; a message on
 * stderr otherwise (gnuplot missing or failing, a path it cannot take). */
int roma_bench_plot(const roma_bench_point *points, int count, const char *title, const char *x_label,
                    int show_front, const char *png_path);

/* A curve of a line plot: its name and up to 16 (x, y) points. */
typedef struct roma_bench_curve {
    char name[40];
    int count;
    double x[16], y[16];
} roma_bench_curve;

/* Two panels side by side, log-log, a line per curve, each panel with its own x label and
 * the same y label, drawn by gnuplot into a PNG. Returns 0 on success; a message on stderr
 * otherwise. */
int roma_bench_plot_curves(const roma_bench_curve *left, int left_count, const char *left_x,
                           const roma_bench_curve *right, int right_count, const char *right_x, const char *title,
                           const char *y_label, const char *png_path);

#endif /* ROMA_BENCH_PLOT_H */
