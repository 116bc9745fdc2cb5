/* Interactive frames (ROMA paper 4.3): each frame's accumulators resolved into
 * effect values on the GPU (resolve.comp), accumulated over frames with
 * reprojection through the motion vectors and rejection of disoccluded history
 * (temporal.comp), and on request filtered by an edge-aware a-trous wavelet
 * (atrous.comp). Effects are indexed 0 ao, 1 direct, 2 gi, 3 lights (the
 * order of ROMA_RESOLVE_*). */
#ifndef ROMA_PASSES_DENOISER_H
#define ROMA_PASSES_DENOISER_H

#include "passes/pixel_pass.h"
#include "roma/image.h"

#define ROMA_DENOISER_EFFECTS 4

typedef struct roma_denoiser {
    roma_context *ctx;
    uint32_t width, height;
    roma_pixel_pass resolve, temporal, atrous;
    roma_buffer current[ROMA_DENOISER_EFFECTS], history[ROMA_DENOISER_EFFECTS][2],
        filtered[ROMA_DENOISER_EFFECTS][2];
    int final_index; /* filtered[e][final_index]: the last filtered frame; -1 before one */
} roma_denoiser;

/* effect_mask: bit e for every effect to carry. On failure nothing stays allocated. */
roma_result roma_denoiser_create(roma_context *ctx, uint32_t width, uint32_t height, uint32_t effect_mask,
                                 roma_denoiser *out);
/* Accepts a zeroed denoiser. */
void roma_denoiser_destroy(roma_denoiser *dn);

typedef struct roma_denoise_inputs {
    VkDeviceAddress pixels, previous_pixels;    /* this and the previous frame's G-buffer */
    VkDeviceAddress accum[ROMA_DENOISER_EFFECTS][2]; /* per effect: resolve's a and b (roma_resolve_push) */
    uint32_t frame;                             /* 0 starts every history afresh */
    int filter;                                 /* run the a-trous iterations into filtered[] */
    uint32_t spp, many_light_count;
    uint32_t max_history;                       /* frames averaged at most (>= 1) */
    uint32_t filter_iterations;                 /* steps 1, 2, 4, ...; 0: the history as it is */
    float footprint;                            /* pixel size per unit of view distance */
    float value_sigma;                          /* a-trous value edge-stopping in noise units */
} roma_denoise_inputs;

roma_result roma_denoiser_record(roma_denoiser *dn, VkCommandBuffer cmd, const roma_denoise_inputs *in);

/* Effect e of the last filtered frame into out (1 channel: .r, 3: .rgb); the
 * recording must have completed. */
roma_result roma_denoiser_read(roma_denoiser *dn, int e, roma_image *out);

#endif /* ROMA_PASSES_DENOISER_H */
