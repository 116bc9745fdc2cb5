#include "roma/image.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define ROMA_IMAGE_MAX_BYTES (1ull << 30)

static int valid_shape(uint32_t width, uint32_t height, uint32_t channels)
{
    if (width == 0 || height == 0 || (channels != 1 && channels != 3))
        return 0;
    /* width * height fits 64 bits; times channels * 4 bytes could wrap (2^31 x 2^31 x 1 -> 0). */
    return (unsigned long long)width * height <= ROMA_IMAGE_MAX_BYTES / (channels * sizeof(float));
}


roma_result roma_image_alloc(roma_image *image, uint32_t width, uint32_t height, uint32_t channels)
{
    if (!image)
        return ROMA_ERROR_INVALID_ARGUMENT;
    memset(image, 0, sizeof *image);
    if (!valid_shape(width, height, channels))
        return ROMA_ERROR_INVALID_ARGUMENT;
    float *pixels = calloc((size_t)width * height * channels, sizeof(float));
    if (!pixels)
        return ROMA_ERROR_OUT_OF_HOST_MEMORY;
    image->width = width;
    image->height = height;
    image->channels = channels;
    image->pixels = pixels;
    return ROMA_SUCCESS;
}

void roma_image_free(roma_image *image)
{
    if (!image)
        return;
    free(image->pixels);
    memset(image, 0, sizeof *image);
}

roma_result roma_image_write_pfm(const roma_image *image, const char *path)
{
    if (!image || !path || !image->pixels || !valid_shape(image->width, image->height, image->channels))
        return ROMA_ERROR_INVALID_ARGUMENT;
    FILE *f = fopen(path, "wb");
    if (!f)
        return errno == ENOENT ? ROMA_ERROR_FILE_NOT_FOUND : ROMA_ERROR_IO;
    /* Negative scale = little-endian; every platform libroma targets is little-endian. */
    int ok = fprintf(f, "%s\n%u %u\n-1.0\n", image->channels == 3 ? "PF" : "Pf", image->width,
                     image->height) > 0;
    size_t row = (size_t)image->width * image->channels;
    for (uint32_t y = image->height; ok && y-- > 0;) /* PFM stores the bottom row first */
        ok = fwrite(image->pixels + (size_t)y * row, sizeof(float), row, f) == row;
    if (fclose(f) != 0)
        ok = 0;
    return ok ? ROMA_SUCCESS : ROMA_ERROR_IO;
}

roma_result roma_image_read_pfm(const char *path, roma_image *out)
{
    if (!out)
        return ROMA_ERROR_INVALID_ARGUMENT;
    memset(out, 0, sizeof *out);
    if (!path)
        return ROMA_ERROR_INVALID_ARGUMENT;
    FILE *f = fopen(path, "rb");
    if (!f)
        return errno == ENOENT ? ROMA_ERROR_FILE_NOT_FOUND : ROMA_ERROR_IO;
    char magic[3] = {0};
    unsigned width = 0, height = 0;
    double scale = 0.0;
    roma_result result = ROMA_ERROR_PARSE;
    if (fscanf(f, "%2s %u %u %lf", magic, &width, &height, &scale) != 4 || fgetc(f) == EOF)
        goto done;
    uint32_t channels = strcmp(magic, "PF") == 0 ? 3 : strcmp(magic, "Pf") == 0 ? 1 : 0;
    if (channels == 0 || !(scale < 0.0) || !valid_shape(width, height, channels))
        goto done; /* big-endian files are not produced by libroma and rejected */
    result = roma_image_alloc(out, width, height, channels);
    if (result != ROMA_SUCCESS)
        goto done;
    size_t row = (size_t)width * channels;
    for (uint32_t y = height; y-- > 0;) {
        if (fread(out->pixels + (size_t)y * row, sizeof(float), row, f) != row) {
            roma_image_free(out);
            result = ROMA_ERROR_PARSE;
            goto done;
        }
    }
    result = ROMA_SUCCESS;
done:
    if (result == ROMA_ERROR_PARSE && ferror(f))
        result = ROMA_ERROR_IO; /* e.g. a directory: nothing could be read, nothing malformed */
    fclose(f);
    return result;
}

