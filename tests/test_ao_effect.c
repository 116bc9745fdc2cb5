/* The public effects on an engine's G-buffer images: the built-in room lit by its spot
 * light, seen from its camera, the G-buffer made on the host from Embree's primary hits
 * and uploaded into RGBA32F images the test owns. roma_ao_effect writes an R32F image,
 * roma_light_effect and roma_gi_effect RGBA32F irradiance images. Compared pixel by pixel with the
 * reference tracer at the same points (AO with the same samples; direct light from the
 * same lights, and with the area light the same samples; GI with the same bounce
 * directions and area-light samples; many lights, sampled per frame, against the image
 * with every light). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gpu_images.h"
#include "harness.h"
#include "reference.h"
#include "roma/builtin_scenes.h"
#include "roma/ao_effect.h"
#include "roma/camera.h"
#include "roma/gi_effect.h"
#include "roma/light_effect.h"
#include "roma/map.h"

#define W 64
#define H 48
#define SPP 64
#define SEED 11
#define RADIUS 0.5f /* the room is closed: unbounded rays would all be occluded */
#define AREA_SPP 16
#define AREA_MAX_ERROR 0.036 /* measured 3.26% (means 0.0944 against 0.0944) */
#define GI_SPP 1024
/* GI: per pixel the bounce hits of snapped rays are not the reference's, so the samples
 * leave noise, heavy-tailed where bounce rays reach the ceiling the lamp lights from 2 cm
 * (docs/accuracy.md): measured mean |difference| 40.6%, bias +2.6%, as an H100 measures it
 * (which gives +3.1% and -0.6% at seeds 12 and 13). 1,024 samples in one record: before the
 * passes split their loops within lavapipe's loop budget (src/vulkan/loop_budget.h), 256
 * samples measured +3.0% here and +6.2% on the H100, and 512 or more came out 40-70% dark:
 * lavapipe's figure was cut short (with the split, 256 samples measure +6.2% here too;
 * docs/accuracy.md, docs/accuracy/gi_loop_budget.sh). */
#define GI_MAX_ERROR 0.41
#define GI_MAX_BIAS 0.035
/* The same with the spot alone (cornell_spot, its light concentrated in one patch: more
 * noise), in place and moved (gi_frame), GI_SPP samples: measured 63.3% and 52.5%, bias
 * +6.5% and -10.2% (256 samples: 63.8% and 53.7%, +6.9% and -10.1%; 64: 67.3% and 57.1%, +7.0%
 * and -9.6%; a grid left in place: 98.7%, -98.6%). */
#define GI_SPOT_MAX_ERROR 0.64
#define GI_SPOT_MAX_BIAS 0.11
#define MIN_SURFACES_LIGHTER 70u /* pixels the surface grid's start makes lighter: measured 81 of 3,072 */
#define MAX_RAYS_ERROR 0.001      /* ROMA_AO_TRACE_SURFACES against Embree, same samples: measured 0.0007 */
#define MAX_RAYS_MEAN_DIFFERENCE 0.0009 /* measured 0.0006 (the walk: 0.057) */

