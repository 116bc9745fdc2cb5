/* The hardware ray-tracing baseline (src/study/hw_ray_tracing.c).
 * Where no device offers VK_KHR_ray_tracing_pipeline and VK_KHR_acceleration_structure
 * (lavapipe): the device's creation says which device lacks which extension, leaves nothing
 * behind (the sanitizer suite checks for leaks) and refuses bad arguments. Where one does: on
 * the built-in room, rays from random points inside it in random directions, some bounded,
 * traced by the hardware and by Embree: the any-hit answers agree but for rays that graze an
 * edge, the closest distances agree to float precision; the ray-traced stochastic depth map
 * keeps, where a view ray passes fewer surfaces than it has layers, exactly the surfaces Embree
 * finds along that ray; the validation layer says nothing. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "reference.h"
#include "roma/builtin_scenes.h"
#include "roma/map.h"
#include "roma/roma.h"
#include "roma_shared.h"
#include "study/hw_ray_tracing.h"
#include "vulkan/upload.h"
#include "vulkan/vk_internal.h"

enum { N = 4096 };

static float rnd(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return (float)(*s >> 8) / 16777216.0f;
}

/* The built-in room on the ray-tracing device, and Embree's copy of it. */
typedef struct room {
    roma_context *ctx;
    roma_scene *scene;
    roma_ref *ref;
} room;

static void trace_against_embree(roma_hwrt_device *dev, const room *rm)
{
    roma_context *ctx = rm->ctx;
    const roma_scene *scene = rm->scene;
    const roma_ref *ref = rm->ref;
    roma_scene_view v;
    roma_scene_get_view(scene, &v);
    static roma_ray rays[N];
    static float orgs[3 * N], dirs[3 * N], tmaxs[N], t_embree[N];
    static uint8_t occ_embree[N];
    uint32_t seed = 7;
    for (uint32_t i = 0; i < N; ++i) {
        roma_ray *r = &rays[i];
        for (int a = 0; a < 3; ++a) {
            r->origin[a] = v.bounds_min[a] + (0.05f + 0.9f * rnd(&seed)) * (v.bounds_max[a] - v.bounds_min[a]);
            r->dir[a] = 2.0f * rnd(&seed) - 1.0f;
        }
        r->tmin = 0.0f;
        r->tmax = i % 2 ? 0.3f : INFINITY;
        const float len = sqrtf(r->dir[0] * r->dir[0] + r->dir[1] * r->dir[1] + r->dir[2] * r->dir[2]);
        for (int a = 0; a < 3; ++a) {
            orgs[3 * i + a] = r->origin[a];
            dirs[3 * i + a] = r->dir[a] / len;
        }
        tmaxs[i] = r->tmax;
    }
    roma_ref_occluded_batch(ref, N, orgs, dirs, NULL, tmaxs, occ_embree);
    roma_ref_intersect_batch(ref, N, orgs, dirs, NULL, tmaxs, t_embree);

    roma_hwrt *h = NULL;
    CHECK_RESULT(roma_hwrt_create(ctx, dev, scene, &h), ROMA_SUCCESS);
    roma_buffer ray_buf = {0}, hit_buf = {0}, readback = {0};
    CHECK_RESULT(roma_buffer_create_filled(ctx, sizeof rays, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                           VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT, rays, &ray_buf),
                 ROMA_SUCCESS);
    CHECK_RESULT(roma_buffer_create(ctx, sizeof(roma_hit) * N, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                    VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                    ROMA_MEMORY_DEVICE, &hit_buf),
                 ROMA_SUCCESS);
    CHECK_RESULT(roma_buffer_create(ctx, sizeof(roma_hit) * N, VK_BUFFER_USAGE_TRANSFER_DST_BIT, ROMA_MEMORY_READBACK,
                                    &readback),
                 ROMA_SUCCESS);
    for (int closest = 0; closest < 2 && h && readback.mapped; ++closest) {
        VkCommandBuffer cmd;
        CHECK_RESULT(roma_begin_one_shot(ctx, &cmd), ROMA_SUCCESS);
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_TRANSFER_READ_BIT,
                                VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR,
                                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        roma_hwrt_record_build(h, cmd); /* a dynamic scene's frame builds again */
        roma_hwrt_record_trace(h, cmd, ray_buf.address, hit_buf.address, N, closest);
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR,
                                VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                                VK_ACCESS_2_TRANSFER_READ_BIT);
        vkCmdCopyBuffer(cmd, hit_buf.buffer, readback.buffer, 1, &(VkBufferCopy){0, 0, sizeof(roma_hit) * N});
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        CHECK_RESULT(roma_submit_one_shot(ctx, cmd), ROMA_SUCCESS);
        CHECK_RESULT(roma_buffer_invalidate(ctx, &readback), ROMA_SUCCESS);
        const roma_hit *hits = readback.mapped;
        uint32_t disagree = 0, hit_count = 0, far = 0;
        for (uint32_t i = 0; i < N; ++i) {
            const int hw = (hits[i].info & ROMA_HIT_FLAG) != 0;
            const int em = closest ? isfinite(t_embree[i]) : occ_embree[i] != 0;
            disagree += hw != em;
            hit_count += hw;
            if (closest && hw && em && fabsf(hits[i].t - t_embree[i]) > 1e-4f * (1.0f + t_embree[i]))
                ++far;
            if (!closest && hw && !isinf(hits[i].t))
                ++far; /* any-hit reports no distance, as ROMA's */
        }
        printf("%s: %u of %u rays hit, %u disagree with Embree, %u distances apart\n",
               closest ? "closest hit" : "any hit", hit_count, N, disagree, far);
        CHECK(hit_count > N / 4 && hit_count < N); /* bounded rays miss, unbounded ones hit the closed room */
        CHECK(disagree <= N / 1000);
        CHECK(far <= N / 1000); /* a ray grazing an edge may meet another triangle */
    }
    roma_buffer_destroy(ctx, &ray_buf);
    roma_buffer_destroy(ctx, &hit_buf);
    roma_buffer_destroy(ctx, &readback);
    roma_hwrt_destroy(h);
}