static int same_shape(const roma_image *a, const roma_image *b)
{
    return a->width == b->width && a->height == b->height && a->channels == b->channels;
}

static int usable(const roma_image *image)
{
    return image && image->pixels && valid_shape(image->width, image->height, image->channels);
}

roma_result roma_image_compare(const roma_image *a, const roma_image *b, const roma_image *mask,
                               float tolerance, roma_image_metrics *out)
{
    if (!out)
        return ROMA_ERROR_INVALID_ARGUMENT;
    memset(out, 0, sizeof *out);
    if (!usable(a) || !usable(b) || !same_shape(a, b) || isnan(tolerance))
        return ROMA_ERROR_INVALID_ARGUMENT; /* NaN would silently count no pixel as above */
    if (mask && (!usable(mask) || mask->channels != 1 || mask->width != a->width ||
                 mask->height != a->height))
        return ROMA_ERROR_INVALID_ARGUMENT;
    size_t pixels = (size_t)a->width * a->height;
    uint32_t c = a->channels;
    double sum_abs = 0.0, sum_sq = 0.0, sum_a = 0.0, sum_b = 0.0, max_abs = 0.0;
    uint64_t counted = 0, above = 0, non_finite = 0;
    for (size_t i = 0; i < pixels; ++i) {
        if (mask && !(mask->pixels[i] > 0.0f))
            continue;
        const float *pa = a->pixels + i * c, *pb = b->pixels + i * c;
        int finite = 1;
        for (uint32_t k = 0; k < c; ++k)
            finite &= isfinite(pa[k]) && isfinite(pb[k]);
        if (!finite) {
            ++non_finite;
            continue;
        }
        double pixel_max = 0.0;
        for (uint32_t k = 0; k < c; ++k) {
            double d = fabs((double)pa[k] - (double)pb[k]);
            sum_abs += d;
            sum_sq += d * d;
            sum_a += pa[k];
            sum_b += pb[k];
            if (d > pixel_max)
                pixel_max = d;
        }
        if (pixel_max > max_abs)
            max_abs = pixel_max;
        if (pixel_max > tolerance)
            ++above;
        ++counted;
    }
    out->pixel_count = counted;
    out->non_finite = non_finite;
    if (counted) {
        double n = (double)counted * c;
        out->mean_abs_error = sum_abs / n;
        out->rmse = sqrt(sum_sq / n);
        out->mean_a = sum_a / n;
        out->mean_b = sum_b / n;
        out->max_abs_error = max_abs;
        out->fraction_above = (double)above / (double)counted;
    }
    return ROMA_SUCCESS;
}

roma_result roma_image_abs_diff(const roma_image *a, const roma_image *b, roma_image *out)
{
    /* out aliasing an input would be zeroed (and its pixels leaked) before being read. */
    if (!out || out == a || out == b)
        return ROMA_ERROR_INVALID_ARGUMENT;
    memset(out, 0, sizeof *out);
    if (!usable(a) || !usable(b) || !same_shape(a, b))
        return ROMA_ERROR_INVALID_ARGUMENT;
    roma_result r = roma_image_alloc(out, a->width, a->height, 1);
    if (r != ROMA_SUCCESS)
        return r;
    size_t pixels = (size_t)a->width * a->height;
    for (size_t i = 0; i < pixels; ++i) {
        float m = 0.0f;
        for (uint32_t k = 0; k < a->channels; ++k) {
            float d = fabsf(a->pixels[i * a->channels + k] - b->pixels[i * a->channels + k]);
            if (!(d <= m)) /* NaN propagates so the heat map shows it */
                m = d;
        }
        out->pixels[i] = m;
    }
    return ROMA_SUCCESS;
}
