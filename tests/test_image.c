/* PFM round trips bit for bit; the metrics match hand-computed values; bad files fail cleanly. */
#include <stdio.h>
#include <string.h>

#include "harness.h"
#include "roma/image.h"

static void write_bytes(const char *path, const void *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (f) {
        fwrite(data, 1, size, f);
        fclose(f);
    }
}

int main(void)
{
    char path[512];
    roma_image img, back;
    CHECK_RESULT(roma_image_alloc(&img, 5, 3, 3), ROMA_SUCCESS);
    for (uint32_t i = 0; i < 5 * 3 * 3; ++i)
        img.pixels[i] = (float)i * 0.25f - 1.5f;
    roma_test_tmp_path("image_rgb.pfm", path, sizeof path);
    CHECK_RESULT(roma_image_write_pfm(&img, path), ROMA_SUCCESS);
    CHECK_RESULT(roma_image_read_pfm(path, &back), ROMA_SUCCESS);
    CHECK(back.width == 5 && back.height == 3 && back.channels == 3);
    CHECK(back.pixels && memcmp(back.pixels, img.pixels, sizeof(float) * 45) == 0);
    roma_image_free(&back);

    /* Row order: the first row in memory is the top row, stored last in the file. */
    roma_image gray;
    CHECK_RESULT(roma_image_alloc(&gray, 2, 2, 1), ROMA_SUCCESS);
    gray.pixels[0] = 1.0f; /* top-left */
    roma_test_tmp_path("image_gray.pfm", path, sizeof path);
    CHECK_RESULT(roma_image_write_pfm(&gray, path), ROMA_SUCCESS);
    FILE *f = fopen(path, "rb");
    CHECK(f != NULL);
    if (f) {
        char header[16] = {0};
        CHECK(fread(header, 1, 11, f) == 11 && memcmp(header, "Pf\n2 2\n-1.0", 11) == 0);
        float data[4];
        fseek(f, -16, SEEK_END);
        CHECK(fread(data, sizeof(float), 4, f) == 4 && data[2] == 1.0f && data[0] == 0.0f);
        fclose(f);
    }

    /* Metrics against values computed by hand. */
    roma_image a, b, mask;
    roma_image_alloc(&a, 2, 2, 1);
    roma_image_alloc(&b, 2, 2, 1);
    roma_image_alloc(&mask, 2, 2, 1);
    float av[4] = {0.0f, 1.0f, 0.5f, 0.25f}, bv[4] = {0.1f, 1.0f, 0.0f, 0.25f};
    memcpy(a.pixels, av, sizeof av);
    memcpy(b.pixels, bv, sizeof bv);
    roma_image_metrics m;
    CHECK_RESULT(roma_image_compare(&a, &b, NULL, 0.2f, &m), ROMA_SUCCESS);
    CHECK(m.pixel_count == 4);
    CHECK_NEAR(m.mean_abs_error, 0.6 / 4.0, 1e-6);
    CHECK_NEAR(m.rmse, sqrt((0.01 + 0.25) / 4.0), 1e-6);
    CHECK_NEAR(m.max_abs_error, 0.5, 1e-6);
    CHECK_NEAR(m.fraction_above, 0.25, 1e-12);
    mask.pixels[0] = 1.0f;
    mask.pixels[1] = 1.0f;
    CHECK_RESULT(roma_image_compare(&a, &b, &mask, 0.2f, &m), ROMA_SUCCESS);
    CHECK(m.pixel_count == 2);
    CHECK_NEAR(m.mean_abs_error, 0.05, 1e-6);
    a.pixels[1] = NAN;
    CHECK_RESULT(roma_image_compare(&a, &b, NULL, 0.2f, &m), ROMA_SUCCESS);
    CHECK(m.non_finite == 1 && m.pixel_count == 3);
    roma_image diff;
    CHECK_RESULT(roma_image_abs_diff(&a, &b, &diff), ROMA_SUCCESS);
    CHECK(isnan(diff.pixels[1]));
    CHECK_NEAR(diff.pixels[2], 0.5, 1e-6);
    roma_image_free(&diff);

    /* Misuse. */
    CHECK_RESULT(roma_image_compare(&a, &img, NULL, 0.1f, &m), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_image_alloc(&back, 0, 4, 1), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_image_alloc(&back, 4, 4, 2), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_image_alloc(&back, 100000, 100000, 3), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(back.pixels == NULL);
    CHECK_RESULT(roma_image_read_pfm("no/such/file.pfm", &back), ROMA_ERROR_FILE_NOT_FOUND);
    roma_test_tmp_path("bad.pfm", path, sizeof path);
    write_bytes(path, "PF\n4 4\n-1.0\n\0\0\0\0", 16); /* truncated pixel data */
    CHECK_RESULT(roma_image_read_pfm(path, &back), ROMA_ERROR_PARSE);
    CHECK(back.pixels == NULL);
    write_bytes(path, "P6\n4 4\n255\n", 11);
    CHECK_RESULT(roma_image_read_pfm(path, &back), ROMA_ERROR_PARSE);
    write_bytes(path, "PF\n4 4\n1.0\n", 11); /* big-endian */
    CHECK_RESULT(roma_image_read_pfm(path, &back), ROMA_ERROR_PARSE);
    roma_image_free(NULL);

    roma_image_free(&a);
    roma_image_free(&b);
    roma_image_free(&mask);
    roma_image_free(&gray);
    roma_image_free(&img);
    return roma_test_finish("test_image");
}