/* Starts a frame in cmd (pool reset) with `out` ready for the compute stage to write. */
static void begin_output_frame(roma_context *ctx, VkImage out, VkCommandBuffer cmd, VkCommandPool pool)
{
    vkResetCommandPool(roma_context_device(ctx), pool, 0);
    VkCommandBufferBeginInfo begin = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vkBeginCommandBuffer(cmd, &begin);
    roma_test_layout_barrier(cmd, out, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                             VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT,
                             VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

/* Ends the frame: copies the RGBA32F `out` into the staging's irradiance plane, submits, waits. */
static void read_back_irradiance(roma_context *ctx, VkImage out, VkCommandBuffer cmd, VkBuffer staging)
{
    roma_test_layout_barrier(cmd, out, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                             VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                             VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy back = {.bufferOffset = 3 * (VkDeviceSize)W * H * 16 + (VkDeviceSize)W * H * 4,
                              .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                              .imageExtent = {W, H, 1}};
    vkCmdCopyImageToBuffer(cmd, out, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging, 1, &back);
    roma_test_submit_and_wait(ctx, cmd);
}

/* Ends the frame: copies the R32F AO image `out` to the staging at back, submits, waits, and
 * counts the values (host, the staging's mapping) that differ from want. */
static uint32_t ao_values_differing(roma_context *ctx, VkImage out, VkCommandBuffer cmd, VkBuffer staging,
                                    const VkBufferImageCopy *back, const float *host, const float *want)
{
    roma_test_layout_barrier(cmd, out, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                             VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                             VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    vkCmdCopyImageToBuffer(cmd, out, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging, 1, back);
    roma_test_submit_and_wait(ctx, cmd);
    uint32_t differ = 0;
    for (uint32_t p = 0; p < W * H; ++p)
        differ += host[p] != want[p];
    return differ;
}

/* Records one frame of the light effect into its output and reads it back into irradiance. */
static void light_frame(roma_context *ctx, roma_light_effect *light, const roma_map *map,
                        const roma_light_images *images, VkImage out, VkCommandBuffer cmd, VkCommandPool pool,
                        VkBuffer staging, const roma_light *lights, uint32_t light_count,
                        const roma_light_settings *settings)
{
    begin_output_frame(ctx, out, cmd, pool);
    CHECK_RESULT(roma_light_effect_record(light, cmd, settings->frame % 2u, map, images, lights, light_count, settings),
                 ROMA_SUCCESS);
    read_back_irradiance(ctx, out, cmd, staging);
}

/* A reference estimator of the light leaving a point (roma_ref_direct_point, roma_ref_indirect_point). */
typedef void (*ref_light_fn)(const roma_ref *, const float *, const float *, const float *, const float *, uint32_t,
                             uint32_t, uint32_t, float *);

/* An effect's irradiance (times albedo / pi) at the covered pixels against the reference's
 * `light` at the same points with spp samples: the mean |difference| relative to the
 * reference's mean; its relative bias and both means (over n pixels) in out[0..2]. */
static double light_error(const roma_ref *ref, ref_light_fn light, uint32_t spp, const roma_scene_view *v,
                          const roma_ref_hit *hits, const int *covered, uint32_t n, const float *irradiance,
                          double out[3])
{
    double err = 0.0, ref_sum = 0.0, got_sum = 0.0;
    for (uint32_t p = 0; p < W * H; ++p) {
        if (!covered[p])
            continue;
        const float *albedo = v->materials[v->triangle_materials[hits[p].triangle]].base_color;
        float want[3];
        light(ref, hits[p].position, hits[p].geometric_normal, hits[p].shading_normal, albedo, spp, SEED, p, want);
        for (int c = 0; c < 3; ++c) {
            float got = irradiance[4 * p + (uint32_t)c] * albedo[c] / 3.14159265f;
            err += fabs((double)got - want[c]);
            ref_sum += want[c];
            got_sum += got;
        }
    }
    out[0] = ref_sum > 0.0 ? (got_sum - ref_sum) / ref_sum : 0.0;
    out[1] = got_sum / (3.0 * n);
    out[2] = ref_sum / (3.0 * n);
    return ref_sum > 0.0 ? err / ref_sum : 1.0;
}

/* Values of the RGBA image rgba whose RGB differ from rgb's. */
static uint32_t rgb_values_differing(const float *rgba, const float *rgb)
{
    uint32_t differ = 0;
    for (uint32_t i = 0; i < 3 * W * H; ++i)
        differ += rgba[i / 3u * 4u + i % 3u] != rgb[i];
    return differ;
}

/* Many lights (roma_light_settings.lights_per_frame): the room's spot and MANY_LIGHTS point
 * lights on a grid through the room. Every light traced every frame, against the reference
 * with the same lights; then the spot every frame and MANY_PER_FRAME of the others per pixel
 * and frame, averaged over MANY_FRAMES frames, against the all-lights image. */
#define MANY_LIGHTS 64u
#define MANY_PER_FRAME 8u
#define MANY_FRAMES 32u
static void many_lights(roma_context *ctx, const roma_scene_view *sv, const roma_map *map, roma_light_effect *light,
                        const roma_light_images *images, VkImage out, VkCommandBuffer cmd, VkCommandPool pool,
                        VkBuffer staging, const float *irradiance, const roma_ref_hit *hits, const int *covered,
                        uint32_t covered_count)
{
    roma_light lights[1 + MANY_LIGHTS];
    lights[0] = sv->lights[0];
    for (uint32_t i = 0; i < MANY_LIGHTS; ++i) {
        roma_light *l = &lights[1 + i];
        memset(l, 0, sizeof *l);
        l->type = ROMA_LIGHT_POINT;
        uint32_t g[3] = {i % 4u, i / 4u % 4u, i / 16u};
        for (int a = 0; a < 3; ++a) {
            float lo = sv->bounds_min[a], hi = sv->bounds_max[a];
            l->position[a] = lo + (hi - lo) * (0.15f + 0.7f * ((float)g[a] + 0.5f) / 4.0f);
            l->color[a] = 0.3f + 0.7f * (float)((i * 7u + (uint32_t)a * 3u) % 5u) / 4.0f;
        }
        l->intensity = 4.0f * sv->lights[0].intensity / MANY_LIGHTS;
    }
    roma_scene_desc d = {.positions = sv->positions, .normals = sv->normals, .vertex_count = sv->vertex_count,
                         .indices = sv->indices, .triangle_count = sv->triangle_count,
                         .triangle_materials = sv->triangle_materials, .materials = sv->materials,
                         .material_count = sv->material_count, .lights = lights, .light_count = 1 + MANY_LIGHTS,
                         .name = "cornell_spot with 64 point lights"};
    roma_scene *crowd = NULL;
    roma_ref *crowd_ref = NULL;
    CHECK_RESULT(roma_scene_create(&d, &crowd), ROMA_SUCCESS);
    CHECK_RESULT(roma_ref_create(crowd, NULL, &crowd_ref), ROMA_SUCCESS);
    static float exact[3 * W * H], mean[3 * W * H], first[3 * W * H];
    /* Every light, every frame. */
    roma_light_settings all = {.seed = SEED, .frame = 100};
    light_frame(ctx, light, map, images, out, cmd, pool, staging, lights, 1 + MANY_LIGHTS, &all);
    for (uint32_t p = 0; p < W * H; ++p)
        for (int c = 0; c < 3; ++c)
            exact[3 * p + (uint32_t)c] = irradiance[4 * p + (uint32_t)c];
    double err = 0.0, total = 0.0;
    for (uint32_t p = 0; crowd_ref && p < W * H; ++p) {
        if (!covered[p])
            continue;
        const float *albedo = sv->materials[sv->triangle_materials[hits[p].triangle]].base_color;
        float want[3];
        roma_ref_direct_point(crowd_ref, hits[p].position, hits[p].geometric_normal, hits[p].shading_normal, albedo, 1,
                              SEED, p, want);
        for (int c = 0; c < 3; ++c) {
            err += fabs((double)exact[3 * p + (uint32_t)c] * albedo[c] / 3.14159265 - want[c]);
            total += want[c];
        }
    }
    printf("many lights: the spot and %u point lights, every light traced: mean |difference| %.2f%% of the "
           "reference's mean radiance\n", MANY_LIGHTS, 100.0 * err / total);
    /* Measured: 6.24% (3,072 pixels; shadow edges a trace cell off, as with the spot alone). */
    CHECK(total > 0.0 && err / total <= 0.068);
    /* The spot every frame, MANY_PER_FRAME of the others sampled. */
    memset(mean, 0, sizeof mean);
    for (uint32_t f = 0; f < MANY_FRAMES; ++f) {
        roma_light_settings some = {.seed = SEED, .frame = 200 + f, .lights_per_frame = MANY_PER_FRAME,
                                    .exact_light_count = 1};
        light_frame(ctx, light, map, images, out, cmd, pool, staging, lights, 1 + MANY_LIGHTS, &some);
        for (uint32_t i = 0; i < 3 * W * H; ++i) {
            float v = irradiance[i / 3u * 4u + i % 3u];
            mean[i] += v / MANY_FRAMES;
            if (f == 0)
                first[i] = v;
        }
    }
    double one_err = 0.0, mean_err = 0.0, mean_sum = 0.0, exact_sum = 0.0;
    for (uint32_t p = 0; p < W * H; ++p)
        for (uint32_t c = 0; covered[p] && c < 3; ++c) {
            one_err += fabs((double)first[3 * p + c] - exact[3 * p + c]);
            mean_err += fabs((double)mean[3 * p + c] - exact[3 * p + c]);
            mean_sum += mean[3 * p + c];
            exact_sum += exact[3 * p + c];
        }
    printf("many lights: %u of %u sampled per pixel and frame: one frame %.2f%% from the all-lights image, the mean "
           "of %u frames %.2f%% (bias %+.2f%%) over %u pixels\n", MANY_PER_FRAME, MANY_LIGHTS,
           100.0 * one_err / exact_sum, MANY_FRAMES, 100.0 * mean_err / exact_sum,
           100.0 * (mean_sum - exact_sum) / exact_sum, covered_count);
    /* Measured: one frame 86.9% (it samples: with every light traced it would be 0), the
     * mean of 32 frames 12.1% (1 / sqrt(32) of one frame would be 15.4%), bias +0.53%. */
    CHECK(exact_sum > 0.0);
    CHECK(one_err / exact_sum >= 0.8 && one_err / exact_sum <= 0.95);
    CHECK(mean_err / exact_sum <= 0.13);
    CHECK(fabs(mean_sum - exact_sum) / exact_sum <= 0.007);
    /* A light without intensity is dropped and the rest move up: exact_light_count counts
     * the kept ones among the first ones it names. A dark light in front of the spot with
     * exact_light_count 2 gives the first sampled frame above bit for bit; an
     * exact_light_count beyond the list traces every light, as the all-lights frame. */
    roma_light dark_first[2 + MANY_LIGHTS];
    dark_first[0] = lights[0];
    dark_first[0].intensity = 0.0f;
    memcpy(dark_first + 1, lights, sizeof lights);
    roma_light_settings shifted = {.seed = SEED, .frame = 200, .lights_per_frame = MANY_PER_FRAME,
                                   .exact_light_count = 2};
    light_frame(ctx, light, map, images, out, cmd, pool, staging, dark_first, 2 + MANY_LIGHTS, &shifted);
    uint32_t differ = rgb_values_differing(irradiance, first);
    roma_light_settings beyond = {.seed = SEED, .frame = 100, .lights_per_frame = MANY_PER_FRAME,
                                  .exact_light_count = 1000};
    light_frame(ctx, light, map, images, out, cmd, pool, staging, lights, 1 + MANY_LIGHTS, &beyond);
    uint32_t differ_all = rgb_values_differing(irradiance, exact);
    printf("many lights: a dropped light before the exact ones: %u values differ; exact_light_count beyond the "
           "list: %u differ from every light traced\n", differ, differ_all);
    CHECK(differ == 0 && differ_all == 0);
    /* The count of visible lights (ROMA_LIGHT_OUTPUT_VISIBLE_COUNT), every light traced,
     * against Embree's count of the same positions (the rule of roma_ref_count_visible_lights:
     * facing the shading normal, a free segment). */
    roma_light_settings count = {.seed = SEED, .frame = 300, .output = ROMA_LIGHT_OUTPUT_VISIBLE_COUNT};
    light_frame(ctx, light, map, images, out, cmd, pool, staging, lights, 1 + MANY_LIGHTS, &count);
    float positions[3 * (1 + MANY_LIGHTS)];
    for (uint32_t i = 0; i < 1 + MANY_LIGHTS; ++i)
        memcpy(&positions[3 * i], lights[i].position, sizeof(float) * 3);
    double count_err = 0.0, count_sum = 0.0;
    uint32_t fractional = 0;
    for (uint32_t p = 0; crowd_ref && p < W * H; ++p) {
        if (!covered[p])
            continue;
        uint32_t want = roma_ref_count_visible_lights(crowd_ref, hits[p].position, hits[p].geometric_normal,
                                                      hits[p].shading_normal, positions, 1 + MANY_LIGHTS);
        count_err += fabs((double)irradiance[4 * p] - want);
        count_sum += want;
        fractional += irradiance[4 * p] != floorf(irradiance[4 * p]) || irradiance[4 * p + 1] != 0.0f;
    }
    printf("many lights: the count of visible lights against Embree's: mean |difference| %.2f%% of its mean %.2f\n",
           100.0 * count_err / count_sum, count_sum / covered_count);
    /* Measured: 4.71% of a mean of 49.2 lights (shadow edges a trace cell off, as above; 4.56%
     * before the end walk at the light, roma_light_end_blocked). */
    CHECK(count_sum > 0.0 && count_err / count_sum <= 0.05);
    CHECK(fractional == 0); /* whole counts in x, nothing in y */
    roma_ref_destroy(crowd_ref);
    roma_scene_destroy(crowd);
}

/* The GI effect follows the map's geometry (roma/gi_effect.h): one effect, given the room
 * once, records two frames; the second's map build moves every vertex by MOVE (host
 * positions), and the G-buffer and the spot move with it. Bounce hits must find their
 * surfaces where the map now has them: against the reference at the unmoved points (the
 * same light transport), the second frame's error and bias stay those of the first. A grid
 * left where the first frame built it finds no surface for most hits. Returns the mean
 * |difference| of the frame, relative to the reference, its bias in *bias. */
static const float MOVE[3] = {0.37f, -0.21f, 0.53f};
static double gi_frame(roma_context *ctx, roma_gi_effect *gi, roma_map *map, const roma_scene_view *sv, int moved,
                       const roma_light_images *images, VkImage out, VkImage position, VkCommandBuffer cmd,
                       VkCommandPool pool, VkBuffer staging, float *host, const float *irradiance, const roma_ref *ref,
                       const roma_ref_hit *hits, const int *covered, double *bias)
{
    float *pos = host; /* the staging's first plane: the G-buffer positions */
    for (uint32_t p = 0; p < W * H; ++p)
        for (int a = 0; a < 3; ++a)
            pos[4 * p + a] = covered[p] ? hits[p].position[a] + (moved ? MOVE[a] : 0.0f) : 0.0f;
    float *positions = malloc(sizeof(float) * 3 * sv->vertex_count);
    for (uint32_t i = 0; positions && i < 3 * sv->vertex_count; ++i)
        positions[i] = sv->positions[i] + (moved ? MOVE[i % 3] : 0.0f);
    roma_light spot = sv->lights[0];
    for (int a = 0; moved && a < 3; ++a)
        spot.position[a] += MOVE[a];
    begin_output_frame(ctx, out, cmd, pool);
    roma_test_layout_barrier(cmd, position, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                             VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT,
                             VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkBufferImageCopy up = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, .imageExtent = {W, H, 1}};
    vkCmdCopyBufferToImage(cmd, staging, position, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &up);
    roma_test_layout_barrier(cmd, position, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                             VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                             VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    roma_map_frame_desc bf = {.frame = 3u + (uint32_t)moved, .seed = 5, .jitter_grid = 1, .jitter_directions = 1,
                              .slot = (uint32_t)moved, .positions = positions, .vertex_count = sv->vertex_count};
    CHECK_RESULT(roma_map_record_build(map, cmd, &bf, NULL), ROMA_SUCCESS);
    roma_gi_settings gs = {.samples = GI_SPP, .seed = SEED};
    CHECK_RESULT(roma_gi_effect_record(gi, cmd, (uint32_t)moved, map, images, &spot, 1, &gs), ROMA_SUCCESS);
    read_back_irradiance(ctx, out, cmd, staging);
    free(positions);
    double stats[3];
    double err = light_error(ref, roma_ref_indirect_point, GI_SPP, sv, hits, covered, 1, irradiance, stats);
    *bias = stats[0];
    return err;
}

int main(void)
{
    roma_context *ctx = roma_test_context_flags(roma_test_sync_validation_flags());
    if (!ctx)
        return roma_test_finish("test_ao_effect");
    VkDevice dev = roma_context_device(ctx);
    roma_scene *scene = NULL;
    CHECK_RESULT(roma_scene_create_builtin("cornell_spot", NULL, &scene), ROMA_SUCCESS);
    roma_ref *ref = NULL;
    CHECK_RESULT(roma_ref_create(scene, NULL, &ref), ROMA_SUCCESS);
    roma_map *map = NULL;
    CHECK_RESULT(roma_map_create(ctx, &(roma_map_desc){.resolution = 128, .angular = 4}, scene, &map), ROMA_SUCCESS);
    roma_ao_effect *ao = NULL;
    /* The list of covered pixels, on every device (a GPU's default is every pixel, below). */
    CHECK_RESULT(roma_ao_effect_create(ctx, &(roma_ao_effect_desc){.pixel_dispatch = ROMA_PIXEL_DISPATCH_LIST}, &ao),
                 ROMA_SUCCESS);
    roma_light_effect *light = NULL;
    CHECK_RESULT(roma_light_effect_create(ctx, NULL, &light), ROMA_SUCCESS);
    if (!ref || !map || !ao || !light)
        return roma_test_finish("test_ao_effect");

    /* The engine's G-buffer: Embree's primary hits. */
    roma_scene_view sv;
    roma_scene_get_view(scene, &sv);
    roma_camera_frame cam;
    roma_camera_make_frame(&sv.camera, W, H, &cam);
    VkDeviceSize plane = (VkDeviceSize)W * H * 16;
    roma_test_staging staging_buffer;
    roma_test_staging_create(ctx, 4 * plane + (VkDeviceSize)W * H * 4, &staging_buffer);
    VkBuffer staging = staging_buffer.buffer;
    float *host = staging_buffer.mapped;
    float *pos = host, *nrm = host + 4 * W * H, *gnrm = host + 8 * W * H, *out = host + 12 * W * H,
          *irradiance = host + 13 * W * H;
    static roma_ref_hit hits[W * H];
    static int covered[W * H];
    for (uint32_t y = 0; y < H; ++y)
        for (uint32_t x = 0; x < W; ++x) {
            uint32_t p = y * W + x;
            float o[3], d[3];
            roma_camera_ray(&cam, (float)x + 0.5f, (float)y + 0.5f, o, d);
            covered[p] = roma_ref_intersect(ref, o, d, 0.0f, INFINITY, &hits[p]);
            for (int a = 0; a < 3; ++a) {
                pos[4 * p + a] = covered[p] ? hits[p].position[a] : 0.0f;
                nrm[4 * p + a] = covered[p] ? hits[p].shading_normal[a] : 0.0f;
                gnrm[4 * p + a] = covered[p] ? hits[p].geometric_normal[a] : 0.0f;
            }
            pos[4 * p + 3] = covered[p] ? 1.0f : 0.0f;
            nrm[4 * p + 3] = gnrm[4 * p + 3] = 0.0f;
        }

    roma_test_image in[3], output, light_out;
    for (int i = 0; i < 3; ++i)
        roma_test_image_create(ctx, W, H, VK_FORMAT_R32G32B32A32_SFLOAT,
                               VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, &in[i]);
    roma_test_image_create(ctx, W, H, VK_FORMAT_R32_SFLOAT,
                           VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, &output);
    roma_test_image_create(ctx, W, H, VK_FORMAT_R32G32B32A32_SFLOAT,
                           VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, &light_out);

    /* One command buffer: upload, build, AO, read back. */
    VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                  .queueFamilyIndex = roma_context_queue_family(ctx)};
    VkCommandPool pool;
    CHECK(vkCreateCommandPool(dev, &pi, NULL, &pool) == VK_SUCCESS);
    VkCommandBufferAllocateInfo cai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = pool,
                                       .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1};
    VkCommandBuffer cmd;
    CHECK(vkAllocateCommandBuffers(dev, &cai, &cmd) == VK_SUCCESS);
    VkCommandBufferBeginInfo begin = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vkBeginCommandBuffer(cmd, &begin);
    for (int i = 0; i < 3; ++i) {
        roma_test_layout_barrier(cmd, in[i].image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                 VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COPY_BIT,
                                 VK_ACCESS_2_TRANSFER_WRITE_BIT);
        VkBufferImageCopy copy = {.bufferOffset = (VkDeviceSize)i * plane,
                                  .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                  .imageExtent = {W, H, 1}};
        vkCmdCopyBufferToImage(cmd, staging, in[i].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
        roma_test_layout_barrier(cmd, in[i].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                                 VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                 VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    }
    roma_test_layout_barrier(cmd, output.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                             VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                             VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    roma_test_layout_barrier(cmd, light_out.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                             VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                             VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    roma_map_frame_desc fd = {.frame = 0, .seed = 5, .jitter_grid = 1, .jitter_directions = 1};
    CHECK_RESULT(roma_map_record_build(map, cmd, &fd, NULL), ROMA_SUCCESS);
    roma_ao_images images = {.width = W, .height = H, .position = in[0].view, .normal = in[1].view,
                             .geometric_normal = in[2].view, .output = output.view};
    roma_ao_settings settings = {.samples = SPP, .radius = RADIUS, .seed = SEED};
    CHECK_RESULT(roma_ao_effect_record(ao, cmd, 0, map, &images, &settings), ROMA_SUCCESS);
    roma_light_images limages = {.width = W, .height = H, .position = in[0].view, .normal = in[1].view,
                                 .geometric_normal = in[2].view, .output = light_out.view};
    CHECK_RESULT(roma_light_effect_record(light, cmd, 0, map, &limages, sv.lights, sv.light_count, NULL), ROMA_SUCCESS);
    CHECK_RESULT(roma_light_effect_record(light, cmd, 0, map, &limages, sv.lights, sv.light_count, NULL),
                 ROMA_ERROR_INVALID_ARGUMENT); /* one record per slot and frame */
    roma_test_layout_barrier(cmd, light_out.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                             VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                             VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy lback = {.bufferOffset = 3 * plane + (VkDeviceSize)W * H * 4,
                               .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                               .imageExtent = {W, H, 1}};
    vkCmdCopyImageToBuffer(cmd, light_out.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging, 1, &lback);
    roma_test_layout_barrier(cmd, output.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                             VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                             VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy back = {
        .bufferOffset = 3 * plane, .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, .imageExtent = {W, H, 1}};
    vkCmdCopyImageToBuffer(cmd, output.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging, 1, &back);
    roma_test_submit_and_wait(ctx, cmd);

    /* Against the reference at the same points with the same samples. */
    roma_map_info mi;
    roma_map_get_info(map, &mi);
    double err = 0.0, mean_roma = 0.0, mean_ref = 0.0;
    uint32_t n = 0, background_ok = 1;
    for (uint32_t p = 0; p < W * H; ++p) {
        if (!covered[p]) {
            background_ok &= out[p] == 1.0f;
            continue;
        }
        float r = roma_ref_ao_point(ref, hits[p].position, hits[p].geometric_normal, hits[p].shading_normal, RADIUS,
                                    SPP, SEED, p);
        err += fabs((double)out[p] - r);
        mean_roma += out[p], mean_ref += r;
        ++n;
    }
    printf("%u covered pixels, %u spp: mean AO ROMA %.4f, Embree %.4f, mean |difference| %.4f\n", n, SPP,
           mean_roma / n, mean_ref / n, err / n);
    CHECK(n > W * H / 2 && background_ok);
    /* Measured: mean |difference| 0.0744, means 0.7181 vs 0.7750 (with the blind skip of
     * the rays' start, before the exact walk of roma/ray_start.glsl: 0.0707, 0.7367; the
     * walk seals the room's corners and darkens a band one cell wide along them). */
    CHECK(err / n <= 0.080);
    CHECK(fabs(mean_roma - mean_ref) / n <= 0.062);

    /* ROMA_AO_START_SURFACES on the same map and samples: its start check opens only rays the
     * walk blocked (the rest of each ray is the same query), so no pixel is darker than the
     * walk's (up to a ray a GPU's two modules may round apart) and the room's edges are lighter;
     * a second record in the slot's frame is refused (one grid record per slot). */
    static float walk_ao[W * H];
    memcpy(walk_ao, out, sizeof walk_ao);
    roma_ao_effect *surf = NULL;
    CHECK_RESULT(roma_ao_effect_create(ctx, NULL, &surf), ROMA_SUCCESS);
    if (surf) {
        roma_ao_settings with_surfaces = settings;
        with_surfaces.start = ROMA_AO_START_SURFACES;
        begin_output_frame(ctx, output.image, cmd, pool);
        CHECK_RESULT(roma_ao_effect_record(surf, cmd, 0, map, &images, &with_surfaces), ROMA_SUCCESS);
        CHECK_RESULT(roma_ao_effect_record(surf, cmd, 0, map, &images, &with_surfaces), ROMA_ERROR_INVALID_ARGUMENT);
        ao_values_differing(ctx, output.image, cmd, staging, &back, out, walk_ao);
        uint32_t darker = 0, lighter = 0;
        for (uint32_t p = 0; p < W * H; ++p) {
            darker += covered[p] && out[p] < walk_ao[p] - 1.5f / SPP;
            lighter += covered[p] && out[p] > walk_ao[p];
        }
        printf("surface grid start: %u pixels lighter than the walk's, %u darker by more than a ray\n", lighter,
               darker);
        CHECK(darker == 0);
        CHECK(lighter >= MIN_SURFACES_LIGHTER);
        /* ROMA_AO_TRACE_SURFACES: refused in the slot's frame the start's record took (the grid's
         * record is the slot's), traced in slot 1 with the same samples: against the reference. */
        roma_ao_settings with_rays = settings;
        with_rays.trace = ROMA_AO_TRACE_SURFACES;
        begin_output_frame(ctx, output.image, cmd, pool);
        CHECK_RESULT(roma_ao_effect_record(surf, cmd, 0, map, &images, &with_rays), ROMA_ERROR_INVALID_ARGUMENT);
        CHECK_RESULT(roma_ao_effect_record(surf, cmd, 1, map, &images, &with_rays), ROMA_SUCCESS);
        ao_values_differing(ctx, output.image, cmd, staging, &back, out, walk_ao);
        double rays_err = 0.0, rays_mean = 0.0, rays_ref = 0.0;
        for (uint32_t p = 0; p < W * H; ++p) {
            if (!covered[p])
                continue;
            float r = roma_ref_ao_point(ref, hits[p].position, hits[p].geometric_normal, hits[p].shading_normal,
                                        RADIUS, SPP, SEED, p);
            rays_err += fabs((double)out[p] - r);
            rays_mean += out[p], rays_ref += r;
        }
        printf("rays through the surface grid: mean AO %.4f against Embree's %.4f, mean |difference| %.4f\n",
               rays_mean / n, rays_ref / n, rays_err / n);
        CHECK(rays_err / n <= MAX_RAYS_ERROR);
        CHECK(fabs(rays_mean - rays_ref) / n <= MAX_RAYS_MEAN_DIFFERENCE);
        roma_ao_effect_destroy(surf);
        memcpy(out, walk_ao, sizeof walk_ao); /* the walk's output, which the records below compare with */
    }

    /* Two records in one frame of slot 1, the first over a quarter of the images: the second
     * outgrows the slot's covered-pixel list (the first's waits for the slot's next frame) and
     * writes what the single record wrote, bit for bit. */
    static float single_record[W * H];
    memcpy(single_record, out, sizeof single_record);
    begin_output_frame(ctx, output.image, cmd, pool);
    roma_ao_images quarter = images;
    quarter.width = W / 2, quarter.height = H / 2;
    CHECK_RESULT(roma_ao_effect_record(ao, cmd, 1, map, &quarter, &settings), ROMA_SUCCESS);
    /* Two records that write one image are ordered by the engine, as any two passes are (on
     * a GPU the second overtook the first without this barrier). */
    roma_test_layout_barrier(cmd, output.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL,
                             VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                             VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    CHECK_RESULT(roma_ao_effect_record(ao, cmd, 1, map, &images, &settings), ROMA_SUCCESS);
    CHECK(ao_values_differing(ctx, output.image, cmd, staging, &back, out, single_record) == 0);
    /* Images wider than 65,536 pixels (the list packs x and y in 16 bits each) are refused before
     * anything is recorded. */
    roma_ao_images huge = images;
    huge.width = 65536u + 1u;
    CHECK_RESULT(roma_ao_effect_record(ao, cmd, 0, map, &huge, &settings), ROMA_ERROR_INVALID_ARGUMENT);
    /* A dispatch over every pixel (a GPU's default) writes the same bits as the list. */
    roma_ao_effect *every = NULL;
    CHECK_RESULT(roma_ao_effect_create(ctx, &(roma_ao_effect_desc){.pixel_dispatch = 7}, &every),
                 ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(every == NULL);
    CHECK_RESULT(roma_ao_effect_create(ctx, &(roma_ao_effect_desc){.pixel_dispatch = ROMA_PIXEL_DISPATCH_EVERY_PIXEL},
                                       &every),
                 ROMA_SUCCESS);
    begin_output_frame(ctx, output.image, cmd, pool);
    CHECK_RESULT(roma_ao_effect_record(every, cmd, 0, map, &images, &settings), ROMA_SUCCESS);
    CHECK(ao_values_differing(ctx, output.image, cmd, staging, &back, out, single_record) == 0);
    roma_ao_effect_destroy(every);

    /* Direct light: ROMA's shadowed irradiance times albedo / pi against the reference's
     * reflected radiance (one spot light: no area-light samples, so no noise). */
    double light_err = 0.0, light_ref = 0.0;
    uint32_t lit_differ = 0;
    for (uint32_t p = 0; p < W * H; ++p) {
        if (!covered[p])
            continue;
        const float *albedo = sv.materials[sv.triangle_materials[hits[p].triangle]].base_color;
        float want[3];
        roma_ref_direct_point(ref, hits[p].position, hits[p].geometric_normal, hits[p].shading_normal, albedo, 1,
                              SEED, p, want);
        float got_lum = 0.0f, want_lum = 0.0f;
        for (int c = 0; c < 3; ++c) {
            float got = irradiance[4 * p + (uint32_t)c] * albedo[c] / 3.14159265f;
            light_err += fabs((double)got - want[c]);
            light_ref += want[c];
            got_lum += got, want_lum += want[c];
        }
        lit_differ += (got_lum > 0.0f) != (want_lum > 0.0f);
    }
    printf("direct light from %u light(s): mean |difference| %.2f%% of the mean radiance; %u of %u pixels lit on one "
           "side only\n", sv.light_count, 100.0 * light_err / light_ref, lit_differ, n);
    CHECK(sv.light_count == 1 && light_ref > 0.0);
    /* Measured: 3.64% and 45 of 3,072 pixels (shadow edges a trace cell off; 2.50% and 35
     * with the blind skip of the rays' start). */
    CHECK(light_err / light_ref <= 0.042);
    CHECK(lit_differ <= 50);

    /* Area lights: the built-in "cornell" is the same room with its ceiling quad emitting
     * (same triangles, so the same map and G-buffer serve). The spot and AREA_SPP samples
     * of the ceiling per pixel, against the reference with the same samples. */
    roma_scene *lit = NULL;
    roma_ref *lit_ref = NULL;
    CHECK_RESULT(roma_scene_create_builtin("cornell", NULL, &lit), ROMA_SUCCESS);
    CHECK_RESULT(roma_ref_create(lit, NULL, &lit_ref), ROMA_SUCCESS);
    CHECK_RESULT(roma_light_effect_set_area_lights(light, lit), ROMA_SUCCESS);
    roma_scene_view lv;
    roma_scene_get_view(lit, &lv);
    CHECK(lv.emissive_triangle_count > 0 && lv.triangle_count == sv.triangle_count);
    if (lit_ref) {
        begin_output_frame(ctx, light_out.image, cmd, pool);
        roma_map_frame_desc af = {.frame = 1, .seed = 5, .jitter_grid = 1, .jitter_directions = 1};
        CHECK_RESULT(roma_map_record_build(map, cmd, &af, NULL), ROMA_SUCCESS);
        /* Slot 1: a new frame of the effect with frame 0, the reference's samples 0 .. AREA_SPP - 1. */
        roma_light_settings ls = {.area_samples = AREA_SPP, .seed = SEED};
        CHECK_RESULT(roma_light_effect_record(light, cmd, 1, map, &limages, lv.lights, lv.light_count, &ls),
                     ROMA_SUCCESS);
        read_back_irradiance(ctx, light_out.image, cmd, staging);
        double area[3]; /* bias, ROMA's mean, the reference's mean */
        double area_err = light_error(lit_ref, roma_ref_direct_point, AREA_SPP, &lv, hits, covered, n, irradiance,
                                      area);
        printf("direct light with the area light (%u emissive triangles, %u samples per pixel): mean |difference| "
               "%.2f%% of the mean radiance, means ROMA %.4f, Embree %.4f\n", lv.emissive_triangle_count, AREA_SPP,
               100.0 * area_err, area[1], area[2]);
        CHECK(3.0 * n * area[2] > light_ref); /* the ceiling adds light */
        CHECK(area_err <= AREA_MAX_ERROR);
    }

    /* One-bounce GI (roma_gi_effect) of the same room, lit by the spot and the ceiling:
     * GI_SPP bounce rays per pixel, against the reference's indirect light with the same
     * bounce directions and area-light samples. */
    roma_gi_effect *gi = NULL;
    CHECK_RESULT(roma_gi_effect_create(ctx, NULL, &gi), ROMA_SUCCESS);
    CHECK_RESULT(roma_gi_effect_set_scene(gi, lit), ROMA_SUCCESS);
    if (gi && lit_ref) {
        begin_output_frame(ctx, light_out.image, cmd, pool);
        roma_map_frame_desc gf = {.frame = 2, .seed = 5, .jitter_grid = 1, .jitter_directions = 1};
        CHECK_RESULT(roma_map_record_build(map, cmd, &gf, NULL), ROMA_SUCCESS);
        roma_gi_settings gs = {.samples = GI_SPP, .seed = SEED};
        CHECK_RESULT(roma_gi_effect_record(gi, cmd, 0, map, &limages, lv.lights, lv.light_count, &gs), ROMA_SUCCESS);
        CHECK_RESULT(roma_gi_effect_record(gi, cmd, 0, map, &limages, lv.lights, lv.light_count, &gs),
                     ROMA_ERROR_INVALID_ARGUMENT); /* one record per slot and frame */
        read_back_irradiance(ctx, light_out.image, cmd, staging);
        double gi_stats[3]; /* bias, ROMA's mean, the reference's mean */
        double gi_err = light_error(lit_ref, roma_ref_indirect_point, GI_SPP, &lv, hits, covered, n, irradiance, gi_stats);
        printf("one-bounce GI (%u bounce rays per pixel): mean |difference| %.1f%% of the mean radiance, means ROMA "
               "%.4f, Embree %.4f (bias %+.1f%%)\n", GI_SPP, 100.0 * gi_err, gi_stats[1], gi_stats[2],
               100.0 * gi_stats[0]);
        CHECK(gi_stats[2] > 0.0);
        CHECK(gi_err <= GI_MAX_ERROR);
        CHECK(fabs(gi_stats[0]) <= GI_MAX_BIAS);
        /* Without a scene the output is 0; bad settings are refused. */
        CHECK_RESULT(roma_gi_effect_set_scene(gi, NULL), ROMA_SUCCESS);
        roma_gi_settings bad_gi = {.offset_cells = -1.0f}, resolved_gi;
        CHECK_RESULT(roma_gi_settings_resolve(&bad_gi, &resolved_gi), ROMA_ERROR_INVALID_ARGUMENT);
        CHECK_RESULT(roma_gi_settings_resolve(NULL, &resolved_gi), ROMA_SUCCESS);
        CHECK(resolved_gi.samples == ROMA_DEFAULT_GI_SAMPLES && resolved_gi.skip_cells == ROMA_DEFAULT_AO_SKIP_CELLS);
        CHECK_RESULT(roma_gi_effect_record(gi, cmd, 9, map, &limages, NULL, 0, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    }
    roma_gi_effect_destroy(gi);
    roma_gi_effect *refused = (roma_gi_effect *)1;
    CHECK_RESULT(roma_gi_effect_create(ctx, &(roma_gi_effect_desc){.surface_resolution = 16}, &refused),
                 ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(refused == NULL);
    CHECK_RESULT(roma_gi_effect_set_scene(NULL, lit), ROMA_ERROR_INVALID_ARGUMENT);

    CHECK_RESULT(roma_light_effect_set_area_lights(light, NULL), ROMA_SUCCESS); /* removes them */
    many_lights(ctx, &sv, map, light, &limages, light_out.image, cmd, pool, staging, irradiance, hits, covered, n);
    CHECK_RESULT(roma_light_effect_set_area_lights(NULL, lit), ROMA_ERROR_INVALID_ARGUMENT);
    roma_ref_destroy(lit_ref);
    roma_scene_destroy(lit);

    /* Two maps in one frame: the AO of both, recorded in one command buffer with the same
     * slot and frame, shares the slot's pool (the second record must not reset the set the
     * first one's dispatch uses; validation would see a freed set at submit). */
    roma_map *second = NULL;
    CHECK_RESULT(roma_map_create(ctx, &(roma_map_desc){.resolution = 64, .angular = 2}, scene, &second),
                 ROMA_SUCCESS);
    if (second) {
        vkResetCommandPool(dev, pool, 0);
        vkBeginCommandBuffer(cmd, &begin);
        roma_test_layout_barrier(cmd, output.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                                 VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT,
                                 VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        roma_map_frame_desc bf = {.frame = 7, .seed = 5, .jitter_grid = 1, .jitter_directions = 1, .slot = 1};
        CHECK_RESULT(roma_map_record_build(map, cmd, &bf, NULL), ROMA_SUCCESS);
        CHECK_RESULT(roma_map_record_build(second, cmd, &bf, NULL), ROMA_SUCCESS);
        roma_ao_settings both = settings;
        both.frame = 7;
        CHECK_RESULT(roma_ao_effect_record(ao, cmd, 1, map, &images, &both), ROMA_SUCCESS);
        CHECK_RESULT(roma_ao_effect_record(ao, cmd, 1, second, &images, &both), ROMA_SUCCESS);
        roma_test_submit_and_wait(ctx, cmd);
        roma_map_destroy(second);
    }

    /* One frame slot, 20 frames (more than a slot's 16 sets): each frame's build starts a
     * new frame of the slot, whose pool is reset; the engine waits for each frame. */
    roma_ao_effect *single = NULL;
    CHECK_RESULT(roma_ao_effect_create(ctx, &(roma_ao_effect_desc){.frames_in_flight = 1}, &single), ROMA_SUCCESS);
    for (uint32_t f = 0; single && f < 20; ++f) {
        roma_map_frame_desc bf = {.frame = f, .seed = 5, .jitter_grid = 1, .jitter_directions = 1};
        CHECK_RESULT(roma_map_build(map, &bf, NULL), ROMA_SUCCESS);
        vkResetCommandPool(dev, pool, 0);
        vkBeginCommandBuffer(cmd, &begin);
        roma_test_layout_barrier(cmd, output.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                                 VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT,
                                 VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        settings.frame = f;
        CHECK_RESULT(roma_ao_effect_record(single, cmd, 0, map, &images, &settings), ROMA_SUCCESS);
        roma_test_submit_and_wait(ctx, cmd);
    }
    roma_ao_effect_destroy(single);

    /* Bad input: refused with its code. */
    roma_ao_images none = images;
    none.output = VK_NULL_HANDLE;
    CHECK_RESULT(roma_ao_effect_record(ao, cmd, 0, map, &none, &settings), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_ao_effect_record(ao, cmd, 5, map, &images, &settings), ROMA_ERROR_INVALID_ARGUMENT);
    roma_ao_settings bad = {.radius = -1.0f}, resolved;
    CHECK_RESULT(roma_ao_settings_resolve(&bad, &resolved), ROMA_ERROR_INVALID_ARGUMENT);
    bad = (roma_ao_settings){.start = (roma_ao_start)(ROMA_AO_START_SURFACES + 1)};
    CHECK_RESULT(roma_ao_settings_resolve(&bad, &resolved), ROMA_ERROR_INVALID_ARGUMENT);
    roma_ao_settings bad_trace = {.trace = (roma_ao_trace)(ROMA_AO_TRACE_SURFACES + 1)};
    CHECK_RESULT(roma_ao_settings_resolve(&bad_trace, &resolved), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_ao_effect_record(ao, cmd, 0, map, &images, &bad), ROMA_ERROR_INVALID_ARGUMENT);
    roma_ao_effect *coarse = NULL;
    CHECK_RESULT(roma_ao_effect_create(ctx, &(roma_ao_effect_desc){.surface_resolution = 16}, &coarse),
                 ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(coarse == NULL);
    CHECK_RESULT(roma_ao_settings_resolve(NULL, &resolved), ROMA_SUCCESS);
    CHECK(resolved.samples == ROMA_DEFAULT_AO_SAMPLES && resolved.skip_cells == ROMA_DEFAULT_AO_SKIP_CELLS &&
          resolved.offset_cells == ROMA_DEFAULT_OFFSET_CELLS);

    roma_gi_effect *follow = NULL;
    roma_map *moving = NULL;
    CHECK_RESULT(roma_gi_effect_create(ctx, NULL, &follow), ROMA_SUCCESS);
    CHECK_RESULT(roma_map_create(ctx, &(roma_map_desc){.resolution = 128, .angular = 4}, scene, &moving),
                 ROMA_SUCCESS);
    if (follow && moving) {
        CHECK_RESULT(roma_gi_effect_set_scene(follow, scene), ROMA_SUCCESS);
        double bias[2], err[2];
        for (int moved = 0; moved < 2; ++moved)
            err[moved] = gi_frame(ctx, follow, moving, &sv, moved, &limages, light_out.image, in[0].image, cmd, pool,
                                  staging, host, irradiance, ref, hits, covered, &bias[moved]);
        printf("GI following the map: mean |difference| %.1f%% (bias %+.1f%%) in place, %.1f%% (%+.1f%%) with "
               "everything moved by (%g, %g, %g)\n", 100.0 * err[0], 100.0 * bias[0], 100.0 * err[1],
               100.0 * bias[1], (double)MOVE[0], (double)MOVE[1], (double)MOVE[2]);
        CHECK(err[0] <= GI_SPOT_MAX_ERROR && err[1] <= GI_SPOT_MAX_ERROR);
        CHECK(fabs(bias[0]) <= GI_SPOT_MAX_BIAS && fabs(bias[1]) <= GI_SPOT_MAX_BIAS);
    }
    roma_map_destroy(moving);
    roma_gi_effect_destroy(follow);

    vkDestroyCommandPool(dev, pool, NULL);
    for (int i = 0; i < 3; ++i)
        roma_test_image_destroy(dev, &in[i]);
    roma_test_image_destroy(dev, &output);
    roma_test_image_destroy(dev, &light_out);
    roma_light nan_light = sv.lights[0];
    nan_light.intensity = NAN;
    CHECK_RESULT(roma_light_effect_record(light, cmd, 0, map, &limages, &nan_light, 1, NULL),
                 ROMA_ERROR_INVALID_ARGUMENT);
    roma_light_effect_destroy(light);
    roma_test_staging_destroy(dev, &staging_buffer);
    roma_ao_effect_destroy(ao);
    roma_map_destroy(map);
    roma_ref_destroy(ref);
    roma_scene_destroy(scene);
    roma_test_context_finish(ctx);
    return roma_test_finish("test_ao_effect");
}
