/* roma_temporal_effect on images the test owns, against what the host computes from the same
 * values: a plane z = 0 seen pixel for pixel (the world position of pixel (x, y) is
 * (x + 0.5, y + 0.5, 0), so a pixel's footprint is 1).
 *  - still camera (the zero matrix): the running mean of 5 frames, then the exponential mean
 *    once max_history is reached; a reset starts over;
 *  - a camera that moved: the history is fetched 3 pixels to the right, where the previous
 *    frame saw the same point, and dropped where it saw another surface or nothing;
 *  - the filter: noise on two faces of a fold (normals at right angles) is smoothed on each
 *    face without crossing the fold, and pixels with a long history pass through unchanged;
 *  - the filter's weights on a curved surface, 1 and 2 iterations, against the same filter
 *    on the host;
 *  - bad input is refused with its code.
 * Synchronization validation is on: the effect's barriers between its own dispatches are
 * checked (without them it reports read-after-write hazards). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gpu_images.h"
#include "harness.h"
#include "roma/sampling.h"
#include "roma/temporal_effect.h"

#define W 32
#define H 24
#define N (W * H)

enum { CURRENT, POSITION, NORMAL, PREVIOUS_POSITION, INPUT_COUNT };
enum { ACC_A, ACC_B, FILTERED, SCRATCH, STORAGE_COUNT };

typedef struct rig {
    roma_context *ctx;
    VkDevice dev;
    VkCommandPool pool;
    VkCommandBuffer cmd;
    roma_test_image inputs[INPUT_COUNT], storage[STORAGE_COUNT];
    roma_test_staging staging; /* INPUT_COUNT input planes, then STORAGE_COUNT read-back planes */
    roma_test_log log;
    float *plane[INPUT_COUNT + STORAGE_COUNT];
} rig;

/* Values in [0, 1): the library's sample sequence (roma/sampling.h), index i. */
static float noise(uint32_t i)
{
    return roma_random(3, i, 0, 0);
}

static void rig_create(rig *g)
{
    memset(g, 0, sizeof *g);
    /* Synchronization validation: the effect's own barriers between its dispatches are checked. */
    roma_context_desc cd = {.flags = roma_test_sync_validation_flags(), .logger = roma_test_logger(&g->log)};
    if (roma_context_create(&cd, &g->ctx) != ROMA_SUCCESS) {
        fprintf(stderr, "roma_context_create failed\n");
        ++roma_test_failures;
        g->ctx = NULL;
        return;
    }
    g->dev = roma_context_device(g->ctx);
    for (int i = 0; i < INPUT_COUNT; ++i)
        roma_test_image_create(g->ctx, W, H, VK_FORMAT_R32G32B32A32_SFLOAT,
                               VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, &g->inputs[i]);
    for (int i = 0; i < STORAGE_COUNT; ++i)
        roma_test_image_create(g->ctx, W, H, VK_FORMAT_R32G32B32A32_SFLOAT,
                               VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                   VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                               &g->storage[i]);
    roma_test_staging_create(g->ctx, (VkDeviceSize)(INPUT_COUNT + STORAGE_COUNT) * N * 16, &g->staging);
    for (int i = 0; i < INPUT_COUNT + STORAGE_COUNT; ++i)
        g->plane[i] = (float *)g->staging.mapped + (size_t)i * N * 4;
    VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                  .queueFamilyIndex = roma_context_queue_family(g->ctx)};
    CHECK(vkCreateCommandPool(g->dev, &pi, NULL, &g->pool) == VK_SUCCESS);
    VkCommandBufferAllocateInfo cai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                       .commandPool = g->pool,
                                       .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                       .commandBufferCount = 1};
    CHECK(vkAllocateCommandBuffers(g->dev, &cai, &g->cmd) == VK_SUCCESS);
    /* Between frames the storage images wait in TRANSFER_SRC_OPTIMAL (read back). */
    VkCommandBufferBeginInfo begin = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vkBeginCommandBuffer(g->cmd, &begin);
    for (int i = 0; i < STORAGE_COUNT; ++i)
        roma_test_layout_barrier(g->cmd, g->storage[i].image, VK_IMAGE_LAYOUT_UNDEFINED,
                                 VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
                                 VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    roma_test_submit_and_wait(g->ctx, g->cmd);
}

