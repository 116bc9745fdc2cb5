/* LDR-FLIP (Andersson et al., "FLIP: A Difference Evaluator for Alternating Images", HPG
 * 2020), implemented from the paper: a colour pipeline (contrast sensitivity filtering in
 * the opponent space YCxCz, then the Hunt-adjusted HyAB distance in L*a*b*, compressed)
 * and a feature pipeline (edges and points of the achromatic channel, first and second
 * derivatives of a Gaussian), combined per pixel as colour^(1 - feature). */
#include "roma/image.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

/* The paper's constants. */
static const double Q_C = 0.7, P_C = 0.4, P_T = 0.95, Q_F = 0.5, FEATURE_WIDTH_DEG = 0.082;
/* Contrast sensitivity of the three opponent channels (Yy, Cx, Cz): a1, b1, a2, b2. */
static const double CSF[3][4] = {{1.0, 0.0047, 0.0, 1e-5}, {1.0, 0.0053, 0.0, 1e-5}, {34.1, 0.04, 13.5, 0.025}};

/* Linear sRGB (D65) <-> XYZ, and the white point (the rows' sums). */
static const double RGB_TO_XYZ[3][3] = {{0.4124564, 0.3575761, 0.1804375},
                                        {0.2126729, 0.7151522, 0.0721750},
                                        {0.0193339, 0.1191920, 0.9503041}};
static const double XYZ_TO_RGB[3][3] = {{3.2404542, -1.5371385, -0.4985314},
                                        {-0.9692660, 1.8760108, 0.0415560},
                                        {0.0556434, -0.2040259, 1.0572252}};
static const double WHITE[3] = {0.9504700, 1.0, 1.0888300};

static void mat3(const double m[3][3], const double in[3], double out[3])
{
    for (int r = 0; r < 3; ++r)
        out[r] = m[r][0] * in[0] + m[r][1] * in[1] + m[r][2] * in[2];
}

static void rgb_to_ycxcz(const double rgb[3], double out[3])
{
    double xyz[3];
    mat3(RGB_TO_XYZ, rgb, xyz);
    const double x = xyz[0] / WHITE[0], y = xyz[1] / WHITE[1], z = xyz[2] / WHITE[2];
    out[0] = 116.0 * y - 16.0;
    out[1] = 500.0 * (x - y);
    out[2] = 200.0 * (y - z);
}

static void ycxcz_to_rgb(const double ycc[3], double out[3])
{
    const double y = (ycc[0] + 16.0) / 116.0, x = ycc[1] / 500.0 + y, z = y - ycc[2] / 200.0;
    const double xyz[3] = {x * WHITE[0], y * WHITE[1], z * WHITE[2]};
    mat3(XYZ_TO_RGB, xyz, out);
}

static double lab_f(double t)
{
    const double d = 6.0 / 29.0;
    return t > d * d * d ? cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
}

/* Linear RGB in [0, 1] -> L*a*b* with a* and b* scaled by 0.01 L* (the Hunt effect). */
static void rgb_to_hunt_lab(const double rgb[3], double out[3])
{
    double xyz[3];
    mat3(RGB_TO_XYZ, rgb, xyz);
    const double fx = lab_f(xyz[0] / WHITE[0]), fy = lab_f(xyz[1] / WHITE[1]), fz = lab_f(xyz[2] / WHITE[2]);
    const double L = 116.0 * fy - 16.0;
    out[0] = L;
    out[1] = 0.01 * L * 500.0 * (fx - fy);
    out[2] = 0.01 * L * 200.0 * (fy - fz);
}

