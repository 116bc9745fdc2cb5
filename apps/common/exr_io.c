/* OpenEXR files of the tools' float images through Debian's tinyexr: 32-bit float
 * channels, ZIP compressed, rows top first (as roma_image). One channel is written as
 * "Y" (luminance, shown grey by image viewers), three as "R", "G", "B". */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <tinyexr.h>

#include "app_common.h"

static roma_result exr_error(const char *what, const char *path, const char *err)
{
    fprintf(stderr, "%s %s: %s\n", what, path, err ? err : "unknown tinyexr error");
    if (err)
        FreeEXRErrorMessage(err);
    return ROMA_ERROR_IO;
}

roma_result roma_app_write_exr(const roma_image *image, const char *path)
{
    if (!image || !image->pixels || (image->channels != 1 && image->channels != 3) || !path)
        return ROMA_ERROR_INVALID_ARGUMENT;
    size_t n = (size_t)image->width * image->height;
    int c = (int)image->channels;
    /* EXR stores channels by name in alphabetical order: B, G, R. */
    static const char *rgb_names[3] = {"B", "G", "R"};
    float *planes = malloc(sizeof(float) * n * (size_t)c);
    if (!planes)
        return ROMA_ERROR_OUT_OF_HOST_MEMORY;
    unsigned char *plane_ptrs[3];
    EXRChannelInfo channels[3];
    int types[3], requested[3];
    memset(channels, 0, sizeof channels);
    for (int k = 0; k < c; ++k) {
        int source = c == 1 ? 0 : 2 - k; /* B from channel 2, G from 1, R from 0 */
        float *plane = planes + n * (size_t)k;
        for (size_t i = 0; i < n; ++i)
            plane[i] = image->pixels[i * (size_t)c + (size_t)source];
        plane_ptrs[k] = (unsigned char *)plane;
        snprintf(channels[k].name, sizeof channels[k].name, "%s", c == 1 ? "Y" : rgb_names[k]);
        types[k] = TINYEXR_PIXELTYPE_FLOAT;
        requested[k] = TINYEXR_PIXELTYPE_FLOAT;
    }
    EXRHeader header;
    InitEXRHeader(&header);
    header.num_channels = c;
    header.channels = channels;
    header.pixel_types = types;
    header.requested_pixel_types = requested;
    header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;
    EXRImage img;
    InitEXRImage(&img);
    img.num_channels = c;
    img.images = plane_ptrs;
    img.width = (int)image->width;
    img.height = (int)image->height;
    const char *err = NULL;
    int rc = SaveEXRImageToFile(&img, &header, path, &err);
    free(planes);
    return rc == TINYEXR_SUCCESS ? ROMA_SUCCESS : exr_error("cannot write", path, err);
}

roma_result roma_app_read_exr(const char *path, roma_image *out)
{
    if (!path || !out)
        return ROMA_ERROR_INVALID_ARGUMENT;
    memset(out, 0, sizeof *out);
    EXRVersion version;
    if (ParseEXRVersionFromFile(&version, path) != TINYEXR_SUCCESS) {
        fprintf(stderr, "cannot read %s: not an OpenEXR file\n", path);
        return ROMA_ERROR_IO;
    }
    if (version.multipart || version.tiled || version.non_image) {
        fprintf(stderr, "cannot read %s: only single-part scanline EXR files are read\n", path);
        return ROMA_ERROR_IO;
    }
    EXRHeader header;
    InitEXRHeader(&header);
    const char *err = NULL;
    if (ParseEXRHeaderFromFile(&header, &version, path, &err) != TINYEXR_SUCCESS)
        return exr_error("cannot read", path, err);
    for (int k = 0; k < header.num_channels; ++k)
        header.requested_pixel_types[k] = TINYEXR_PIXELTYPE_FLOAT; /* half becomes float */
    EXRImage img;
    InitEXRImage(&img);
    if (LoadEXRImageFromFile(&img, &header, path, &err) != TINYEXR_SUCCESS) {
        FreeEXRHeader(&header);
        return exr_error("cannot read", path, err);
    }
    /* Y, or R, G and B (other channels, such as A, are ignored). */
    int y = -1, rgb[3] = {-1, -1, -1};
    for (int k = 0; k < header.num_channels; ++k) {
        const char *name = header.channels[k].name;
        if (!strcmp(name, "Y"))
            y = k;
        else if (!strcmp(name, "R"))
            rgb[0] = k;
        else if (!strcmp(name, "G"))
            rgb[1] = k;
        else if (!strcmp(name, "B"))
            rgb[2] = k;
    }
    int has_rgb = rgb[0] >= 0 && rgb[1] >= 0 && rgb[2] >= 0;
    roma_result r = ROMA_ERROR_IO;
    if (!has_rgb && y < 0) {
        fprintf(stderr, "cannot read %s: it has neither a Y channel nor R, G and B\n", path);
    } else if (img.width <= 0 || img.height <= 0) {
        fprintf(stderr, "cannot read %s: empty image\n", path);
    } else {
        uint32_t c = has_rgb ? 3 : 1;
        r = roma_image_alloc(out, (uint32_t)img.width, (uint32_t)img.height, c);
        if (r == ROMA_SUCCESS) {
            size_t n = (size_t)img.width * (size_t)img.height;
            for (uint32_t k = 0; k < c; ++k) {
                const float *plane = (const float *)img.images[has_rgb ? rgb[k] : y];
                for (size_t i = 0; i < n; ++i)
                    out->pixels[i * c + k] = plane[i];
            }
        }
    }
    FreeEXRImage(&img);
    FreeEXRHeader(&header);
    return r;
}

roma_result roma_app_read_image(const char *path, roma_image *out)
{
    size_t n = path ? strlen(path) : 0;
    if (n > 4 && !strcmp(path + n - 4, ".exr"))
        return roma_app_read_exr(path, out);
    return roma_image_read_pfm(path, out);
}
