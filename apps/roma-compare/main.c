/* roma-compare: error metrics between two float images, PFM or OpenEXR (and an optional heat map). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "roma/image.h"
#include "stats_json.h"

static const char *usage =
    "usage: roma-compare A.pfm|A.exr B.pfm|B.exr [--mask M.pfm|M.exr [--mask-max V]] [--tolerance T] [--heatmap out.png] [--heat-scale S]\n"
    "                    [--side-by-side out.png] [--exposure E] [--threshold T] [--json out.json]\n"
    "  Images are read as OpenEXR when their name ends in .exr, as PFM otherwise.\n"
    "  Prints mean absolute error, RMSE, max error and the fraction of pixels whose error\n"
    "  exceeds T (default 0.05), over the pixels where the mask (1 channel) is > 0.\n"
    "  --mask-max V: only where the mask is <= V too (with roma-render's distance.pfm as the\n"
    "  mask: the pixels whose surface is within V of the eye).\n"
    "  The heat map shows |A-B| (max over channels) with S as white (default: the max error).\n"
    "  A 12-pixel strip under the heat map is its legend: black (0) to white (S), left to right.\n"
    "  --side-by-side writes A and B next to each other, tone-mapped with exposure E (default 1).\n"
    "  flip: the mean LDR-FLIP (0: no visible difference, 1: the largest) of the images as\n"
    "  displayed: times E, clamped to [0, 1], seen at 67 pixels per degree.\n"
    "  --threshold T: exit status 3 when the mean absolute error is above T (a pass/fail check).\n"
    "  --json writes the figures as JSON.\n"
    "  Output: one line per figure, its key first (scripts read the first two columns), then\n"
    "  what it means. relative = mean_abs / mean_b; bias = mean_a - mean_b.\n"
    "  Exit status: 0 ok, 1 unreadable or mismatched images, 2 usage, 3 above --threshold.\n";

/* A finite, non-negative number or -1. */
static float parse_non_negative(const char *s)
{
    char *end;
    float v = strtof(s, &end);
    return (end != s && !*end && isfinite(v) && v >= 0.0f) ? v : -1.0f;
}

/* A | B in one PNG (same size and channels, checked by the comparison). */
static int write_side_by_side(const roma_image img[2], const char *path, float exposure)
{
    const uint32_t w = img[0].width, h = img[0].height, c = img[0].channels;
    roma_image both = {0};
    if (roma_image_alloc(&both, 2 * w, h, c) != ROMA_SUCCESS) {
        fprintf(stderr, "roma-compare: cannot allocate the side-by-side image\n");
        return 0;
    }
    for (uint32_t y = 0; y < h; ++y)
        for (int k = 0; k < 2; ++k)
            memcpy(&both.pixels[((size_t)y * 2 * w + (size_t)k * w) * c], &img[k].pixels[(size_t)y * w * c],
                   sizeof(float) * w * c);
    int ok = roma_app_write_png(&both, path, ROMA_PNG_SRGB, exposure) == ROMA_SUCCESS;
    if (ok)
        printf("wrote %s\n", path);
    else
        fprintf(stderr, "roma-compare: cannot write %s\n", path);
    roma_image_free(&both);
    return ok;
}

