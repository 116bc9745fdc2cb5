/* roma_pixel_list: the covered pixels listed once and shared by the frame's effects. On the
 * built-in room (area light and spot) seen from its camera, with Embree's primary hits as the
 * engine's G-buffer, AO, direct light and GI recorded over one shared list write, on every
 * covered pixel, the bits each effect writes over the list it makes itself, and leave every
 * other pixel as it was (a sentinel cleared in before); a later frame of the slot reuses the
 * list without recording it again (a still camera), also at a resolution divisor of 2 (which
 * traces a list of its own and upsamples the rest). Synchronization validation is on, so a
 * missing barrier between the list and the effects fails. Misuse: a slot the list was not
 * recorded in, images of another size, a list of another context, a fifth record in one
 * frame, bad arguments. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gbuffer_images.h"
#include "harness.h"
#include "reference.h"
#include "roma/ao_effect.h"
#include "roma/builtin_scenes.h"
#include "roma/gi_effect.h"
#include "roma/light_effect.h"
#include "roma/map.h"
#include "roma/pixel_list.h"

#define W 40
#define H 30
#define SENTINEL 7.0f

enum { OUT_AO, OUT_DIRECT, OUT_GI, OUTPUTS };

typedef struct effects {
    roma_ao_effect *ao;
    roma_light_effect *light;
    roma_gi_effect *gi;
} effects;

/* The engine's side: the G-buffer inputs and a command buffer (gbuffer_images.h), and three
 * outputs that can be cleared to the sentinel, read back into a staging buffer of their own. */
typedef struct frame_objects {
    roma_context *ctx;
    roma_test_gbuffer g;
    VkCommandBuffer cmd;
    roma_test_image out[OUTPUTS];
    roma_test_staging staging;
    VkDeviceSize plane; /* W * H * 16 bytes: one RGBA32F image */
} frame_objects;

static void create_effects(roma_context *ctx, const roma_scene *scene, roma_pixel_dispatch dispatch, effects *e)
{
    CHECK_RESULT(roma_ao_effect_create(ctx, &(roma_ao_effect_desc){.pixel_dispatch = dispatch}, &e->ao), ROMA_SUCCESS);
    CHECK_RESULT(roma_light_effect_create(ctx, &(roma_light_effect_desc){.pixel_dispatch = dispatch}, &e->light),
                 ROMA_SUCCESS);
    CHECK_RESULT(roma_light_effect_set_area_lights(e->light, scene), ROMA_SUCCESS);
    CHECK_RESULT(roma_gi_effect_create(ctx, &(roma_gi_effect_desc){.pixel_dispatch = dispatch}, &e->gi), ROMA_SUCCESS);
    CHECK_RESULT(roma_gi_effect_set_scene(e->gi, scene), ROMA_SUCCESS);
}

static void destroy_effects(effects *e)
{
    roma_gi_effect_destroy(e->gi);
    roma_light_effect_destroy(e->light);
    roma_ao_effect_destroy(e->ao);
}

/* Begins the command buffer (the first time with the G-buffer's upload). */
static void begin(frame_objects *f) { f->cmd = roma_test_gbuffer_begin(&f->g); }

