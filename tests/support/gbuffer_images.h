/* The engine's side of a test of the public effects: Embree's primary hits of a camera as
 * the G-buffer images an engine would hand the effects (position, shading and geometric
 * normal, uploaded once), an RGBA32F and an R32F output, a host staging buffer the outputs
 * are read back into, and one command buffer. Failures count as test failures. */
#ifndef ROMA_TEST_GBUFFER_IMAGES_H
#define ROMA_TEST_GBUFFER_IMAGES_H

#include "gpu_images.h"
#include "reference.h"
#include "roma/ao_effect.h"
#include "roma/camera.h"
#include "roma/light_effect.h"

typedef struct roma_test_gbuffer {
    uint32_t width, height, covered_count;
    roma_ref_hit *hits; /* width * height */
    int *covered;       /* 1 where the primary ray hit */
    roma_test_image in[3], rgba, r;
    roma_test_staging staging; /* the three input planes, then the RGBA output, then the R output */
    VkDevice device;
    VkCommandPool pool;
    VkCommandBuffer cmd;
    int uploaded;
} roma_test_gbuffer;

/* Returns 0 (a failed check) when something could not be made. */
int roma_test_gbuffer_create(roma_context *ctx, const roma_ref *ref, const roma_camera *camera, uint32_t width,
                             uint32_t height, roma_test_gbuffer *out);
/* The same with the first `border` columns and rows left uncovered (w = 0) whatever they
 * see: pixels an effect must leave as they were. */
int roma_test_gbuffer_create_bordered(roma_context *ctx, const roma_ref *ref, const roma_camera *camera,
                                      uint32_t width, uint32_t height, uint32_t border, roma_test_gbuffer *out);
void roma_test_gbuffer_destroy(roma_context *ctx, roma_test_gbuffer *g);

/* Begins g->cmd: the first time with the inputs' upload; every time with both outputs moved
 * to GENERAL for the effects to write. */
VkCommandBuffer roma_test_gbuffer_begin(roma_test_gbuffer *g);
/* Copies both outputs back, submits and waits; the RGBA output (4 floats a pixel) and the R
 * output (1 a pixel) are then in *rgba and *r. */
void roma_test_gbuffer_finish(roma_context *ctx, roma_test_gbuffer *g, const float **rgba, const float **r);

roma_light_images roma_test_gbuffer_light_images(const roma_test_gbuffer *g);
roma_ao_images roma_test_gbuffer_ao_images(const roma_test_gbuffer *g);

#endif /* ROMA_TEST_GBUFFER_IMAGES_H */