int main(int argc, char **argv)
{
    const char *paths[2] = {NULL, NULL}, *mask_path = NULL, *heatmap = NULL, *side_by_side = NULL;
    float tolerance = 0.05f, heat_scale = 0.0f, exposure = 1.0f, threshold = -1.0f, mask_max = INFINITY;
    const char *json_path = NULL;
    int n = 0;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            fputs(usage, stdout);
            return 0;
        } else if (strcmp(a, "--mask") == 0 && v) mask_path = v, ++i;
        else if (strcmp(a, "--mask-max") == 0 && v) {
            mask_max = parse_non_negative(v), ++i;
            if (!(mask_max > 0.0f)) {
                fprintf(stderr, "roma-compare: --mask-max takes a number > 0\n%s", usage);
                return 2;
            }
        }
        else if (strcmp(a, "--tolerance") == 0 && v) tolerance = parse_non_negative(v), ++i;
        else if (strcmp(a, "--heatmap") == 0 && v) heatmap = v, ++i;
        else if (strcmp(a, "--heat-scale") == 0 && v) heat_scale = parse_non_negative(v), ++i;
        else if (strcmp(a, "--side-by-side") == 0 && v) side_by_side = v, ++i;
        else if (strcmp(a, "--exposure") == 0 && v) exposure = parse_non_negative(v), ++i;
        else if (strcmp(a, "--threshold") == 0 && v) {
            threshold = parse_non_negative(v), ++i;
            if (threshold < 0.0f) {
                fprintf(stderr, "roma-compare: --threshold takes a number >= 0\n%s", usage);
                return 2;
            }
        } else if (strcmp(a, "--json") == 0 && v) json_path = v, ++i;
        else if (a[0] != '-' && n < 2) paths[n++] = a;
        else {
            fprintf(stderr, "roma-compare: unexpected argument %s\n%s", a, usage);
            return 2;
        }
    }
    if (n == 2 && !mask_path && isfinite(mask_max)) {
        fprintf(stderr, "roma-compare: --mask-max needs --mask\n%s", usage);
        return 2;
    }
    if (n != 2 || tolerance < 0.0f || heat_scale < 0.0f || exposure < 0.0f) {
        fprintf(stderr, "roma-compare: %s\n%s",
                n != 2 ? "need two images" : "--tolerance, --heat-scale and --exposure take a number >= 0", usage);
        return 2;
    }
    roma_image img[2] = {{0}}, mask = {0};
    for (int k = 0; k < 2; ++k) {
        roma_result r = roma_app_read_image(paths[k], &img[k]);
        if (r != ROMA_SUCCESS) {
            fprintf(stderr, "roma-compare: %s: %s\n", paths[k], roma_result_string(r));
            roma_image_free(&img[0]);
            return 1;
        }
    }
    int status = 0;
    if (mask_path) {
        roma_result r = roma_app_read_image(mask_path, &mask);
        if (r != ROMA_SUCCESS) {
            fprintf(stderr, "roma-compare: the mask %s: %s\n", mask_path, roma_result_string(r));
            status = 1;
        } else if (mask.channels != 1) {
            fprintf(stderr, "roma-compare: the mask %s has %u channels; a mask has 1 (coverage.pfm)\n", mask_path,
                    mask.channels);
            status = 1;
        } else if (mask.width != img[0].width || mask.height != img[0].height) {
            fprintf(stderr, "roma-compare: the mask %s is %ux%u, the images %ux%u\n", mask_path, mask.width,
                    mask.height, img[0].width, img[0].height);
            status = 1;
        } else {
            for (size_t i = 0; i < (size_t)mask.width * mask.height; ++i)
                if (!(mask.pixels[i] <= mask_max))
                    mask.pixels[i] = 0.0f;
        }
    }
    roma_image_metrics m;
    if (status == 0) {
        roma_result r = roma_image_compare(&img[0], &img[1], mask_path ? &mask : NULL, tolerance, &m);
        if (r != ROMA_SUCCESS) {
            fprintf(stderr, "roma-compare: the images differ in size or channels: A (%s) is %ux%u with %u channel%s, "
                            "B (%s) %ux%u with %u\n", paths[0], img[0].width, img[0].height, img[0].channels,
                    img[0].channels == 1 ? "" : "s", paths[1], img[1].width, img[1].height, img[1].channels);
            status = 1;
        }
    }
    double relative = 0.0, bias = 0.0, flip = 0.0;
    float scale = 1.0f;
    int flip_ok = 0;
    if (status == 0) {
        /* FLIP sees the images as displayed: times the exposure. */
        roma_image shown[2] = {{0}, {0}};
        int copied = 1;
        for (int k = 0; k < 2 && copied; ++k) {
            copied = roma_image_alloc(&shown[k], img[k].width, img[k].height, img[k].channels) == ROMA_SUCCESS;
            for (size_t i = 0; copied && i < (size_t)img[k].width * img[k].height * img[k].channels; ++i)
                shown[k].pixels[i] = img[k].pixels[i] * exposure;
        }
        flip_ok = copied && roma_image_flip(&shown[1], &shown[0], mask_path ? &mask : NULL, 0.0f, &flip, NULL) ==
                                ROMA_SUCCESS;
        roma_image_free(&shown[0]);
        roma_image_free(&shown[1]);
    }
    if (status == 0) {
        relative = m.mean_b != 0.0 ? m.mean_abs_error / fabs(m.mean_b) : 0.0;
        bias = m.mean_a - m.mean_b;
        scale = heat_scale > 0.0f ? heat_scale : m.max_abs_error > 0.0 ? (float)m.max_abs_error : 1.0f;
        printf("A             %s\n", paths[0]);
        printf("B             %s\n", paths[1]);
        if (isfinite(mask_max))
            printf("pixels        %-12llu pixels compared (where the mask is > 0 and <= %g)\n",
                   (unsigned long long)m.pixel_count, (double)mask_max);
        else
            printf("pixels        %-12llu pixels compared%s\n", (unsigned long long)m.pixel_count,
                   mask_path ? " (where the mask is > 0)" : "");
        printf("mean_abs      %-12.6g mean |A - B| over every channel\n", m.mean_abs_error);
        printf("relative      %-12.6g mean_abs / mean_b (%.2f%%)\n", relative, 100.0 * relative);
        printf("bias          %-12.6g mean_a - mean_b (> 0: A is brighter)\n", bias);
        printf("rmse          %-12.6g root mean square of A - B\n", m.rmse);
        printf("max_abs       %-12.6g largest |A - B|\n", m.max_abs_error);
        printf("above_%-7g %-12.6g fraction of pixels whose error (max over channels) is above %g\n", tolerance,
               m.fraction_above, tolerance);
        printf("mean_a        %-12.6g mean of A\nmean_b        %-12.6g mean of B\n", m.mean_a, m.mean_b);
        if (flip_ok)
            printf("flip          %-12.6g mean LDR-FLIP of A and B times %g, clamped to [0, 1]\n", flip, exposure);
        if (m.non_finite)
            printf("non_finite    %-12llu pixels skipped: NaN or infinite in A or B\n",
                   (unsigned long long)m.non_finite);
        if (heatmap) {
            printf("heat_scale    %-12.6g |A - B| drawn white in the heat map (black: 0)\n", scale);
            roma_image diff, legend = {0};
            if (roma_image_abs_diff(&img[0], &img[1], &diff) == ROMA_SUCCESS &&
                roma_image_alloc(&legend, diff.width, diff.height + 12, 1) == ROMA_SUCCESS) {
                /* The heat map (max over channels), then a 12-pixel strip: 0 to scale. */
                for (size_t i = 0; i < (size_t)diff.width * diff.height; ++i) {
                    float v = diff.pixels[i * diff.channels];
                    for (uint32_t c = 1; c < diff.channels; ++c)
                        v = fmaxf(v, diff.pixels[i * diff.channels + c]);
                    legend.pixels[i] = v;
                }
                for (uint32_t y = diff.height; y < diff.height + 12; ++y)
                    for (uint32_t x = 0; x < diff.width; ++x)
                        legend.pixels[(size_t)y * diff.width + x] =
                            y < diff.height + 2 ? 0.0f : scale * (float)x / (float)(diff.width > 1 ? diff.width - 1 : 1);
                if (roma_app_write_png(&legend, heatmap, ROMA_PNG_HEAT, scale) == ROMA_SUCCESS)
                    printf("wrote %s\n", heatmap);
                else {
                    fprintf(stderr, "roma-compare: cannot write %s\n", heatmap);
                    status = 1;
                }
            }
            roma_image_free(&diff);
            roma_image_free(&legend);
        }
    }
    if (status == 0 && json_path) {
        FILE *f = fopen(json_path, "w");
        if (!f) {
            fprintf(stderr, "roma-compare: cannot write %s: %s\n", json_path, strerror(errno));
            status = 1;
        } else {
            roma_json j = {.f = f};
            roma_json_begin_object(&j, NULL);
            roma_json_string(&j, "a", paths[0]);
            roma_json_string(&j, "b", paths[1]);
            roma_json_string(&j, "mask", mask_path ? mask_path : "");
            if (isfinite(mask_max))
                roma_json_number(&j, "mask_max", mask_max);
            roma_json_int(&j, "pixels", (long long)m.pixel_count);
            roma_json_number(&j, "mean_abs", m.mean_abs_error);
            roma_json_number(&j, "relative", relative);
            roma_json_number(&j, "bias", bias);
            roma_json_number(&j, "rmse", m.rmse);
            roma_json_number(&j, "max_abs", m.max_abs_error);
            roma_json_number(&j, "tolerance", tolerance);
            roma_json_number(&j, "fraction_above", m.fraction_above);
            roma_json_number(&j, "mean_a", m.mean_a);
            roma_json_number(&j, "mean_b", m.mean_b);
            if (flip_ok)
                roma_json_number(&j, "flip", flip);
            roma_json_int(&j, "non_finite", (long long)m.non_finite);
            if (threshold >= 0.0f) {
                roma_json_number(&j, "threshold", threshold);
                roma_json_string(&j, "result", m.mean_abs_error <= threshold ? "pass" : "fail");
            }
            roma_json_end_object(&j);
            if (j.failed | ferror(f) | fclose(f)) {
                fprintf(stderr, "roma-compare: error while writing %s\n", json_path);
                status = 1;
            } else {
                printf("wrote %s\n", json_path);
            }
        }
    }
    if (status == 0 && side_by_side && !write_side_by_side(img, side_by_side, exposure))
        status = 1;
    if (status == 0 && threshold >= 0.0f && m.mean_abs_error > threshold) {
        printf("FAIL: mean_abs %.6g is above the threshold %g\n", m.mean_abs_error, threshold);
        status = 3;
    } else if (status == 0 && threshold >= 0.0f) {
        printf("pass: mean_abs %.6g is within the threshold %g\n", m.mean_abs_error, threshold);
    }
    roma_image_free(&img[0]);
    roma_image_free(&img[1]);
    roma_image_free(&mask);
    return status;
}
