/* roma-compare: error metrics between two float images, PFM or OpenEXR (and an optional heat map). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "roma/image.h"

static const char *usage =
    "usage: roma-compare A.pfm|A.exr B.pfm|B.exr [--mask M.pfm|M.exr] [--tolerance T] [--heatmap out.png] [--heat-scale S]\n"
    "                    [--side-by-side out.png] [--exposure E]\n"
    "  Images are read as OpenEXR when their name ends in .exr, as PFM otherwise.\n"
    "  Prints mean absolute error, RMSE, max error and the fraction of pixels whose error\n"
    "  exceeds T (default 0.05), over the pixels where the mask (1 channel) is > 0.\n"
    "  The heat map shows |A-B| (max over channels) with S as white (default: the max error).\n"
    "  --side-by-side writes A and B next to each other, tone-mapped with exposure E (default 1).\n"
    "  Exit status: 0 ok, 1 unreadable or mismatched images, 2 usage.\n";

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
    float tolerance = 0.05f, heat_scale = 0.0f, exposure = 1.0f;
    int n = 0;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            fputs(usage, stdout);
            return 0;
        } else if (strcmp(a, "--mask") == 0 && v) mask_path = v, ++i;
        else if (strcmp(a, "--tolerance") == 0 && v) tolerance = parse_non_negative(v), ++i;
        else if (strcmp(a, "--heatmap") == 0 && v) heatmap = v, ++i;
        else if (strcmp(a, "--heat-scale") == 0 && v) heat_scale = parse_non_negative(v), ++i;
        else if (strcmp(a, "--side-by-side") == 0 && v) side_by_side = v, ++i;
        else if (strcmp(a, "--exposure") == 0 && v) exposure = parse_non_negative(v), ++i;
        else if (a[0] != '-' && n < 2) paths[n++] = a;
        else {
            fprintf(stderr, "roma-compare: unexpected argument %s\n%s", a, usage);
            return 2;
        }
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
            fprintf(stderr, "roma-compare: %s: %s\n", mask_path, roma_result_string(r));
            status = 1;
        }
    }
    roma_image_metrics m;
    if (status == 0) {
        roma_result r = roma_image_compare(&img[0], &img[1], mask_path ? &mask : NULL, tolerance, &m);
        if (r != ROMA_SUCCESS) {
            fprintf(stderr, "roma-compare: images differ in size or channels (%ux%ux%u vs %ux%ux%u)\n",
                    img[0].width, img[0].height, img[0].channels, img[1].width, img[1].height, img[1].channels);
            status = 1;
        }
    }
    if (status == 0) {
        printf("pixels        %llu\n", (unsigned long long)m.pixel_count);
        printf("mean_abs      %.6g\n", m.mean_abs_error);
        printf("rmse          %.6g\n", m.rmse);
        printf("max_abs       %.6g\n", m.max_abs_error);
        printf("above_%-7g %.6g\n", tolerance, m.fraction_above);
        printf("mean_a        %.6g\nmean_b        %.6g\n", m.mean_a, m.mean_b);
        if (m.non_finite)
            printf("non_finite    %llu\n", (unsigned long long)m.non_finite);
        if (heatmap) {
            roma_image diff;
            if (roma_image_abs_diff(&img[0], &img[1], &diff) == ROMA_SUCCESS) {
                float scale = heat_scale > 0.0f ? heat_scale : (float)m.max_abs_error;
                if (roma_app_write_png(&diff, heatmap, ROMA_PNG_HEAT, scale > 0.0f ? scale : 1.0f) == ROMA_SUCCESS)
                    printf("wrote %s\n", heatmap);
                else
                    status = 1;
                roma_image_free(&diff);
            }
        }
    }
    if (status == 0 && side_by_side && !write_side_by_side(img, side_by_side, exposure))
        status = 1;
    roma_image_free(&img[0]);
    roma_image_free(&img[1]);
    roma_image_free(&mask);
    return status;
}