static void rig_destroy(rig *g)
{
    if (!g->ctx)
        return;
    vkDestroyCommandPool(g->dev, g->pool, NULL);
    for (int i = 0; i < INPUT_COUNT; ++i)
        roma_test_image_destroy(g->dev, &g->inputs[i]);
    for (int i = 0; i < STORAGE_COUNT; ++i)
        roma_test_image_destroy(g->dev, &g->storage[i]);
    roma_test_staging_destroy(g->dev, &g->staging);
    uint32_t messages = roma_context_validation_error_count(g->ctx);
    printf("validation messages: %u, warnings logged: %d\n", messages, g->log.warnings);
    CHECK(messages == 0 && g->log.warnings == 0);
    roma_context_destroy(g->ctx);
}

/* One frame as an engine records it: the input planes uploaded, the storage images the record
 * reads made visible, the record, every storage image read back into its plane. */
static roma_result frame(rig *g, roma_temporal_effect *e, uint32_t slot, const roma_temporal_images *images,
                         const roma_temporal_settings *settings)
{
    vkResetCommandPool(g->dev, g->pool, 0);
    VkCommandBufferBeginInfo begin = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vkBeginCommandBuffer(g->cmd, &begin);
    for (int i = 0; i < INPUT_COUNT; ++i) {
        roma_test_layout_barrier(g->cmd, g->inputs[i].image, VK_IMAGE_LAYOUT_UNDEFINED,
                                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                 VK_ACCESS_2_MEMORY_READ_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                                 VK_ACCESS_2_TRANSFER_WRITE_BIT);
        VkBufferImageCopy copy = {.bufferOffset = (VkDeviceSize)i * N * 16,
                                  .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                  .imageExtent = {W, H, 1}};
        vkCmdCopyBufferToImage(g->cmd, g->staging.buffer, g->inputs[i].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                               &copy);
        roma_test_layout_barrier(g->cmd, g->inputs[i].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                                 VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                 VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    }
    for (int i = 0; i < STORAGE_COUNT; ++i) /* last frame's read-backs before this frame's use */
        roma_test_layout_barrier(g->cmd, g->storage[i].image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                 VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COPY_BIT, 0,
                                 VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                 VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                                     VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    roma_result r = roma_temporal_effect_record(e, g->cmd, slot, images, settings);
    for (int i = 0; i < STORAGE_COUNT; ++i) {
        roma_test_layout_barrier(g->cmd, g->storage[i].image, VK_IMAGE_LAYOUT_GENERAL,
                                 VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                 VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                                 VK_ACCESS_2_TRANSFER_READ_BIT);
        VkBufferImageCopy back = {.bufferOffset = (VkDeviceSize)(INPUT_COUNT + i) * N * 16,
                                  .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                  .imageExtent = {W, H, 1}};
        vkCmdCopyImageToBuffer(g->cmd, g->storage[i].image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, g->staging.buffer, 1,
                               &back);
    }
    roma_test_submit_and_wait(g->ctx, g->cmd);
    return r;
}

/* The plane z = 0, pixel for pixel, into a position plane (and its normal +z). */
static void flat_plane(float *position, float *normal)
{
    for (uint32_t p = 0; p < N; ++p) {
        float v[4] = {(float)(p % W) + 0.5f, (float)(p / W) + 0.5f, 0.0f, 1.0f};
        memcpy(position + 4 * p, v, sizeof v);
        if (normal) {
            float n[4] = {0.0f, 0.0f, 1.0f, 0.0f};
            memcpy(normal + 4 * p, n, sizeof n);
        }
    }
}

static roma_temporal_images images_of(const rig *g, int accumulated, int history)
{
    roma_temporal_images im = {.width = W, .height = H, .current = g->inputs[CURRENT].view,
                               .position = g->inputs[POSITION].view, .normal = g->inputs[NORMAL].view,
                               .previous_position = g->inputs[PREVIOUS_POSITION].view,
                               .history = history >= 0 ? g->storage[history].view : VK_NULL_HANDLE,
                               .accumulated = g->storage[accumulated].view};
    return im;
}

/* Still camera: 5 frames averaged exactly (max_history 8), then 3 more with max_history 3
 * (exponential: weight 1/3 on the new value); a reset starts over. */
static void still_camera(rig *g, roma_temporal_effect *e)
{
    flat_plane(g->plane[POSITION], g->plane[NORMAL]);
    flat_plane(g->plane[PREVIOUS_POSITION], NULL);
    static double want[N];
    double worst = 0.0;
    int counts_ok = 1;
    for (uint32_t f = 0; f < 8; ++f) {
        for (uint32_t p = 0; p < N; ++p) {
            float v = noise(f * N + p);
            g->plane[CURRENT][4 * p] = v, g->plane[CURRENT][4 * p + 1] = 0.5f * v, g->plane[CURRENT][4 * p + 2] = 1.0f;
            uint32_t count = f < 5 ? f + 1 : 3;
            want[p] = f == 0 ? v : want[p] + (v - want[p]) / count;
        }
        int acc = f % 2 ? ACC_B : ACC_A, hist = f % 2 ? ACC_A : ACC_B;
        roma_temporal_images im = images_of(g, acc, f == 0 ? -1 : hist);
        roma_temporal_settings s = {.max_history = f < 5 ? 8 : 3, .reset = f == 0, .frame = f};
        CHECK_RESULT(frame(g, e, f % 2, &im, &s), ROMA_SUCCESS);
        const float *out = g->plane[INPUT_COUNT + acc];
        for (uint32_t p = 0; p < N; ++p) {
            worst = fmax(worst, fabs(out[4 * p] - want[p]));
            worst = fmax(worst, fabs(out[4 * p + 1] - 0.5 * want[p]));
            counts_ok &= out[4 * p + 3] == (float)(f < 5 ? f + 1 : 3) && out[4 * p + 2] == 1.0f;
        }
    }
    printf("still camera: 8 frames (a running mean of 5, then max_history 3): largest difference from the host's "
           "mean %.2g\n", worst);
    CHECK(worst < 1e-6 && counts_ok);
    /* A reset keeps nothing: the output is this frame's value with a history of 1. */
    roma_temporal_images im = images_of(g, ACC_A, ACC_B);
    roma_temporal_settings s = {.reset = 1, .frame = 8};
    CHECK_RESULT(frame(g, e, 0, &im, &s), ROMA_SUCCESS);
    int reset_ok = 1;
    for (uint32_t p = 0; p < N; ++p)
        reset_ok &= g->plane[INPUT_COUNT + ACC_A][4 * p] == g->plane[CURRENT][4 * p] &&
                    g->plane[INPUT_COUNT + ACC_A][4 * p + 3] == 1.0f;
    CHECK(reset_ok);
}

/* A camera that moved: the previous frame's matrix puts this frame's point of pixel x at pixel
 * x + 3 of the previous picture. There the previous frame saw the same point, except in
 * every fifth column (a surface 5 units in front) and the last 3 columns have no history. */
static void moved_camera(rig *g, roma_temporal_effect *e)
{
    flat_plane(g->plane[POSITION], g->plane[NORMAL]);
    /* History: value 0.25 + noise, 1 frame; the previous positions shifted by 3 pixels. */
    for (uint32_t p = 0; p < N; ++p) {
        uint32_t x = p % W, y = p / W;
        float was[4] = {(float)x - 3.0f + 0.5f, (float)y + 0.5f, x % 5 == 0 ? 5.0f : 0.0f, 1.0f};
        memcpy(g->plane[PREVIOUS_POSITION] + 4 * p, was, sizeof was);
        g->plane[CURRENT][4 * p] = 1.0f, g->plane[CURRENT][4 * p + 1] = 0.0f, g->plane[CURRENT][4 * p + 2] = 0.0f;
    }
    /* Frame 0 (reset) puts a known history into ACC_A: this frame's current = history values. */
    for (uint32_t p = 0; p < N; ++p)
        g->plane[CURRENT][4 * p] = 0.25f * noise(7 * N + p);
    roma_temporal_images im = images_of(g, ACC_A, -1);
    roma_temporal_settings s = {.reset = 1, .frame = 20};
    CHECK_RESULT(frame(g, e, 0, &im, &s), ROMA_SUCCESS);
    static float history[N];
    for (uint32_t p = 0; p < N; ++p)
        history[p] = g->plane[CURRENT][4 * p], g->plane[CURRENT][4 * p] = 1.0f;
    /* world -> clip, column-major: clip.x = 2 (X + 3) / W - 1, clip.y = 2 Y / H - 1, w = 1. */
    roma_temporal_settings moved = {.previous_view_proj = {2.0f / W, 0, 0, 0, 0, 2.0f / H, 0, 0, 0, 0, 0, 0,
                                                           6.0f / W - 1.0f, -1.0f, 0, 1.0f},
                                    .frame = 21};
    im = images_of(g, ACC_B, ACC_A);
    CHECK_RESULT(frame(g, e, 1, &im, &moved), ROMA_SUCCESS);
    const float *out = g->plane[INPUT_COUNT + ACC_B];
    uint32_t kept = 0, dropped = 0, wrong = 0;
    for (uint32_t p = 0; p < N; ++p) {
        uint32_t x = p % W, q = p + 3;
        int has = x + 3 < W && (x + 3) % 5 != 0;
        float want = has ? (history[q] + 1.0f) / 2.0f : 1.0f;
        wrong += fabsf(out[4 * p] - want) > 1e-6f || out[4 * p + 3] != (has ? 2.0f : 1.0f);
        kept += has, dropped += !has;
    }
    printf("moved camera: %u pixels kept the history 3 pixels over, %u dropped it (another surface or off the "
           "picture), %u wrong\n", kept, dropped, wrong);
    CHECK(wrong == 0 && kept > 0 && dropped > 0);
}

/* The filter: a fold along x = W / 2 (left face z = 0 facing +z, right face x = W / 2
 * facing -x, running off in z), values 0.2 and 0.8 with noise; one frame of history. */
static void filter(rig *g, roma_temporal_effect *e)
{
    for (uint32_t p = 0; p < N; ++p) {
        uint32_t x = p % W, y = p / W;
        int left = x < W / 2;
        float pos[4] = {left ? (float)x + 0.5f : W / 2.0f, (float)y + 0.5f, left ? 0.0f : (float)x - W / 2.0f + 0.5f,
                        1.0f};
        float nrm[4] = {left ? 0.0f : -1.0f, 0.0f, left ? 1.0f : 0.0f, 0.0f};
        memcpy(g->plane[POSITION] + 4 * p, pos, sizeof pos);
        memcpy(g->plane[NORMAL] + 4 * p, nrm, sizeof nrm);
        float v = (left ? 0.2f : 0.8f) + 0.2f * (noise(11 * N + p) - 0.5f);
        g->plane[CURRENT][4 * p] = g->plane[CURRENT][4 * p + 1] = g->plane[CURRENT][4 * p + 2] = v;
    }
    roma_temporal_images im = images_of(g, ACC_A, -1);
    im.filtered = g->storage[FILTERED].view;
    im.scratch = g->storage[SCRATCH].view;
    roma_temporal_settings s = {.reset = 1, .frame = 30};
    CHECK_RESULT(frame(g, e, 0, &im, &s), ROMA_SUCCESS);
    const float *in = g->plane[INPUT_COUNT + ACC_A], *out = g->plane[INPUT_COUNT + FILTERED];
    double var_in[2] = {0, 0}, var_out[2] = {0, 0}, edge = 0.0;
    uint32_t count[2] = {0, 0}, edge_n = 0;
    for (uint32_t p = 0; p < N; ++p) {
        uint32_t x = p % W;
        int side = x >= W / 2;
        double mean = side ? 0.8 : 0.2;
        var_in[side] += (in[4 * p] - mean) * (in[4 * p] - mean);
        var_out[side] += (out[4 * p] - mean) * (out[4 * p] - mean);
        ++count[side];
        if (x == W / 2 - 1) /* the last column of the left face, beside the fold */
            edge += out[4 * p], ++edge_n;
    }
    double ratio = fmax(var_out[0] / var_in[0], var_out[1] / var_in[1]);
    printf("filter: variance on each face %.3g and %.3g of its input's; the column beside the fold averages %.4f "
           "(its face 0.2)\n", var_out[0] / var_in[0], var_out[1] / var_in[1], edge / edge_n);
    /* Measured: 0.0044 and 0.0086; 0.2041 (across the fold, weight 0: no 0.8 leaks in). */
    CHECK(ratio < 0.01 && fabs(edge / edge_n - 0.2) < 0.01);
    /* With a history as long as filter_below the values pass through unchanged. */
    s.filter_below = 1;
    s.frame = 31;
    CHECK_RESULT(frame(g, e, 1, &im, &s), ROMA_SUCCESS);
    CHECK(memcmp(g->plane[INPUT_COUNT + ACC_A], g->plane[INPUT_COUNT + FILTERED], (size_t)N * 16) == 0);
}

/* The filter's weights on a curved surface (z = 0.03 (x - W/2)^2, normals turning across it,
 * points leaving each other's tangent planes): one iteration (no scratch image) and two
 * (through scratch into filtered) against the same filter on the host, taps weighted by the B3 spline, cos^32 of the normals' angle and
 * exp(-distance to the tangent plane / (footprint * step)), the footprint the distance to
 * the nearest of the four neighbours' points (atrous_images.comp, roma_footprint.glsl). */
static void curved_point(uint32_t x, uint32_t y, double p[3], double n[3])
{
    double u = (double)x + 0.5 - W / 2.0;
    p[0] = (double)x + 0.5, p[1] = (double)y + 0.5, p[2] = 0.03 * u * u;
    double len = sqrt(0.0036 * u * u + 1.0);
    n[0] = -0.06 * u / len, n[1] = 0.0, n[2] = 1.0 / len;
}

static void atrous_curved_host(const float *src, float *dst, int step)
{
    const double kernel[3] = {3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0};
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            double p[3], n[3], footprint = 1e30;
            curved_point((uint32_t)x, (uint32_t)y, p, n);
            const int near[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
            for (int i = 0; i < 4; ++i) {
                int qx = x + near[i][0], qy = y + near[i][1];
                if (qx < 0 || qy < 0 || qx >= W || qy >= H)
                    continue;
                double q[3], qn[3];
                curved_point((uint32_t)qx, (uint32_t)qy, q, qn);
                footprint = fmin(footprint, sqrt((q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]) +
                                                 (q[2] - p[2]) * (q[2] - p[2])));
            }
            footprint *= step;
            double sum = 0.0, weights = 0.0;
            for (int dy = -2; dy <= 2; ++dy)
                for (int dx = -2; dx <= 2; ++dx) {
                    int qx = x + dx * step, qy = y + dy * step;
                    if (qx < 0 || qy < 0 || qx >= W || qy >= H)
                        continue;
                    double q[3], qn[3];
                    curved_point((uint32_t)qx, (uint32_t)qy, q, qn);
                    double c = fmax(n[0] * qn[0] + n[1] * qn[1] + n[2] * qn[2], 0.0);
                    double plane = fabs((q[0] - p[0]) * n[0] + (q[1] - p[1]) * n[1] + (q[2] - p[2]) * n[2]) / footprint;
                    double w = kernel[abs(dx)] * kernel[abs(dy)] * pow(c, 32.0) * exp(-plane);
                    sum += w * src[qy * W + qx];
                    weights += w;
                }
            dst[y * W + x] = (float)(sum / weights);
        }
}

static void filter_curved(rig *g, roma_temporal_effect *e)
{
    for (uint32_t p = 0; p < N; ++p) {
        double pos[3], nrm[3];
        curved_point(p % W, p / W, pos, nrm);
        float fpos[4] = {(float)pos[0], (float)pos[1], (float)pos[2], 1.0f};
        float fnrm[4] = {(float)nrm[0], (float)nrm[1], (float)nrm[2], 0.0f};
        memcpy(g->plane[POSITION] + 4 * p, fpos, sizeof fpos);
        memcpy(g->plane[NORMAL] + 4 * p, fnrm, sizeof fnrm);
        float v = 0.5f + 0.4f * (noise(13 * N + p) - 0.5f);
        g->plane[CURRENT][4 * p] = g->plane[CURRENT][4 * p + 1] = g->plane[CURRENT][4 * p + 2] = v;
    }
    const float *in = g->plane[INPUT_COUNT + ACC_A], *out = g->plane[INPUT_COUNT + FILTERED];
    static float host[2][N];
    for (uint32_t iterations = 1; iterations <= 2; ++iterations) {
        roma_temporal_images im = images_of(g, ACC_A, -1);
        im.filtered = g->storage[FILTERED].view;
        im.scratch = iterations > 1 ? g->storage[SCRATCH].view : VK_NULL_HANDLE; /* one needs none */
        roma_temporal_settings fs = {.reset = 1, .frame = 40 + iterations, .filter_iterations = iterations};
        CHECK_RESULT(frame(g, e, iterations % 2, &im, &fs), ROMA_SUCCESS);
        for (uint32_t p = 0; p < N; ++p)
            host[0][p] = in[4 * p];
        for (uint32_t i = 0; i < iterations; ++i) {
            atrous_curved_host(host[0], host[1], 1 << i);
            memcpy(host[0], host[1], sizeof host[0]);
        }
        double worst = 0.0, moved = 0.0;
        for (uint32_t p = 0; p < N; ++p) {
            worst = fmax(worst, fabs((double)out[4 * p] - host[0][p]));
            moved = fmax(moved, fabs((double)out[4 * p] - in[4 * p]));
        }
        printf("filter on a curved surface: %u iteration%s, largest difference from the host's %.2g (the filter "
               "moved values by up to %.3f)\n", iterations, iterations > 1 ? "s" : "", worst, moved);
        /* Measured: 2.1e-7 and 2.4e-7 (float against double); cos^16 instead of cos^32 would
         * give 0.0021 / 0.003, a plane distance half as heavy 0.0011 / 0.00084. */
        CHECK(moved > 0.01 && worst < 5e-7);
    }
}

static void bad_input(rig *g, roma_temporal_effect *e)
{
    roma_temporal_images im = images_of(g, ACC_A, ACC_B), bad = im;
    roma_temporal_settings s = {.frame = 40};
    bad.history = VK_NULL_HANDLE; /* without reset */
    CHECK_RESULT(roma_temporal_effect_record(e, g->cmd, 0, &bad, &s), ROMA_ERROR_INVALID_ARGUMENT);
    bad = im, bad.normal = VK_NULL_HANDLE;
    CHECK_RESULT(roma_temporal_effect_record(e, g->cmd, 0, &bad, &s), ROMA_ERROR_INVALID_ARGUMENT);
    bad = im, bad.filtered = g->storage[FILTERED].view; /* 3 iterations, no scratch */
    CHECK_RESULT(roma_temporal_effect_record(e, g->cmd, 0, &bad, &s), ROMA_ERROR_INVALID_ARGUMENT);
    bad = im, bad.history = im.accumulated; /* read and written in one dispatch */
    CHECK_RESULT(roma_temporal_effect_record(e, g->cmd, 0, &bad, &s), ROMA_ERROR_INVALID_ARGUMENT);
    bad = im, bad.filtered = g->storage[FILTERED].view, bad.scratch = bad.filtered;
    CHECK_RESULT(roma_temporal_effect_record(e, g->cmd, 0, &bad, &s), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_temporal_effect_record(e, g->cmd, 2, &im, &s), ROMA_ERROR_INVALID_ARGUMENT); /* slot */
    CHECK_RESULT(roma_temporal_effect_record(e, g->cmd, 0, NULL, &s), ROMA_ERROR_INVALID_ARGUMENT);
    roma_temporal_settings nan = s, many = s, resolved;
    nan.previous_view_proj[5] = NAN;
    CHECK_RESULT(roma_temporal_effect_record(e, g->cmd, 0, &im, &nan), ROMA_ERROR_INVALID_ARGUMENT);
    many.filter_iterations = ROMA_MAX_FILTER_ITERATIONS + 1;
    CHECK_RESULT(roma_temporal_settings_resolve(&many, &resolved), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_temporal_settings_resolve(NULL, &resolved), ROMA_SUCCESS);
    CHECK(resolved.max_history == ROMA_DEFAULT_TEMPORAL_HISTORY &&
          resolved.filter_iterations == ROMA_DEFAULT_FILTER_ITERATIONS &&
          resolved.filter_below == ROMA_DEFAULT_FILTER_BELOW);
    roma_temporal_effect *none = (roma_temporal_effect *)1;
    CHECK_RESULT(roma_temporal_effect_create(g->ctx, &(roma_temporal_effect_desc){.frames_in_flight = 9}, &none),
                 ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(none == NULL);
}

int main(void)
{
    rig g;
    rig_create(&g);
    if (!g.ctx)
        return roma_test_finish("test_temporal_effect");
    roma_temporal_effect *e = NULL;
    CHECK_RESULT(roma_temporal_effect_create(g.ctx, NULL, &e), ROMA_SUCCESS);
    if (e) {
        still_camera(&g, e);
        moved_camera(&g, e);
        filter(&g, e);
        filter_curved(&g, e);
        bad_input(&g, e);
    }
    roma_temporal_effect_destroy(e);
    rig_destroy(&g);
    return roma_test_finish("test_temporal_effect");
}
