/* roma-bench --cascades: a dynamic AO frame on a level, ROMA's cascade levels and public AO
 * effect against Embree (level_frame.h). roma-bench plays the engine: it owns the G-buffer
 * images and records the build and the effect into its own command buffer. */
#include "level_frame.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "app_image.h"
#include "frame.h"
#include "reference.h"
#include "roma/ao_effect.h"
#include "roma/builtin_scenes.h"
#include "roma/map.h"
#include "vulkan/vk_internal.h"

#define W 160u
#define H 120u
#define SEED 7u

/* The engine's side: the G-buffer (position, shading and geometric normal) of Embree's camera
 * rays on the level, uploaded once; the AO output; the points for Embree's side. */
typedef struct level_gbuffer {
    app_image in[3], out;
    roma_buffer staging, readback;
    roma_gbuffer_pixel *px;
    uint32_t *covered, count;
} level_gbuffer;

static void gbuffer_destroy(roma_context *ctx, level_gbuffer *g)
{
    for (int i = 0; i < 3; ++i)
        app_image_destroy(ctx, &g->in[i]);
    app_image_destroy(ctx, &g->out);
    roma_buffer_destroy(ctx, &g->staging);
    roma_buffer_destroy(ctx, &g->readback);
    free(g->px);
    free(g->covered);
    memset(g, 0, sizeof *g);
}