/* The outputs cleared to the sentinel, then in GENERAL for the effects' storage writes. */
static void clear_outputs(frame_objects *f)
{
    const VkClearColorValue sentinel = {.float32 = {SENTINEL, SENTINEL, SENTINEL, SENTINEL}};
    const VkImageSubresourceRange all = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    for (int i = 0; i < OUTPUTS; ++i) {
        roma_test_layout_barrier(f->cmd, f->out[i].image, VK_IMAGE_LAYOUT_UNDEFINED,
                                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                 VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT,
                                 VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        vkCmdClearColorImage(f->cmd, f->out[i].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &sentinel, 1, &all);
        roma_test_layout_barrier(f->cmd, f->out[i].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                 VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_CLEAR_BIT,
                                 VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                 VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    }
}

/* AO, direct light and GI of frame n over the images (pixels: the shared list or NULL), the
 * outputs read back into the staging buffer; submits and waits. */
static void record_effects(frame_objects *f, const effects *e, const roma_map *map, const roma_scene_view *sv,
                           const roma_pixel_list *pixels, uint32_t n, uint32_t divisor)
{
    roma_ao_images ai = roma_test_gbuffer_ao_images(&f->g);
    ai.output = f->out[OUT_AO].view;
    ai.pixels = pixels;
    roma_light_images li = roma_test_gbuffer_light_images(&f->g);
    li.output = f->out[OUT_DIRECT].view;
    li.pixels = pixels;
    roma_light_images gi = li;
    gi.output = f->out[OUT_GI].view;
    CHECK_RESULT(roma_ao_effect_record(e->ao, f->cmd, 0, map, &ai,
                                       &(roma_ao_settings){.samples = 4, .radius = 0.5f, .seed = 3, .frame = n,
                                                           .resolution_divisor = divisor}),
                 ROMA_SUCCESS);
    CHECK_RESULT(roma_light_effect_record(e->light, f->cmd, 0, map, &li, sv->lights, sv->light_count,
                                          &(roma_light_settings){.area_samples = 2, .seed = 3, .frame = n,
                                                                 .resolution_divisor = divisor}),
                 ROMA_SUCCESS);
    CHECK_RESULT(roma_gi_effect_record(e->gi, f->cmd, 0, map, &gi, sv->lights, sv->light_count,
                                       &(roma_gi_settings){.samples = 2, .seed = 3, .frame = n,
                                                           .resolution_divisor = divisor}),
                 ROMA_SUCCESS);
    for (int i = 0; i < OUTPUTS; ++i) {
        roma_test_layout_barrier(f->cmd, f->out[i].image, VK_IMAGE_LAYOUT_GENERAL,
                                 VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                 VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                                 VK_ACCESS_2_TRANSFER_READ_BIT);
        VkBufferImageCopy copy = {.bufferOffset = (VkDeviceSize)i * f->plane,
                                  .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                  .imageExtent = {W, H, 1}};
        vkCmdCopyImageToBuffer(f->cmd, f->out[i].image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, f->staging.buffer, 1,
                               &copy);
    }
    roma_test_submit_and_wait(f->ctx, f->cmd);
}

/* Copies the read-back outputs (AO: 1 float a pixel; direct and GI: 4). */
static void keep_outputs(const frame_objects *f, float *ao, float *direct, float *gi)
{
    const char *base = f->staging.mapped;
    memcpy(ao, base, (size_t)W * H * 4);
    memcpy(direct, base + f->plane, (size_t)W * H * 16);
    memcpy(gi, base + 2 * f->plane, (size_t)W * H * 16);
}

/* Covered pixels bit for bit as the own lists', uncovered ones still the sentinel. */
static void compare(const char *what, const int *covered, const float *ao, const float *direct, const float *gi,
                    const float *ao_own, const float *direct_own, const float *gi_own)
{
    uint32_t differing = 0, overwritten = 0, lit = 0;
    for (uint32_t p = 0; p < W * H; ++p) {
        if (covered[p]) {
            differing += memcmp(&ao[p], &ao_own[p], 4) != 0;
            differing += memcmp(&direct[4 * p], &direct_own[4 * p], 12) != 0;
            differing += memcmp(&gi[4 * p], &gi_own[4 * p], 12) != 0;
            lit += direct[4 * p] > 0.0f;
        } else {
            overwritten += ao[p] != SENTINEL;
            for (int c = 0; c < 3; ++c)
                overwritten += (direct[4 * p + c] != SENTINEL) + (gi[4 * p + c] != SENTINEL);
        }
    }
    if (differing || overwritten)
        fprintf(stderr, "%s: %u values differ from the effects' own lists, %u uncovered values overwritten\n", what,
                differing, overwritten);
    CHECK(differing == 0);
    CHECK(overwritten == 0);
    CHECK(lit > 0); /* the comparison is not of empty images */
}

int main(void)
{
    roma_context *ctx = roma_test_context_flags(roma_test_sync_validation_flags());
    if (!ctx)
        return roma_test_finish("test_pixel_list");
    VkDevice dev = roma_context_device(ctx);
    roma_scene *scene = NULL;
    CHECK_RESULT(roma_scene_create_builtin("cornell", NULL, &scene), ROMA_SUCCESS);
    roma_ref *ref = NULL;
    CHECK_RESULT(roma_ref_create(scene, NULL, &ref), ROMA_SUCCESS);
    roma_map *map = NULL;
    CHECK_RESULT(roma_map_create(ctx, &(roma_map_desc){.resolution = 64, .angular = 4}, scene, &map), ROMA_SUCCESS);
    /* Each effect's own list, and effects over every pixel that a shared list turns to it. */
    effects own = {0}, shared = {0};
    create_effects(ctx, scene, ROMA_PIXEL_DISPATCH_LIST, &own);
    create_effects(ctx, scene, ROMA_PIXEL_DISPATCH_EVERY_PIXEL, &shared);
    roma_pixel_list *list = NULL;
    CHECK_RESULT(roma_pixel_list_create(ctx, NULL, &list), ROMA_SUCCESS);
    if (!ref || !map || !own.ao || !own.light || !own.gi || !shared.ao || !shared.light || !shared.gi || !list)
        return roma_test_finish("test_pixel_list");

    /* The engine's G-buffer: Embree's primary hits; a border of uncovered pixels besides the
     * camera's own: the room fills the view. */
    roma_scene_view sv;
    roma_scene_get_view(scene, &sv);
    frame_objects f = {.ctx = ctx, .plane = (VkDeviceSize)W * H * 16};
    if (!roma_test_gbuffer_create_bordered(ctx, ref, &sv.camera, W, H, 3, &f.g))
        return roma_test_finish("test_pixel_list");
    const int *covered = f.g.covered;
    CHECK(f.g.covered_count > W * H / 2 && f.g.covered_count < W * H);
    roma_test_staging_create(ctx, 3 * f.plane, &f.staging);
    const VkImageUsageFlags out_usage =
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    roma_test_image_create(ctx, W, H, VK_FORMAT_R32_SFLOAT, out_usage, &f.out[OUT_AO]);
    roma_test_image_create(ctx, W, H, VK_FORMAT_R32G32B32A32_SFLOAT, out_usage, &f.out[OUT_DIRECT]);
    roma_test_image_create(ctx, W, H, VK_FORMAT_R32G32B32A32_SFLOAT, out_usage, &f.out[OUT_GI]);

    /* Upload the G-buffer and build the map. */
    begin(&f);
    CHECK_RESULT(roma_map_record_build(map, f.cmd, &(roma_map_frame_desc){.seed = 5}, NULL), ROMA_SUCCESS);
    roma_test_submit_and_wait(ctx, f.cmd);

    static float ao_own[W * H], direct_own[4 * W * H], gi_own[4 * W * H];
    static float ao[W * H], direct[4 * W * H], gi[4 * W * H];
    /* Frame 2 at a resolution divisor: the effects trace their own list of one pixel a block
     * and upsample the rest, leaving the uncovered pixels as they were. */
    static const char *what[3] = {"frame 0 (list recorded)", "frame 1 (list reused)", "frame 2 (divisor 2)"};
    for (uint32_t n = 0; n < 3; ++n) {
        const uint32_t divisor = n == 2 ? 2 : 1;
        /* Each effect's own list (the background written into the uncovered pixels: the
         * comparison takes the covered ones). */
        begin(&f);
        clear_outputs(&f);
        record_effects(&f, &own, map, &sv, NULL, n, divisor);
        keep_outputs(&f, ao_own, direct_own, gi_own);
        /* One list for the three: recorded by frame 0, reused as it is by frames 1 and 2. */
        begin(&f);
        clear_outputs(&f);
        if (n == 0)
            CHECK_RESULT(roma_pixel_list_record(list, f.cmd, 0,
                                                &(roma_pixel_list_images){.width = W, .height = H,
                                                                          .position = f.g.in[0].view, .frame = n}),
                         ROMA_SUCCESS);
        record_effects(&f, &shared, map, &sv, list, n, divisor);
        keep_outputs(&f, ao, direct, gi);
        compare(what[n], covered, ao, direct, gi, ao_own, direct_own, gi_own);
    }

    /* Misuse: nothing recorded, a clear message. */
    roma_test_log log = {0};
    roma_pixel_list *logged = NULL;
    CHECK_RESULT(roma_pixel_list_create(ctx, &(roma_pixel_list_desc){.frames_in_flight = 2,
                                                                     .logger = roma_test_logger(&log)},
                                        &logged),
                 ROMA_SUCCESS);
    CHECK_RESULT(roma_pixel_list_create(ctx, &(roma_pixel_list_desc){.frames_in_flight = ROMA_MAX_FRAMES_IN_FLIGHT + 1},
                                        &(roma_pixel_list *){NULL}),
                 ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_pixel_list_create(NULL, NULL, &(roma_pixel_list *){NULL}), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_pixel_list_create(ctx, NULL, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    begin(&f);
    roma_pixel_list_images li = {.width = W, .height = H, .position = f.g.in[0].view, .frame = 9};
    CHECK_RESULT(roma_pixel_list_record(NULL, f.cmd, 0, &li), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_pixel_list_record(logged, f.cmd, 0, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_pixel_list_record(logged, f.cmd, 2, &li), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_pixel_list_record(logged, f.cmd, 0, &(roma_pixel_list_images){.width = W, .height = H}),
                 ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_pixel_list_record(logged, f.cmd, 0,
                                        &(roma_pixel_list_images){.width = 1u << 30, .height = 1u << 30,
                                                                  .position = f.g.in[0].view}),
                 ROMA_ERROR_INVALID_ARGUMENT);
    /* An effect of a slot the list holds nothing for, and images of another size. */
    roma_ao_images ai = {.width = W, .height = H, .position = f.g.in[0].view, .normal = f.g.in[1].view,
                         .output = f.out[OUT_AO].view, .pixels = logged};
    CHECK_RESULT(roma_ao_effect_record(shared.ao, f.cmd, 0, map, &ai, &(roma_ao_settings){.frame = 9}),
                 ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_pixel_list_record(logged, f.cmd, 0, &li), ROMA_SUCCESS);
    ai.width = W - 1;
    CHECK_RESULT(roma_ao_effect_record(shared.ao, f.cmd, 0, map, &ai, &(roma_ao_settings){.frame = 9}),
                 ROMA_ERROR_INVALID_ARGUMENT);
    /* A list of another context. */
    roma_context *other_ctx = roma_test_context();
    roma_pixel_list *other = NULL;
    if (other_ctx)
        CHECK_RESULT(roma_pixel_list_create(other_ctx, NULL, &other), ROMA_SUCCESS);
    if (other) {
        ai.width = W;
        ai.pixels = other;
        CHECK_RESULT(roma_ao_effect_record(shared.ao, f.cmd, 0, map, &ai, &(roma_ao_settings){.frame = 9}),
                     ROMA_ERROR_INVALID_ARGUMENT);
        ai.pixels = logged;
    }
    roma_pixel_list_destroy(other);
    if (other_ctx)
        roma_test_context_finish(other_ctx);
    CHECK_RESULT(roma_pixel_list_record(logged, f.cmd, UINT32_MAX, &li), ROMA_ERROR_INVALID_ARGUMENT);
    /* Four records in one frame of a slot, not five. */
    for (int i = 0; i < 3; ++i)
        CHECK_RESULT(roma_pixel_list_record(logged, f.cmd, 0, &li), ROMA_SUCCESS);
    CHECK_RESULT(roma_pixel_list_record(logged, f.cmd, 0, &li), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(log.last, "more than 4 records") != NULL);
    vkEndCommandBuffer(f.cmd);
    CHECK(log.errors >= 3);

    roma_pixel_list_destroy(logged);
    roma_pixel_list_destroy(list);
    roma_pixel_list_destroy(NULL);
    destroy_effects(&shared);
    destroy_effects(&own);
    roma_test_gbuffer_destroy(ctx, &f.g);
    for (int i = 0; i < OUTPUTS; ++i)
        roma_test_image_destroy(dev, &f.out[i]);
    roma_test_staging_destroy(dev, &f.staging);
    roma_map_destroy(map);
    roma_ref_destroy(ref);
    roma_scene_destroy(scene);
    roma_test_context_finish(ctx);
    return roma_test_finish("test_pixel_list");
}
