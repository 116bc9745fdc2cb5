#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include <stb_image_write.h>

#include "app_common.h"

static uint8_t to_srgb8(float linear)
{
    if (!(linear > 0.0f)) /* also NaN */
        return 0;
    if (linear >= 1.0f)
        return 255;
    float s = linear <= 0.0031308f ? 12.92f * linear : 1.055f * powf(linear, 1.0f / 2.4f) - 0.055f;
    return (uint8_t)(s * 255.0f + 0.5f);
}

static void heat(float t, uint8_t rgb[3])
{
    if (isnan(t)) { /* NaN shows as magenta so it cannot hide */
        rgb[0] = 255, rgb[1] = 0, rgb[2] = 255;
        return;
    }
    t = t < 0.0f ? 0.0f : t > 1.0f ? 1.0f : t;
    float r = fminf(1.0f, 3.0f * t), g = fminf(1.0f, fmaxf(0.0f, 3.0f * t - 1.0f)),
          b = fmaxf(0.0f, 3.0f * t - 2.0f);
    rgb[0] = (uint8_t)(r * 255.0f + 0.5f);
    rgb[1] = (uint8_t)(g * 255.0f + 0.5f);
    rgb[2] = (uint8_t)(b * 255.0f + 0.5f);
}

roma_result roma_app_write_png(const roma_image *image, const char *path, roma_png_mode mode, float scale)
{
    if (!image || !image->pixels || !path)
        return ROMA_ERROR_INVALID_ARGUMENT;
    size_t n = (size_t)image->width * image->height;
    uint8_t *rgb = malloc(n * 3);
    if (!rgb)
        return ROMA_ERROR_OUT_OF_HOST_MEMORY;
    for (size_t i = 0; i < n; ++i) {
        const float *p = image->pixels + i * image->channels;
        if (mode == ROMA_PNG_HEAT) {
            float m = p[0];
            for (uint32_t c = 1; c < image->channels; ++c)
                m = fmaxf(m, p[c]);
            heat(scale > 0.0f ? m / scale : m, rgb + 3 * i);
        } else {
            for (int c = 0; c < 3; ++c)
                rgb[3 * i + c] = to_srgb8(p[image->channels == 3 ? c : 0] * scale);
        }
    }
    int ok = stbi_write_png(path, (int)image->width, (int)image->height, 3, rgb, (int)image->width * 3);
    free(rgb);
    return ok ? ROMA_SUCCESS : ROMA_ERROR_IO;
}
