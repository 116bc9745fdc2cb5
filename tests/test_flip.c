/* roma_image_flip (src/util/flip.c), LDR-FLIP from its paper, on images with known
 * differences:
 * - identical images: 0 at every pixel;
 * - uniform black against uniform white: no features, so the colour term alone, which the
 *   paper's formulas give from the CIE L*a*b* of black, white and the sRGB green and blue
 *   primaries (published values, independent of the code's colour conversions);
 * - noise of growing amplitude on grey: FLIP grows with it; FLIP is symmetric;
 * - a black/white edge moved by two pixels: large along the edge, 0 far from it (the
 *   feature and colour terms are local);
 * - the mask, and bad arguments. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "harness.h"
#include "roma/image.h"

#define N 64

static void fill(roma_image *img, float v)
{
    for (uint32_t i = 0; i < img->width * img->height * img->channels; ++i)
        img->pixels[i] = v;
}

static float hash(uint32_t i)
{
    i = (i ^ 61u) ^ (i >> 16);
    i *= 9u;
    i ^= i >> 4;
    i *= 0x27d4eb2du;
    i ^= i >> 15;
    return (float)(i & 0xffffu) / 65535.0f * 2.0f - 1.0f;
}

int main(void)
{
    roma_image a, b, map;
    CHECK_RESULT(roma_image_alloc(&a, N, N, 3), ROMA_SUCCESS);
    CHECK_RESULT(roma_image_alloc(&b, N, N, 3), ROMA_SUCCESS);
    if (!a.pixels || !b.pixels)
        return roma_test_finish("test_flip");
    double mean = -1.0;

    /* Identical. */
    for (uint32_t i = 0; i < N * N * 3; ++i)
        a.pixels[i] = b.pixels[i] = 0.5f + 0.4f * hash(i);
    CHECK_RESULT(roma_image_flip(&a, &b, NULL, 0.0f, &mean, &map), ROMA_SUCCESS);
    float largest = 0.0f;
    for (uint32_t i = 0; map.pixels && i < N * N; ++i)
        largest = fmaxf(largest, map.pixels[i]);
    CHECK(mean == 0.0 && largest == 0.0f);
    roma_image_free(&map);

    /* Black against white: HyAB(black, white) = 100 (L* 0 and 100, a* = b* = 0); the largest
     * difference is between the green and blue primaries, Hunt-scaled (a* and b* times one hundredth of L*). */
    fill(&a, 0.0f);
    fill(&b, 1.0f);
    CHECK_RESULT(roma_image_flip(&a, &b, NULL, 0.0f, &mean, NULL), ROMA_SUCCESS);
    const double g[3] = {87.7347, -86.1827, 83.1793}, bl[3] = {32.3026, 79.1967, -107.8637};
    const double ga = g[1] * g[0] / 100.0, gb = g[2] * g[0] / 100.0, ba = bl[1] * bl[0] / 100.0,
                 bb = bl[2] * bl[0] / 100.0;
    const double cmax = pow(fabs(g[0] - bl[0]) + sqrt((ga - ba) * (ga - ba) + (gb - bb) * (gb - bb)), 0.7);
    const double d = pow(100.0, 0.7), knee = 0.4 * cmax;
    const double expected = d < knee ? 0.95 / knee * d : 0.95 + (d - knee) / (cmax - knee) * 0.05;
    printf("black against white: FLIP %.5f, the paper's formulas %.5f\n", mean, expected);
    CHECK(fabs(mean - expected) < 1e-3);

    /* Noise on grey: growing with the amplitude; symmetric. */
    double previous = 0.0;
    const float amplitudes[4] = {0.02f, 0.05f, 0.1f, 0.2f};
    for (int k = 0; k < 4; ++k) {
        fill(&a, 0.5f);
        for (uint32_t i = 0; i < N * N * 3; ++i)
            b.pixels[i] = 0.5f + amplitudes[k] * hash(i / 3u);
        double ab, ba_mean;
        CHECK_RESULT(roma_image_flip(&a, &b, NULL, 0.0f, &ab, NULL), ROMA_SUCCESS);
        CHECK_RESULT(roma_image_flip(&b, &a, NULL, 0.0f, &ba_mean, NULL), ROMA_SUCCESS);
        printf("grey with noise of amplitude %.2f: FLIP %.4f\n", (double)amplitudes[k], ab);
        CHECK(ab > previous);
        CHECK(fabs(ab - ba_mean) < 1e-9);
        previous = ab;
    }

    /* An edge moved by two pixels (1 channel). */
    roma_image e1, e2;
    CHECK_RESULT(roma_image_alloc(&e1, N, N, 1), ROMA_SUCCESS);
    CHECK_RESULT(roma_image_alloc(&e2, N, N, 1), ROMA_SUCCESS);
    for (uint32_t y = 0; e1.pixels && e2.pixels && y < N; ++y)
        for (uint32_t x = 0; x < N; ++x) {
            e1.pixels[y * N + x] = x < 30 ? 0.0f : 1.0f;
            e2.pixels[y * N + x] = x < 32 ? 0.0f : 1.0f;
        }
    CHECK_RESULT(roma_image_flip(&e1, &e2, NULL, 0.0f, &mean, &map), ROMA_SUCCESS);
    float at_edge = 0.0f, far = 0.0f;
    for (uint32_t y = 0; map.pixels && y < N; ++y)
        for (uint32_t x = 0; x < N; ++x) {
            float v = map.pixels[y * N + x];
            if (x >= 30 && x < 32)
                at_edge = fmaxf(at_edge, v);
            else if (x < 10 || x >= 54)
                far = fmaxf(far, v);
        }
    printf("edge moved by 2 pixels: FLIP at the edge %.3f, farther than 20 pixels %.5f, mean %.4f\n", at_edge, far,
           mean);
    CHECK(at_edge > 0.9f);
    CHECK(far < 1e-3f);

    /* The mask: the mean over the counted pixels of the map. */
    roma_image mask;
    CHECK_RESULT(roma_image_alloc(&mask, N, N, 1), ROMA_SUCCESS);
    double masked = 0.0, want = 0.0;
    for (uint32_t i = 0; mask.pixels && map.pixels && i < N * N; ++i) {
        mask.pixels[i] = (i % N) >= 28 && (i % N) < 36 ? 1.0f : 0.0f;
        want += mask.pixels[i] > 0.0f ? map.pixels[i] : 0.0;
    }
    want /= 8.0 * N;
    CHECK_RESULT(roma_image_flip(&e1, &e2, &mask, 0.0f, &masked, NULL), ROMA_SUCCESS);
    CHECK(fabs(masked - want) < 1e-6);

    /* Bad arguments. */
    CHECK_RESULT(roma_image_flip(&e1, &a, NULL, 0.0f, &mean, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_image_flip(&e1, &e2, NULL, -1.0f, &mean, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_image_flip(&e1, &e2, NULL, NAN, &mean, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_image_flip(&e1, &e2, &a, 0.0f, &mean, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_image_flip(&e1, &e2, NULL, 0.0f, NULL, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_image_flip(&e1, &e2, NULL, 0.0f, &mean, &e1), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(e1.pixels != NULL && e1.pixels[N - 1] == 1.0f); /* the refused call left the input as it was */
    CHECK_RESULT(roma_image_flip(&e1, &e2, &mask, 0.0f, &mean, &mask), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(mask.pixels != NULL); /* the refused call left the mask as it was */
    roma_image_free(&map);
    roma_image_free(&mask);
    roma_image_free(&e1);
    roma_image_free(&e2);
    roma_image_free(&a);
    roma_image_free(&b);
    return roma_test_finish("test_flip");
}
