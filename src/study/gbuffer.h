/* G-buffer raster pass (internal for now).
 *
 * Rasterizes a triangle soup from buffer device addresses with the pinhole
 * camera of roma/camera.h and writes, per pixel, the nearest surface's world
 * position, distance along the camera ray, shading and geometric normals (both
 * facing the eye, as in the reference tracer), triangle id, albedo and motion
 * vector into a storage buffer of roma_gbuffer_pixel (roma_shared.h), row 0 at
 * the top. Two passes over the geometry: depth only, then shading with depth
 * test EQUAL and early fragment tests, so exactly one fragment writes a pixel.
 * Reversed Z with an infinite far plane: only the near plane is needed. */
#ifndef ROMA_STUDY_GBUFFER_H
#define ROMA_STUDY_GBUFFER_H

#include <vulkan/vulkan.h>

#include "roma/camera.h"
#include "roma/context.h"
#include "roma/scene.h"
#include "roma_shared.h"

typedef struct roma_gbuffer roma_gbuffer;

typedef struct roma_gbuffer_inputs {
    VkDeviceAddress positions;  /* float4 per vertex (w ignored) */
    VkDeviceAddress normals;    /* float4 per vertex (w ignored); zero length = use the face normal */
    VkDeviceAddress indices;    /* uint x3 per triangle */
    VkDeviceAddress albedo;     /* float4 per triangle (rgb used) */
    uint32_t triangle_count;
    roma_camera camera;
    roma_camera previous_camera; /* camera of the previous frame, for motion vectors */
    /* Near plane distance (> 0): geometry closer to the eye is clipped. Something
     * like 1e-4 of the scene's bounding-box diagonal; reversed Z keeps precision. */
    float near_plane;
    /* A stochastic layer only (roma_gbuffer_create_stochastic): each fragment is kept with
     * probability keep (0 or >= 1: all), drawn from a hash of its pixel, its triangle and seed,
     * so the layer holds the nearest kept surface of each pixel. */
    float keep;
    uint32_t seed;
} roma_gbuffer_inputs;

/* The near plane for a scene's views: 1e-4 of its bounds' diagonal. */
float roma_gbuffer_near_plane(const roma_scene *scene);

/* The camera as the shaders project with it (roma_shared.h); 0 for a degenerate camera. */
int roma_gbuffer_camera_make(const roma_camera *cam, uint32_t width, uint32_t height, float near_plane,
                             roma_gbuffer_camera *out);

/* width, height in 1..16384. */
roma_result roma_gbuffer_create(roma_context *ctx, uint32_t width, uint32_t height, roma_gbuffer **out);
/* A layer of a stochastic depth map (the accuracy study's screen-space baseline with more
 * than one layer, after Vardis et al. 2016): the depth pass drops fragments at random
 * (roma_gbuffer_inputs.keep, .seed), so each pixel holds a random one of the surfaces behind
 * it, the nearer ones more often. */
roma_result roma_gbuffer_create_stochastic(roma_context *ctx, uint32_t width, uint32_t height, roma_gbuffer **out);
/* A G-buffer of the same kind as source (stochastic or not) that uses source's pipelines
 * instead of creating its own (the viewport is dynamic: any size). Destroy it before
 * source. */
roma_result roma_gbuffer_create_sharing(const roma_gbuffer *source, uint32_t width, uint32_t height,
                                        roma_gbuffer **out);
/* Accepts NULL. */
void roma_gbuffer_destroy(roma_gbuffer *g);

/* Records both passes into cmd (outside any rendering). Makes transfer and
 * compute writes of the inputs visible first; afterwards the pixel buffer is
 * visible to compute, fragment and transfer reads. Reuses one small parameter
 * buffer (vkCmdUpdateBuffer): do not have two recordings of the same g in flight. */
roma_result roma_gbuffer_record(roma_gbuffer *g, VkCommandBuffer cmd, const roma_gbuffer_inputs *in);

/* The pixel buffer (width * height roma_gbuffer_pixel, row-major from the top). */
VkBuffer roma_gbuffer_pixels_buffer(const roma_gbuffer *g);
VkDeviceAddress roma_gbuffer_pixels_address(const roma_gbuffer *g);

/* Blocking: copies the last recorded result into out (width * height entries).
 * The recording must have been submitted and completed. */
roma_result roma_gbuffer_download(roma_gbuffer *g, roma_gbuffer_pixel *out);

#endif /* ROMA_STUDY_GBUFFER_H */
