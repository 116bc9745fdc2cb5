/* The stochastic depth map of the accuracy study's screen-space AO, acquired one of two ways:
 * - rasterized (after Vardis et al. 2016): `layers` G-buffers rasterized every frame beside the
 *   engine's (study/gbuffer.h), each keeping a fragment with probability `keep`, so a pixel's
 *   k-th surface from the eye is in a layer with probability keep^k; copied one after the other
 *   into one buffer;
 * - ray traced (seed 003, Brüll and Grosch): one view ray a pixel through the hardware's
 *   acceleration structures, rebuilt every frame, a reservoir of `layers` of the surfaces it
 *   passes (roma_hwrt_record_depth_layers) written straight into that buffer.
 * The study's AO pass reads the buffer in the BOM's place (study/study_ao.h, roma_ssao.glsl).
 * Tools only. */
#ifndef ROMA_STUDY_STUDY_DEPTH_LAYERS_H
#define ROMA_STUDY_STUDY_DEPTH_LAYERS_H

#include "roma/camera.h"
#include "roma/scene.h"
#include "study/hw_ray_tracing.h"
#include "vulkan/vk_internal.h"

typedef struct roma_study_depth_layers roma_study_depth_layers;

/* layers in 1..ROMA_AO_SSAO_MAX_LAYERS; keep 0 = ROMA_AO_SSAO_KEEP (rasterized only). traced:
 * NULL rasterizes; otherwise the layers are ray traced through it (made from the same scene on
 * ctx, and kept alive and unused elsewhere while the layers are recorded). */
roma_result roma_study_depth_layers_create(roma_context *ctx, const roma_scene *scene, roma_hwrt *traced,
                                           uint32_t width, uint32_t height, uint32_t layers, float keep,
                                           roma_study_depth_layers **out);
/* Accepts NULL. */
void roma_study_depth_layers_destroy(roma_study_depth_layers *layers);

/* Rasterizes every layer from camera with fragments dropped by a hash of seed, frame and the
 * layer (new ones each frame), then copies them into the view's buffer; or, traced, rebuilds
 * the acceleration structures and traces the layers into it, the reservoir drawn by a hash of
 * seed and frame. Visible afterwards to compute shaders. */
roma_result roma_study_depth_layers_record(roma_study_depth_layers *layers, VkCommandBuffer cmd,
                                           const roma_camera *camera, uint32_t seed, uint32_t frame);

/* The layers as one RGBA32_UINT texel buffer (4 texels a roma_gbuffer_pixel, layer after layer). */
VkBufferView roma_study_depth_layers_view(const roma_study_depth_layers *layers);
uint32_t roma_study_depth_layers_count(const roma_study_depth_layers *layers);
/* Device memory of the layers (rasterized: and their copy; traced: the acceleration
 * structures are the roma_hwrt's). */
uint64_t roma_study_depth_layers_bytes(const roma_study_depth_layers *layers);

#endif /* ROMA_STUDY_STUDY_DEPTH_LAYERS_H */
