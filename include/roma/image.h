/** @file
 * libroma tools (library roma_tools): float images, PFM I/O and image metrics.
 *
 * The metrics here are the ones every accuracy test and benchmark uses to
 * compare a ROMA image with the reference. The functions touch only their arguments: any
 * thread, as long as no other thread writes the same image. */
#ifndef ROMA_IMAGE_H
#define ROMA_IMAGE_H

#include "roma/api.h"

#include <stdint.h>

#include "roma/result.h"

#ifdef __cplusplus
extern "C" {
#endif

/** A float image: row-major, row 0 at the top, `channels` floats per pixel (1 or 3). */
typedef struct roma_image {
    uint32_t width; /**< pixels */
    uint32_t height; /**< pixels */
    uint32_t channels; /**< 1 or 3 */
    float *pixels; /**< width * height * channels floats, rows top first; owned (roma_image_free) */
} roma_image;

/** Allocates zeroed pixels. Rejects zero sizes, channels not in {1,3}, and sizes
 * whose byte count overflows or exceeds 1 GiB.
 *
 * @param[out] image  zeroed first (pixels it held are not freed), then filled; owns the new
 *                    pixels (roma_image_free).
 * @param width       pixels, > 0.
 * @param height      pixels, > 0.
 * @param channels    1 or 3.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL image or a rejected size;
 *         ROMA_ERROR_OUT_OF_HOST_MEMORY.
 * @par Threads
 * Any thread. */
ROMA_API roma_result roma_image_alloc(roma_image *image, uint32_t width, uint32_t height,
                                      uint32_t channels);
/** Frees pixels and zeroes the struct.
 *
 * @param image  the image; NULL and zeroed images are accepted.
 * @par Threads
 * Any thread. */
ROMA_API void roma_image_free(roma_image *image);

/** Writes a portable float map: "Pf" for 1 channel, "PF" for 3, little-endian, rows stored
 * bottom-up as the format requires. Overwrites path.
 *
 * @param image  the image, with pixels and a valid size.
 * @param path   the file to write.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for NULL arguments or an image without
 *         pixels or with an invalid size; ROMA_ERROR_FILE_NOT_FOUND when path cannot be
 *         created (its directory is missing); ROMA_ERROR_IO for other open or write failures.
 * @par Threads
 * Any thread. */
ROMA_API roma_result roma_image_write_pfm(const roma_image *image, const char *path);
/** Reads a little-endian portable float map ("Pf" or "PF"; big-endian files are refused).
 *
 * @param path            the file to read.
 * @param[out] out_image  on success owns new pixels (roma_image_free); on failure it is zeroed.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for NULL arguments;
 *         ROMA_ERROR_FILE_NOT_FOUND; ROMA_ERROR_IO (cannot open or read, e.g. a directory);
 *         ROMA_ERROR_PARSE (bad header, big-endian, a size roma_image_alloc refuses, truncated
 *         data); ROMA_ERROR_OUT_OF_HOST_MEMORY.
 * @par Threads
 * Any thread. */
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
 * excluded from the other figures. A NaN tolerance is rejected.
 *
 * @param a          first image (mean_a), with pixels.
 * @param b          second image (mean_b), same size and channels.
 * @param mask       NULL: every pixel counts.
 * @param tolerance  per-pixel error above which a pixel counts in fraction_above.
 * @param[out] out_metrics  the figures; zeroed first (the errors and means stay 0 when no
 *                   pixel counts).
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL out_metrics, a or b NULL,
 *         without pixels or of different shapes, a mask of the wrong shape, a NaN tolerance.
 * @par Threads
 * Any thread. */
ROMA_API roma_result roma_image_compare(const roma_image *a, const roma_image *b, const roma_image *mask,
                                        float tolerance, roma_image_metrics *out_metrics);

/** |a - b| per pixel (max over channels) into a new 1-channel image; out_diff must
 * not be a or b. NaN differences stay NaN.
 *
 * @param a              first image, with pixels.
 * @param b              second image, same size and channels.
 * @param[out] out_diff  zeroed first, then owns new pixels (roma_image_free).
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL out_diff, out_diff equal to a
 *         or b, a or b unusable or of different shapes; ROMA_ERROR_OUT_OF_HOST_MEMORY.
 * @par Threads
 * Any thread. */
ROMA_API roma_result roma_image_abs_diff(const roma_image *a, const roma_image *b, roma_image *out_diff);

/** FLIP's default observer: 0.7 m from a 0.7 m wide monitor of 3840 pixels, 67 pixels per
 * degree of visual angle. */
#define ROMA_FLIP_DEFAULT_PPD 67.02f

/** LDR-FLIP, the perceptual difference of Andersson et al. (HPG 2020), implemented from the
 * paper: per pixel 0 (no visible difference) to 1, from a colour term (the images filtered by
 * the eye's contrast sensitivity in an opponent colour space, then compared in L*a*b* with
 * the Hunt effect) and a feature term (edges and points of the achromatic channel that one
 * image has and the other lacks). The images are taken as displayed: linear values clamped
 * to [0, 1] (scale radiance by an exposure first); a 1-channel image is grey. Symmetric in
 * its two images.
 *
 * @param reference          first image, with pixels (1 or 3 channels).
 * @param test               second image, same size and channels.
 * @param mask               NULL or 1 channel of the same size: the mean counts only pixels
 *                           with mask > 0 (the filters still see every pixel).
 * @param pixels_per_degree  the observer (0 = ROMA_FLIP_DEFAULT_PPD); sets the filters' widths.
 * @param[out] out_mean      the mean FLIP over the counted pixels (0 when none counts).
 * @param[out] out_map       NULL, or zeroed then given the per-pixel FLIP (1 channel,
 *                           roma_image_free); must not be an input.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL out_mean, images unusable or of
 *         different shapes, a mask of the wrong shape, a negative or non-finite
 *         pixels_per_degree, out_map equal to an input (left as it was); ROMA_ERROR_OUT_OF_HOST_MEMORY.
 * @par Threads
 * Any thread. */
ROMA_API roma_result roma_image_flip(const roma_image *reference, const roma_image *test, const roma_image *mask,
                                     float pixels_per_degree, double *out_mean, roma_image *out_map);

#ifdef __cplusplus
}
#endif

#endif /* ROMA_IMAGE_H */