enum { W = 64, H = 48, LAYERS = 4 };

/* Every surface along a view ray, by Embree: closest hits, each next one searched from just
 * past the last (at most max). */
static uint32_t embree_surfaces(const roma_ref *ref, const float o[3], const float d[3], float tmin, float *t,
                                uint32_t max)
{
    uint32_t n = 0;
    float from = tmin;
    while (n < max) {
        const float inf = INFINITY;
        float hit;
        roma_ref_intersect_batch(ref, 1, o, d, &from, &inf, &hit);
        if (!isfinite(hit))
            break;
        t[n++] = hit;
        from = hit + 1e-4f;
    }
    return n;
}

/* The depth map's view: from inside the room, towards a corner with its blocks. */
static roma_camera view_camera(const roma_scene *scene)
{
    roma_scene_view v;
    roma_scene_get_view(scene, &v);
    roma_camera cam = {.fovy_deg = 60.0f};
    for (int a = 0; a < 3; ++a) {
        const float c = 0.5f * (v.bounds_min[a] + v.bounds_max[a]), e = v.bounds_max[a] - v.bounds_min[a];
        const float eye[3] = {0.0f, 0.1f, 0.3f}, at[3] = {-0.2f, -0.2f, -0.5f};
        cam.eye[a] = c + eye[a] * e;
        cam.target[a] = c + at[a] * e;
    }
    return cam;
}

#define NEAR_PLANE 0.01f

/* The view ray of pixel (x, y), as hwrt_depth_layers.rgen makes it: unit d, and *len the
 * length of the ray of unit depth (the near plane lies at NEAR_PLANE * len). */
static void view_ray(const roma_camera_frame *f, uint32_t x, uint32_t y, float d[3], float *len)
{
    const float sx = 0.5f * (float)W / (f->tan_half_fovy * f->aspect), sy = 0.5f * (float)H / f->tan_half_fovy;
    const float cx = (float)x + 0.5f - 0.5f * W, cy = (float)y + 0.5f - 0.5f * H;
    float l = 0.0f;
    for (int a = 0; a < 3; ++a) {
        d[a] = f->forward[a] + f->right[a] * (cx / sx) - f->up[a] * (cy / sy);
        l += d[a] * d[a];
    }
    l = sqrtf(l);
    for (int a = 0; a < 3; ++a)
        d[a] /= l;
    *len = l;
}

/* How many surfaces Embree finds along the view's rays (every machine): the comparison on a
 * GPU needs most pixels to pass at most LAYERS surfaces, and more than one in the mean. */