static double hyab(const double a[3], const double b[3])
{
    return fabs(a[0] - b[0]) + sqrt((a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* Separable filtering of one plane (w x h) with a 1D kernel of 2r + 1 taps along x then
 * along y (kx, ky), edges clamped. tmp: w * h scratch. */
static void filter2(const float *in, float *out, float *tmp, uint32_t w, uint32_t h, const double *kx,
                    const double *ky, int r)
{
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            double s = 0.0;
            for (int k = -r; k <= r; ++k) {
                int xx = (int)x + k;
                xx = xx < 0 ? 0 : xx >= (int)w ? (int)w - 1 : xx;
                s += kx[k + r] * in[(size_t)y * w + (size_t)xx];
            }
            tmp[(size_t)y * w + x] = (float)s;
        }
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            double s = 0.0;
            for (int k = -r; k <= r; ++k) {
                int yy = (int)y + k;
                yy = yy < 0 ? 0 : yy >= (int)h ? (int)h - 1 : yy;
                s += ky[k + r] * tmp[(size_t)yy * w + x];
            }
            out[(size_t)y * w + x] = (float)s;
        }
}

/* Scales the positive taps to sum 1 and the negative ones to sum -1 (the paper's
 * normalisation of the feature detectors). */
static void normalise_signed(double *k, int n)
{
    double pos = 0.0, neg = 0.0;
    for (int i = 0; i < n; ++i)
        k[i] > 0.0 ? (pos += k[i]) : (neg -= k[i]);
    for (int i = 0; i < n; ++i)
        k[i] = k[i] > 0.0 ? (pos > 0.0 ? k[i] / pos : 0.0) : (neg > 0.0 ? k[i] / neg : 0.0);
}

typedef struct flip_planes {
    float *ycc[3];          /* the image in YCxCz, then CSF-filtered */
    float *edge, *point;    /* feature magnitudes of the normalised achromatic channel */
} flip_planes;

/* One image's planes. px: linear values, clamped to [0, 1]; 1 channel = grey. */
static int prepare(const roma_image *img, double ppd, flip_planes *p, float *tmp, float *work)
{
    const uint32_t w = img->width, h = img->height;
    const size_t n = (size_t)w * h;
    for (int c = 0; c < 3; ++c)
        if (!(p->ycc[c] = malloc(n * sizeof(float))))
            return 0;
    if (!(p->edge = malloc(n * sizeof(float))) || !(p->point = malloc(n * sizeof(float))))
        return 0;
    float *grey = work; /* (Yy + 16) / 116 of the unfiltered image */
    for (size_t i = 0; i < n; ++i) {
        double rgb[3], ycc[3];
        for (int c = 0; c < 3; ++c) {
            double v = img->pixels[i * img->channels + (img->channels == 3 ? (size_t)c : 0)];
            rgb[c] = isfinite(v) ? (v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v) : 0.0;
        }
        rgb_to_ycxcz(rgb, ycc);
        for (int c = 0; c < 3; ++c)
            p->ycc[c][i] = (float)ycc[c];
        grey[i] = (float)((ycc[0] + 16.0) / 116.0);
    }
    /* Colour: each channel filtered by its contrast sensitivity, a sum of Gaussians in
     * visual degrees (x / ppd), normalised to sum 1 over the 2D kernel; each Gaussian is
     * separable, so each term is filtered apart and the terms summed with their weights. */
    const double bmax = fmax(CSF[2][1], CSF[2][3]);
    const int r = (int)ceil(3.0 * sqrt(bmax / (2.0 * PI * PI)) * ppd);
    double *g = malloc(sizeof(double) * (size_t)(2 * r + 1));
    float *term = malloc(n * sizeof(float)), *acc = malloc(n * sizeof(float));
    if (!g || !term || !acc) {
        free(g), free(term), free(acc);
        return 0;
    }
    for (int c = 0; c < 3; ++c) {
        double weight[2], total = 0.0;
        for (int k = 0; k < 2; ++k) {
            const double a = CSF[c][2 * k], b = CSF[c][2 * k + 1];
            double s = 0.0;
            for (int i = -r; i <= r; ++i)
                s += exp(-PI * PI * (i / ppd) * (i / ppd) / b);
            weight[k] = a * sqrt(PI / b) * s * s; /* the 2D term's sum */
            total += weight[k];
        }
        memset(acc, 0, n * sizeof(float));
        for (int k = 0; k < 2; ++k) {
            if (weight[k] == 0.0)
                continue;
            const double b = CSF[c][2 * k + 1];
            double s = 0.0;
            for (int i = -r; i <= r; ++i)
                s += g[i + r] = exp(-PI * PI * (i / ppd) * (i / ppd) / b);
            for (int i = 0; i <= 2 * r; ++i)
                g[i] /= s;
            filter2(p->ycc[c], term, tmp, w, h, g, g, r);
            for (size_t i = 0; i < n; ++i)
                acc[i] += (float)(weight[k] / total) * term[i];
        }
        memcpy(p->ycc[c], acc, n * sizeof(float));
    }
    free(g);
    /* Features: first (edges) and second (points) derivatives of a Gaussian of standard
     * deviation 0.5 * 0.082 degrees, along x and along y. */
    const double sigma = 0.5 * FEATURE_WIDTH_DEG * ppd;
    const int fr = (int)ceil(3.0 * sigma);
    double *gauss = malloc(sizeof(double) * (size_t)(2 * fr + 1)), *d1 = malloc(sizeof(double) * (size_t)(2 * fr + 1)),
           *d2 = malloc(sizeof(double) * (size_t)(2 * fr + 1));
    if (!gauss || !d1 || !d2) {
        free(gauss), free(d1), free(d2), free(term), free(acc);
        return 0;
    }
    double gs = 0.0;
    for (int i = -fr; i <= fr; ++i) {
        const double e = exp(-(double)(i * i) / (2.0 * sigma * sigma));
        gauss[i + fr] = e;
        gs += e;
        d1[i + fr] = -(double)i * e;
        d2[i + fr] = ((double)(i * i) / (sigma * sigma) - 1.0) * e;
    }
    for (int i = 0; i <= 2 * fr; ++i)
        gauss[i] /= gs;
    normalise_signed(d1, 2 * fr + 1);
    normalise_signed(d2, 2 * fr + 1);
    float *fx = term, *fy = acc;
    filter2(grey, fx, tmp, w, h, d1, gauss, fr);
    filter2(grey, fy, tmp, w, h, gauss, d1, fr);
    for (size_t i = 0; i < n; ++i)
        p->edge[i] = sqrtf(fx[i] * fx[i] + fy[i] * fy[i]);
    filter2(grey, fx, tmp, w, h, d2, gauss, fr);
    filter2(grey, fy, tmp, w, h, gauss, d2, fr);
    for (size_t i = 0; i < n; ++i)
        p->point[i] = sqrtf(fx[i] * fx[i] + fy[i] * fy[i]);
    free(gauss), free(d1), free(d2), free(term), free(acc);
    return 1;
}

static void planes_free(flip_planes *p)
{
    for (int c = 0; c < 3; ++c)
        free(p->ycc[c]);
    free(p->edge);
    free(p->point);
}

roma_result roma_image_flip(const roma_image *reference, const roma_image *test, const roma_image *mask,
                            float pixels_per_degree, double *out_mean, roma_image *out_map)
{
    if (out_mean)
        *out_mean = 0.0;
    /* An out_map that is also an input is refused before it is cleared: the caller keeps its image. */
    if (out_map && (out_map == reference || out_map == test || out_map == mask))
        return ROMA_ERROR_INVALID_ARGUMENT;
    if (out_map)
        memset(out_map, 0, sizeof *out_map);
    if (!out_mean || !reference || !test || !reference->pixels || !test->pixels ||
        reference->width != test->width || reference->height != test->height ||
        reference->channels != test->channels || (reference->channels != 1 && reference->channels != 3) ||
        reference->width == 0 || reference->height == 0 || !(pixels_per_degree >= 0.0f) ||
        !isfinite(pixels_per_degree))
        return ROMA_ERROR_INVALID_ARGUMENT;
    if (mask && (!mask->pixels || mask->channels != 1 || mask->width != reference->width ||
                 mask->height != reference->height))
        return ROMA_ERROR_INVALID_ARGUMENT;
    const double ppd = pixels_per_degree > 0.0f ? pixels_per_degree : ROMA_FLIP_DEFAULT_PPD;
    const uint32_t w = reference->width, h = reference->height;
    const size_t n = (size_t)w * h;
    flip_planes pr = {0}, pt = {0};
    float *tmp = malloc(n * sizeof(float)), *work = malloc(n * sizeof(float));
    roma_result r = ROMA_SUCCESS;
    if (!tmp || !work || !prepare(reference, ppd, &pr, tmp, work) || !prepare(test, ppd, &pt, tmp, work))
        r = ROMA_ERROR_OUT_OF_HOST_MEMORY;
    if (r == ROMA_SUCCESS && out_map)
        r = roma_image_alloc(out_map, w, h, 1);
    if (r == ROMA_SUCCESS) {
        /* The largest colour difference: between green and blue. */
        double green[3], blue[3];
        rgb_to_hunt_lab((const double[3]){0.0, 1.0, 0.0}, green);
        rgb_to_hunt_lab((const double[3]){0.0, 0.0, 1.0}, blue);
        const double cmax = pow(hyab(green, blue), Q_C), knee = P_C * cmax;
        double sum = 0.0;
        uint64_t counted = 0;
        for (size_t i = 0; i < n; ++i) {
            double lab[2][3];
            for (int k = 0; k < 2; ++k) {
                const flip_planes *p = k ? &pt : &pr;
                double ycc[3] = {p->ycc[0][i], p->ycc[1][i], p->ycc[2][i]}, rgb[3];
                ycxcz_to_rgb(ycc, rgb);
                for (int c = 0; c < 3; ++c)
                    rgb[c] = rgb[c] < 0.0 ? 0.0 : rgb[c] > 1.0 ? 1.0 : rgb[c];
                rgb_to_hunt_lab(rgb, lab[k]);
            }
            const double d = pow(hyab(lab[0], lab[1]), Q_C);
            const double colour = d < knee ? P_T / knee * d : P_T + (d - knee) / (cmax - knee) * (1.0 - P_T);
            const double feature = pow(fmax(fabs((double)pr.edge[i] - pt.edge[i]),
                                            fabs((double)pr.point[i] - pt.point[i])) / sqrt(2.0),
                                       Q_F);
            const double e = pow(colour, 1.0 - feature);
            if (out_map)
                out_map->pixels[i] = (float)e;
            if (!mask || mask->pixels[i] > 0.0f) {
                sum += e;
                ++counted;
            }
        }
        *out_mean = counted ? sum / (double)counted : 0.0;
    }
    if (r != ROMA_SUCCESS && out_map)
        roma_image_free(out_map);
    planes_free(&pr);
    planes_free(&pt);
    free(tmp);
    free(work);
    return r;
}
