/** @file
 * libroma tools (library roma_tools): float images, PFM I/O and image metrics.
 *
 * The metrics here are the ones every accuracy test and benchmark uses to
 * compare a ROMA image with the reference. */
#ifndef ROMA_IMAGE_H
#define ROMA_IMAGE_H

#include "roma/api.h"

#include <stdint.h>

#include "roma/result.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Row-major, row 0 at the top, `channels` floats per pixel (1 or 3). */
typedef struct roma_image {
    uint32_t width; /**< pixels */
    uint32_t height; /**< pixels */
    uint32_t channels; /**< 1 or 3 */
    float *pixels; /**< width * height * channels floats, rows top first; owned (roma_image_free) */
} roma_image;

/** Allocates zeroed pixels. Rejects zero sizes, channels not in {1,3}, and sizes
 * whose byte count overflows or exceeds 1 GiB. */
ROMA_API roma_result roma_image_alloc(roma_image *image, uint32_t width, uint32_t height,
                                      uint32_t channels);
/** Frees pixels and zeroes the struct; accepts NULL and zeroed images. */
ROMA_API void roma_image_free(roma_image *image);

/** Portable float map: "Pf" for 1 channel, "PF" for 3, little-endian, rows stored bottom-up
 * as the format requires. */
ROMA_API roma_result roma_image_write_pfm(const roma_image *image, const char *path);
/** On success *out_image owns new pixels; on failure it is zeroed. */
ROMA_API roma_result roma_image_read_pfm(const char *path, roma_image *out_image);

/** Error figures of two images (roma_image_compare). */
typedef struct roma_image_metrics {
    double mean_abs_error;   /**< over all channels of the counted pixels */
    double rmse; /**< root mean square error over the counted channels */
    double max_abs_error; /**< largest absolute channel error */
    double mean_a; /**< mean of a over the counted pixels */
    double mean_b; /**< mean of b over the counted pixels */
    double fraction_above;   /**< fraction of counted pixels whose max channel error > tolerance */
    uint64_t pixel_count;    /**< pixels counted */
    uint64_t non_finite;     /**< pixels skipped because a or b held NaN/Inf */
} roma_image_metrics;

/** Compares a and b (same size and channels). mask is optional (1 channel, same size):
 * only pixels with mask > 0 count. Non-finite pixels are counted in non_finite and
 * excluded from the other figures. A NaN tolerance is rejected. */
ROMA_API roma_result roma_image_compare(const roma_image *a, const roma_image *b, const roma_image *mask,
                                        float tolerance, roma_image_metrics *out_metrics);

/** |a - b| per pixel (max over channels) into a new 1-channel image; out_diff must
 * not be a or b. */
ROMA_API roma_result roma_image_abs_diff(const roma_image *a, const roma_image *b, roma_image *out_diff);

#ifdef __cplusplus
}
#endif

#endif /**< ROMA_IMAGE_H */