static void view_surfaces(const roma_scene *scene, const roma_ref *ref)
{
    const roma_camera cam = view_camera(scene);
    roma_camera_frame f;
    CHECK(roma_camera_make_frame(&cam, W, H, &f));
    uint32_t histogram[10] = {0}, total = 0, few = 0;
    for (uint32_t y = 0; y < H; ++y)
        for (uint32_t x = 0; x < W; ++x) {
            float d[3], len, t[9];
            view_ray(&f, x, y, d, &len);
            const uint32_t n = embree_surfaces(ref, f.origin, d, NEAR_PLANE * len, t, 9);
            ++histogram[n];
            total += n;
            few += n <= LAYERS;
        }
    printf("the depth map's view, %ux%u: Embree finds", W, H);
    for (uint32_t n = 0; n < 10; ++n)
        if (histogram[n])
            printf(" %u surface%s along %u rays;", n, n == 1 ? "" : "s", histogram[n]);
    printf(" %u in all\n", total);
    CHECK(few > W * H / 2 && total > W * H);
}

/* The ray-traced stochastic depth map from inside the built-in room, against Embree. */
static void depth_layers_against_embree(roma_hwrt_device *dev, const room *rm)
{
    roma_context *ctx = rm->ctx;
    const roma_scene *scene = rm->scene;
    const roma_ref *ref = rm->ref;
    roma_hwrt *h = NULL;
    CHECK_RESULT(roma_hwrt_create(ctx, dev, scene, &h), ROMA_SUCCESS);
    if (!h)
        return;
    const roma_camera cam = view_camera(scene);
    const float near_plane = NEAR_PLANE;
    const size_t bytes = (size_t)W * H * LAYERS * sizeof(roma_gbuffer_pixel);
    roma_buffer pixels = {0}, readback = {0};
    CHECK_RESULT(roma_buffer_create(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                    VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                    ROMA_MEMORY_DEVICE, &pixels),
                 ROMA_SUCCESS);
    CHECK_RESULT(roma_buffer_create(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, ROMA_MEMORY_READBACK, &readback),
                 ROMA_SUCCESS);
    VkCommandBuffer cmd;
    if (readback.mapped && roma_begin_one_shot(ctx, &cmd) == ROMA_SUCCESS) {
        /* Bad arguments record nothing. */
        CHECK_RESULT(roma_hwrt_record_depth_layers(h, cmd, &cam, near_plane, pixels.address, W, H, 0, 1),
                     ROMA_ERROR_INVALID_ARGUMENT);
        CHECK_RESULT(roma_hwrt_record_depth_layers(h, cmd, &cam, 0.0f, pixels.address, W, H, LAYERS, 1),
                     ROMA_ERROR_INVALID_ARGUMENT);
        CHECK_RESULT(roma_hwrt_record_depth_layers(h, cmd, &cam, near_plane, pixels.address, W, H, LAYERS, 1),
                     ROMA_SUCCESS);
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR, VK_ACCESS_2_SHADER_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        vkCmdCopyBuffer(cmd, pixels.buffer, readback.buffer, 1, &(VkBufferCopy){0, 0, bytes});
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        CHECK_RESULT(roma_submit_one_shot(ctx, cmd), ROMA_SUCCESS);
        CHECK_RESULT(roma_buffer_invalidate(ctx, &readback), ROMA_SUCCESS);
        const roma_gbuffer_pixel *px = readback.mapped;
        roma_camera_frame f;
        CHECK(roma_camera_make_frame(&cam, W, H, &f));
        uint32_t compared = 0, differ = 0, kept = 0, off_triangle = 0;
        for (uint32_t y = 0; y < H; ++y)
            for (uint32_t x = 0; x < W; ++x) {
                float d[3], len, t[9];
                view_ray(&f, x, y, d, &len);
                const uint32_t n = embree_surfaces(ref, f.origin, d, near_plane * len, t, 9);
                float got[LAYERS];
                uint32_t m = 0;
                for (uint32_t l = 0; l < LAYERS; ++l) {
                    const roma_gbuffer_pixel *g = &px[(size_t)l * W * H + (size_t)y * W + x];
                    if (!isfinite(g->position_t[3]))
                        continue;
                    got[m++] = g->position_t[3];
                    /* The point is on the ray at its distance. */
                    float e = 0.0f;
                    for (int a = 0; a < 3; ++a)
                        e += fabsf(g->position_t[a] - (f.origin[a] + d[a] * g->position_t[3]));
                    off_triangle += e > 1e-3f * (1.0f + g->position_t[3]);
                }
                kept += m;
                if (n > LAYERS)
                    continue; /* a reservoir's draw: fewer kept than passed */
                ++compared;
                /* Every surface Embree passes is kept (order aside), nothing else. */
                int same = m == n;
                for (uint32_t i = 0; i < n && same; ++i) {
                    int found = 0;
                    for (uint32_t j = 0; j < m; ++j)
                        found |= fabsf(got[j] - t[i]) <= 1e-4f * (1.0f + t[i]);
                    same = found;
                }
                differ += !same;
            }
        printf("depth map: %u surfaces kept in %u layers of %ux%u; %u pixels passing at most %u surfaces, %u of "
               "them differ from Embree; %u points off their ray\n",
               kept, LAYERS, W, H, compared, LAYERS, differ, off_triangle);
        CHECK(compared > W * H / 2);
        CHECK(kept > W * H); /* more than one surface a pixel in the mean: the layers see behind */
        CHECK(differ <= W * H / 100); /* a ray grazing an edge may meet a triangle twice or not */
        CHECK(off_triangle == 0);
    }
    roma_buffer_destroy(ctx, &pixels);
    roma_buffer_destroy(ctx, &readback);
    roma_hwrt_destroy(h);
}