static int gbuffer_create(roma_context *ctx, const roma_ref *ref, const roma_camera *camera, level_gbuffer *g)
{
    memset(g, 0, sizeof *g);
    const uint32_t n = W * H;
    roma_camera_frame cam;
    g->px = calloc(n, sizeof *g->px);
    g->covered = calloc(n, sizeof *g->covered);
    if (!g->px || !g->covered || !roma_camera_make_frame(camera, W, H, &cam) ||
        roma_buffer_create(ctx, 48ull * n, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, ROMA_MEMORY_UPLOAD, &g->staging) !=
            ROMA_SUCCESS ||
        roma_buffer_create(ctx, 4ull * n, VK_BUFFER_USAGE_TRANSFER_DST_BIT, ROMA_MEMORY_READBACK, &g->readback) !=
            ROMA_SUCCESS)
        return 0;
    float *host = g->staging.mapped;
    for (uint32_t p = 0; p < n; ++p) {
        float o[3], d[3];
        roma_ref_hit hit;
        roma_camera_ray(&cam, (float)(p % W) + 0.5f, (float)(p / W) + 0.5f, o, d);
        const int covered = roma_ref_intersect(ref, o, d, 0.0f, INFINITY, &hit);
        for (int a = 0; a < 3; ++a) {
            host[4 * p + a] = g->px[p].position_t[a] = covered ? hit.position[a] : 0.0f;
            host[4 * (n + p) + a] = g->px[p].shading_normal[a] = covered ? hit.shading_normal[a] : 0.0f;
            host[4 * (2 * n + p) + a] = g->px[p].geometric_normal[a] = covered ? hit.geometric_normal[a] : 0.0f;
        }
        host[4 * p + 3] = covered ? 1.0f : 0.0f;
        host[4 * (n + p) + 3] = host[4 * (2 * n + p) + 3] = 0.0f;
        g->px[p].position_t[3] = covered ? 1.0f : INFINITY;
        if (covered)
            g->covered[g->count++] = p;
    }
    for (int i = 0; i < 3; ++i)
        if (app_image_create(ctx, W, H, VK_FORMAT_R32G32B32A32_SFLOAT,
                             VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, &g->in[i]) != ROMA_SUCCESS)
            return 0;
    if (app_image_create(ctx, W, H, VK_FORMAT_R32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                         &g->out) != ROMA_SUCCESS)
        return 0;
    VkCommandBuffer cmd;
    if (roma_begin_one_shot(ctx, &cmd) != ROMA_SUCCESS)
        return 0;
    for (int i = 0; i < 3; ++i) {
        app_image_barrier(cmd, g->in[i].image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        const VkBufferImageCopy copy = {.bufferOffset = 16ull * n * (VkDeviceSize)i,
                                        .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                        .imageExtent = {W, H, 1}};
        vkCmdCopyBufferToImage(cmd, g->staging.buffer, g->in[i].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
        app_image_barrier(cmd, g->in[i].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
               VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
               VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    }
    app_image_barrier(cmd, g->out.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_NONE, 0,
           VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    return roma_submit_one_shot(ctx, cmd) == ROMA_SUCCESS;
}

/* One submission, submit to fence: the build (what & 1) and the AO effect (what & 2) of frame f,
 * the object moved to where frame f puts it; with `read`, the output copied back. */
typedef struct level_side {
    roma_context *ctx;
    const roma_bench_cascades_desc *d;
    const roma_scene *object;
    roma_map *map;
    uint32_t instance;
    roma_ao_effect *ao;
    level_gbuffer *g;
    float finest;
} level_side;

static double roma_ms(const level_side *s, uint32_t f, uint32_t spp, int what, int read)
{
    float t[12];
    roma_bench_object_transform(s->d, s->object, s->finest, f, t);
    if (roma_map_set_instance_transform(s->map, s->instance, t) != ROMA_SUCCESS)
        return NAN;
    VkCommandBuffer cmd;
    if (roma_begin_one_shot(s->ctx, &cmd) != ROMA_SUCCESS)
        return NAN;
    roma_result r = ROMA_SUCCESS;
    if (what & 1) {
        const roma_map_frame_desc fd = {.frame = f, .seed = SEED, .focus = s->d->camera.eye,
                                        .finest_extent = s->finest};
        r = roma_map_record_build(s->map, cmd, &fd, NULL);
    }
    if (r == ROMA_SUCCESS && (what & 2)) {
        const roma_ao_images images = {.width = W, .height = H, .position = s->g->in[0].view,
                                       .normal = s->g->in[1].view, .geometric_normal = s->g->in[2].view,
                                       .output = s->g->out.view};
        const roma_ao_settings settings = {.samples = spp, .radius = s->d->radius, .seed = SEED, .frame = f};
        r = roma_ao_effect_record(s->ao, cmd, 0, s->map, &images, &settings);
        /* the next record (or the copy) after this one's writes */
        app_image_barrier(cmd, s->g->out.image, VK_IMAGE_LAYOUT_GENERAL, read ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL
                                                                   : VK_IMAGE_LAYOUT_GENERAL,
               VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
               VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
               VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                   VK_ACCESS_2_TRANSFER_READ_BIT);
        if (read) {
            const VkBufferImageCopy copy = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                            .imageExtent = {W, H, 1}};
            vkCmdCopyImageToBuffer(cmd, s->g->out.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, s->g->readback.buffer, 1,
                                   &copy);
            app_image_barrier(cmd, s->g->out.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL,
                   VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                   VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
            roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                    VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        }
    }
    return roma_bench_submit_ms(s->ctx, cmd, r);
}

int roma_bench_level_frame(roma_context *ctx, const roma_scene *scene, const roma_bench_cascades_desc *d, FILE *csv)
{
    const uint32_t runs = d->runs ? d->runs : 5, frames = d->frames;
    level_side s = {.ctx = ctx, .d = d, .finest = roma_app_finest_extent(d->resolution, d->radius)};
    level_gbuffer g;
    memset(&g, 0, sizeof g);
    s.g = &g;
    roma_scene *object = NULL;
    roma_ref *level_ref = NULL;
    double *samples = malloc(sizeof(double) * runs * 5 * (size_t)frames);
    uint32_t mesh = 0;
    int ok = samples && roma_scene_create_builtin("cornell", NULL, &object) == ROMA_SUCCESS &&
             roma_ref_create(scene, NULL, &level_ref) == ROMA_SUCCESS && gbuffer_create(ctx, level_ref, &d->camera, &g);
    s.object = object;
    const roma_map_desc md = {.resolution = d->resolution, .angular = 4, .cascades = d->levels};
    ok = ok && roma_map_create(ctx, &md, scene, &s.map) == ROMA_SUCCESS &&
         roma_map_add_mesh(s.map, object, &mesh) == ROMA_SUCCESS && roma_ao_effect_create(ctx, NULL, &s.ao) == ROMA_SUCCESS;
    if (ok) {
        roma_instance_desc id = {.mesh = mesh, .flags = ROMA_INSTANCE_DYNAMIC};
        roma_bench_object_transform(d, object, s.finest, 0, id.transform);
        ok = roma_map_add_instance(s.map, &id, &s.instance) == ROMA_SUCCESS;
    }
    /* The first frame, untimed: the levels' static parts and the pipelines made. */
    ok = ok && isfinite(roma_ms(&s, 0, 1, 3, 0));
    if (!ok) {
        fprintf(stderr, "roma-bench: --cascades: the level frame's setup failed\n");
    } else {
        printf("\nA dynamic AO frame on the level: the %u levels around the still camera (unjittered) with the\n"
               "object moving, and the public AO effect (radius %.3g) at the camera's %u of %u pixels; ROMA in one\n"
               "submission, host-observed (each part alone, and both); Embree: the BVH of the level with the\n"
               "object where it is, rebuilt (wall clock), and AO at the same points and samples (all cores).\n"
               "The mean of %u frames, medians of %u runs.\n\n"
               "| spp | ROMA build ms | ROMA AO ms | ROMA frame ms | Embree BVH ms | Embree AO ms | Embree frame ms "
               "| ROMA speed-up | AO mean ROMA / Embree |\n|---|---|---|---|---|---|---|---|---|\n",
               d->levels, (double)d->radius, g.count, W * H, frames, runs);
    }
    static const uint32_t spps[2] = {1, 4};
    for (int si = 0; si < 2 && ok; ++si) {
        const uint32_t spp = spps[si];
        double ref_mean = 0.0, roma_mean = 0.0;
        for (uint32_t k = 0; k < runs && ok; ++k) {
            double sum[5] = {0, 0, 0, 0, 0};
            for (uint32_t f = 0; f < frames && ok; ++f) {
                const uint32_t frame = 1 + (k * frames + f) * 3;
                sum[0] += roma_ms(&s, frame, spp, 1, 0);
                sum[1] += roma_ms(&s, frame + 1, spp, 2, 0);
                sum[2] += roma_ms(&s, frame + 2, spp, 3, f + 1 == frames);
                float t[12];
                roma_bench_object_transform(d, object, s.finest, frame + 2, t);
                roma_scene *with = roma_bench_level_with_object(scene, object, t);
                roma_ref *ref = NULL;
                const double t0 = roma_app_now_ms();
                ok = with && roma_ref_create(with, NULL, &ref) == ROMA_SUCCESS;
                sum[3] += roma_app_now_ms() - t0;
                if (ok)
                    sum[4] += roma_bench_embree_ao_ms(ref, g.px, g.covered, g.count, spp, d->radius, &ref_mean);
                roma_ref_destroy(ref);
                roma_scene_destroy(with);
            }
            for (int c = 0; c < 5; ++c)
                samples[c * runs + k] = sum[c] / frames;
            ok = ok && isfinite(sum[0] + sum[1] + sum[2]);
        }
        if (!ok)
            break;
        /* The last frame's ROMA AO (read back), for its mean beside the reference's. */
        roma_buffer_invalidate(ctx, &g.readback);
        for (uint32_t i = 0; i < g.count; ++i)
            roma_mean += ((const float *)g.readback.mapped)[g.covered[i]];
        roma_mean = g.count ? roma_mean / g.count : 0.0;
        double med[5];
        for (int c = 0; c < 5; ++c)
            med[c] = roma_app_median(samples + c * runs, (int)runs);
        const double embree_frame = med[3] + med[4];
        printf("| %u | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2fx | %.3f / %.3f |\n", spp, med[0], med[1], med[2],
               med[3], med[4], embree_frame, embree_frame / med[2], roma_mean, ref_mean);
        if (csv) {
            static const char *names[5] = {"roma_build", "roma_ao", "roma_frame", "embree_bvh", "embree_ao"};
            for (int c = 0; c < 5; ++c)
                fprintf(csv, "level_frame,%s spp %u,%u,4,%.6f,ms\n", names[c], spp, d->resolution, med[c]);
        }
    }
    if (!ok)
        fprintf(stderr, "roma-bench: --cascades: a level frame failed\n");
    roma_ao_effect_destroy(s.ao);
    roma_map_destroy(s.map);
    gbuffer_destroy(ctx, &g);
    roma_ref_destroy(level_ref);
    roma_scene_destroy(object);
    free(samples);
    return ok ? 0 : 1;
}