int main(void)
{
    char why[256];
    roma_hwrt_device *dev = NULL;
    /* Bad arguments: refused, nothing made. */
    CHECK_RESULT(roma_hwrt_device_create(NULL, 0, NULL, why, sizeof why), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_hwrt_create(NULL, NULL, NULL, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    roma_hwrt *h = (roma_hwrt *)&why;
    CHECK_RESULT(roma_hwrt_create(NULL, NULL, NULL, &h), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(h == NULL);
    roma_hwrt_destroy(NULL);
    CHECK(roma_hwrt_device_destroy(NULL) == 0);
    CHECK(roma_hwrt_device_external(NULL) == NULL);

    const char *validation = getenv("ROMA_VALIDATION");
    const int validate = validation && *validation && strcmp(validation, "0") != 0;
    /* A device name no device has: refused with a reason. */
    CHECK_RESULT(roma_hwrt_device_create("no such device anywhere", validate, &dev, why, sizeof why),
                 ROMA_ERROR_MISSING_FEATURE);
    CHECK(dev == NULL && strstr(why, "no device matches") != NULL);

    /* The room and Embree's copy (the depth map's view checked on every machine). */
    room rm = {0};
    CHECK_RESULT(roma_scene_create_builtin("cornell", NULL, &rm.scene), ROMA_SUCCESS);
    if (rm.scene)
        CHECK_RESULT(roma_ref_create(rm.scene, NULL, &rm.ref), ROMA_SUCCESS);
    if (rm.ref)
        view_surfaces(rm.scene, rm.ref);

    const roma_result r = roma_hwrt_device_create(getenv("ROMA_DEVICE"), validate, &dev, why, sizeof why);
    if (r != ROMA_SUCCESS) {
        /* No device offers the extensions: the reason names the device and what it lacks. */
        printf("hardware ray tracing skipped: %s\n", why);
        CHECK(r == ROMA_ERROR_MISSING_FEATURE && dev == NULL);
        CHECK(strstr(why, "offers no VK_KHR_") != NULL || strstr(why, "lacks") != NULL ||
              strstr(why, "not 1.3") != NULL);
    }
    if (r == ROMA_SUCCESS) {
        printf("hardware ray tracing on this device\n");
        roma_context_desc cd = {.external = roma_hwrt_device_external(dev)};
        CHECK_RESULT(roma_context_create(&cd, &rm.ctx), ROMA_SUCCESS);
        if (rm.ctx && rm.scene && rm.ref) {
            trace_against_embree(dev, &rm);
            depth_layers_against_embree(dev, &rm);
        }
        roma_context_destroy(rm.ctx);
        CHECK(roma_hwrt_device_destroy(dev) == 0); /* no validation error in its whole life */
    }
    roma_ref_destroy(rm.ref);
    roma_scene_destroy(rm.scene);
    return roma_test_finish("test_hw_ray_tracing");
}
