/* Misuse of every public entry point: NULL handles and out-pointers, zero and
 * oversized sizes, enums out of range, mismatched buffers and objects. Each call
 * must return its exact code, log one error naming the bad parameter where a
 * logger is reachable, leave its outputs NULL or zeroed, and leave the objects
 * involved usable. Cases already asserted by test_map_api, test_scene_builder,
 * test_image, test_context and test_effect_plan are not repeated. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "roma/builtin_scenes.h"
#include "roma/effects.h"
#include "roma/gltf.h"
#include "roma/image.h"
#include "roma/map.h"

static int sentinel_storage;
#define SENTINEL ((void *)&sentinel_storage)

/* `expr` returns `code` and logs exactly one error containing `word`. */
static void expect_fail(roma_result got, roma_result code, roma_test_log *log, int errors_before,
                        const char *word, const char *what, int line)
{
    /* One error, logged with the code the call returned; the message names the problem
     * for the person who reads it. */
    int logged = log->errors - errors_before;
    if (got != code || logged != 1 || log->last_code != code || !strstr(log->last, word)) {
        fprintf(stderr, "line %d: %s gave '%s' with %d error(s), last \"%s\" ('%s'); expected '%s' naming '%s'\n",
                line, what, roma_result_string(got), logged, log->last, roma_result_string(log->last_code),
                roma_result_string(code), word);
        ++roma_test_failures;
    }
}
#define FAILS(expr, code, log, word)                                                          \
    do {                                                                                      \
        int before_ = (log)->errors;                                                          \
        expect_fail((expr), (code), (log), before_, (word), #expr, __LINE__);                 \
    } while (0)

static int all_zero(const void *p, size_t n)
{
    const unsigned char *b = p;
    for (size_t i = 0; i < n; ++i)
        if (b[i])
            return 0;
    return 1;
}

/* --- no GPU ------------------------------------------------------------------------- */

static void test_camera(void)
{
    roma_camera cam = {{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 60.0f};
    roma_camera_frame f;
    CHECK(!roma_camera_make_frame(&cam, 8, 8, NULL)); /* used to write through NULL */
    memset(&f, 0xab, sizeof f);
    CHECK(!roma_camera_make_frame(NULL, 8, 8, &f) && all_zero(&f, sizeof f));
    roma_camera bad = cam;
    bad.fovy_deg = 180.0f;
    CHECK(!roma_camera_make_frame(&bad, 8, 8, &f));
    bad.fovy_deg = -10.0f;
    CHECK(!roma_camera_make_frame(&bad, 8, 8, &f));
    bad.fovy_deg = NAN;
    CHECK(!roma_camera_make_frame(&bad, 8, 8, &f) && all_zero(&f, sizeof f));
    bad = cam;
    bad.up[2] = INFINITY;
    CHECK(!roma_camera_make_frame(&bad, 8, 8, &f));

    /* A zeroed frame (what a failed make_frame leaves) gives zero vectors, not NaN. */
    float o[3] = {1, 1, 1}, d[3] = {1, 1, 1};
    roma_camera_ray(&f, 4.0f, 4.0f, o, d);
    CHECK(all_zero(o, sizeof o) && all_zero(d, sizeof d));
    o[0] = d[0] = 1.0f;
    roma_camera_ray(NULL, 4.0f, 4.0f, o, d);
    CHECK(o[0] == 0.0f && d[0] == 0.0f);
    CHECK(roma_camera_make_frame(&cam, 100000, 100000, &f)); /* no allocation: any size works */
    roma_camera_ray(&f, 50000.0f, 50000.0f, NULL, d);
    roma_camera_ray(&f, 50000.0f, 50000.0f, o, NULL);
    roma_camera_ray(&f, 50000.0f, 50000.0f, o, d);
    CHECK_NEAR(d[2], -1.0, 1e-6);

    const float bmin[3] = {-1, -1, -1}, bmax[3] = {1, 1, 1}, binf[3] = {-INFINITY, 0, 0};
    roma_camera out;
    memset(&out, 0xab, sizeof out);
    roma_camera_frame_bounds(NULL, bmax, 1.0f, &out);
    CHECK(all_zero(&out, sizeof out));
    roma_camera_frame_bounds(bmin, NULL, 1.0f, &out);
    CHECK(all_zero(&out, sizeof out));
    roma_camera_frame_bounds(binf, bmax, 1.0f, &out);
    CHECK(all_zero(&out, sizeof out) && !roma_camera_make_frame(&out, 8, 8, &f));
    roma_camera_frame_bounds(bmin, bmax, 1.0f, NULL);
    const float aspects[] = {0.0f, -1.0f, NAN, INFINITY};
    for (size_t i = 0; i < sizeof aspects / sizeof aspects[0]; ++i) {
        roma_camera_frame_bounds(bmin, bmax, aspects[i], &out);
        CHECK(roma_camera_make_frame(&out, 8, 8, &f));
    }
}

static void test_image(void)
{
    roma_image img;
    memset(&img, 0xab, sizeof img);
    /* 2^31 x 2^31 floats is 2^64 bytes: the byte count wrapped to 0 and passed. */
    CHECK_RESULT(roma_image_alloc(&img, 1u << 31, 1u << 31, 1), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(all_zero(&img, sizeof img));
    CHECK_RESULT(roma_image_alloc(&img, 65536, 65536, 1), ROMA_ERROR_INVALID_ARGUMENT); /* 16 GiB */
    CHECK_RESULT(roma_image_alloc(&img, UINT32_MAX, UINT32_MAX, 3), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_image_alloc(&img, 4, 0, 1), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_image_alloc(&img, 4, 4, 0), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_image_alloc(NULL, 4, 4, 1), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(img.pixels == NULL);

    char path[512], dir[512];
    roma_test_tmp_path("misuse_huge.pfm", path, sizeof path);
    FILE *fp = fopen(path, "wb");
    if (fp) {
        fputs("Pf\n2147483648 2147483648\n-1.0\n", fp); /* same wrap, from a file header */
        fclose(fp);
    }
    memset(&img, 0xab, sizeof img);
    CHECK_RESULT(roma_image_read_pfm(path, &img), ROMA_ERROR_PARSE);
    CHECK(all_zero(&img, sizeof img));
    roma_test_tmp_path("", dir, sizeof dir); /* the scratch directory itself */
    CHECK_RESULT(roma_image_read_pfm(dir, &img), ROMA_ERROR_IO);
    CHECK(img.pixels == NULL);
    CHECK_RESULT(roma_image_read_pfm(NULL, &img), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_image_read_pfm(path, NULL), ROMA_ERROR_INVALID_ARGUMENT);

    roma_image a, b, c3, mask3, mask_small, empty = {0};
    CHECK_RESULT(roma_image_alloc(&a, 4, 2, 1), ROMA_SUCCESS);
    CHECK_RESULT(roma_image_alloc(&b, 4, 2, 1), ROMA_SUCCESS);
    CHECK_RESULT(roma_image_alloc(&c3, 4, 2, 3), ROMA_SUCCESS);
    CHECK_RESULT(roma_image_alloc(&mask3, 4, 2, 3), ROMA_SUCCESS);
    CHECK_RESULT(roma_image_alloc(&mask_small, 2, 2, 1), ROMA_SUCCESS);
    if (!a.pixels || !b.pixels || !c3.pixels || !mask3.pixels || !mask_small.pixels)
        goto done;
    for (int i = 0; i < 8; ++i) {
        a.pixels[i] = (float)i;
        b.pixels[i] = (float)i + (i == 3 ? 0.5f : 0.0f);
    }

    CHECK_RESULT(roma_image_write_pfm(NULL, path), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_image_write_pfm(&a, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_image_write_pfm(&empty, path), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_image_write_pfm(&a, dir), ROMA_ERROR_IO);

    roma_image_metrics m;
    memset(&m, 0xab, sizeof m);
    CHECK_RESULT(roma_image_compare(NULL, &b, NULL, 0.1f, &m), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(all_zero(&m, sizeof m));
    CHECK_RESULT(roma_image_compare(&a, &b, NULL, 0.1f, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_image_compare(&a, &empty, NULL, 0.1f, &m), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_image_compare(&a, &b, &mask3, 0.1f, &m), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_image_compare(&a, &b, &mask_small, 0.1f, &m), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_image_compare(&a, &b, &empty, 0.1f, &m), ROMA_ERROR_INVALID_ARGUMENT);
    /* A NaN tolerance counted no pixel as above it: a silent pass. */
    CHECK_RESULT(roma_image_compare(&a, &b, NULL, NAN, &m), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(all_zero(&m, sizeof m));

    roma_image diff;
    memset(&diff, 0xab, sizeof diff);
    CHECK_RESULT(roma_image_abs_diff(&a, &c3, &diff), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(all_zero(&diff, sizeof diff));
    CHECK_RESULT(roma_image_abs_diff(NULL, &b, &diff), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_image_abs_diff(&a, &b, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    /* Output aliasing an input: the input was zeroed (pixels leaked) before being read. */
    CHECK_RESULT(roma_image_abs_diff(&a, &b, &a), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_image_abs_diff(&a, &b, &b), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(a.pixels && a.width == 4 && a.pixels[7] == 7.0f && b.pixels && b.pixels[3] == 3.5f);

    /* Everything still compares. */
    CHECK_RESULT(roma_image_compare(&a, &b, NULL, 0.1f, &m), ROMA_SUCCESS);
    CHECK(m.pixel_count == 8 && m.fraction_above == 1.0 / 8.0);
    CHECK_RESULT(roma_image_abs_diff(&a, &b, &diff), ROMA_SUCCESS);
    CHECK(diff.pixels && diff.pixels[3] == 0.5f);
    roma_image_free(&diff);
    roma_image_free(&empty);
done:
    roma_image_free(&a);
    roma_image_free(&b);
    roma_image_free(&c3);
    roma_image_free(&mask3);
    roma_image_free(&mask_small);
}

static void test_scene(roma_scene *scene)
{
    roma_test_log log;
    roma_logger logger = roma_test_logger(&log);

    roma_scene_view v;
    memset(&v, 0xab, sizeof v);
    CHECK_RESULT(roma_scene_get_view(NULL, &v), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(all_zero(&v, sizeof v));
    CHECK_RESULT(roma_scene_get_view(scene, NULL), ROMA_ERROR_INVALID_ARGUMENT);

    roma_scene *s = SENTINEL;
    FAILS(roma_scene_create_builtin("", &logger, &s), ROMA_ERROR_INVALID_ARGUMENT, &log, "''");
    CHECK(s == NULL);
    CHECK(roma_builtin_scene_names() && roma_builtin_scene_names()[0]);

    /* vertex_count 0 with arrays present: every index is out of range. */
    const float pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t idx[] = {0, 1, 2};
    roma_scene_desc d = {.positions = pos, .vertex_count = 0, .indices = idx, .triangle_count = 1,
                         .name = "tri", .logger = logger};
    s = SENTINEL;
    FAILS(roma_scene_create(&d, &s), ROMA_ERROR_INVALID_SCENE, &log, "vertex");
    CHECK(s == NULL);
    d.vertex_count = 3;
    roma_light light = {.type = (roma_light_type)99, .color = {1, 1, 1}, .intensity = 1.0f};
    d.lights = &light;
    d.light_count = 1;
    s = SENTINEL;
    FAILS(roma_scene_create(&d, &s), ROMA_ERROR_INVALID_SCENE, &log, "type");
    CHECK(s == NULL);

    /* Animation channels with enums out of range; the scene keeps working. */
    roma_scene_node node = {-1, -1, {0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1},
                            {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}};
    roma_scene_anim_channel ch = {0, 0, ROMA_ANIM_TRANSLATION, ROMA_ANIM_LINEAR, 1, 3, 0, 0};
    float times[1] = {0.0f}, values[4] = {0};
    roma_scene_animation_data a = {.nodes = &node, .node_count = 1, .channels = &ch, .channel_count = 1,
                                   .animation_count = 1, .times = times, .values = values};
    roma_scene_view sv;
    roma_scene_get_view(scene, &sv);
    const roma_scene_node *kept = sv.animation.nodes;
    ch.path = (roma_anim_path)9;
    FAILS(roma_scene_set_animation_data(scene, &a, &logger), ROMA_ERROR_INVALID_SCENE, &log, "path");
    ch.path = (roma_anim_path)0;
    FAILS(roma_scene_set_animation_data(scene, &a, &logger), ROMA_ERROR_INVALID_SCENE, &log, "path");
    ch.path = ROMA_ANIM_TRANSLATION;
    ch.interpolation = (roma_anim_interp)-1;
    FAILS(roma_scene_set_animation_data(scene, &a, &logger), ROMA_ERROR_INVALID_SCENE, &log, "interpolation");
    ch.interpolation = (roma_anim_interp)3;
    FAILS(roma_scene_set_animation_data(scene, &a, &logger), ROMA_ERROR_INVALID_SCENE, &log, "interpolation");
    ch.interpolation = ROMA_ANIM_LINEAR;
    /* Skinned vertices without their joints and weights (the animator would read NULL). */
    roma_scene_skin skin = {.first_joint = 0, .joint_count = 1};
    uint32_t joint = 0;
    float bind[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    int32_t *skinned = calloc(sv.vertex_count ? sv.vertex_count : 1, sizeof *skinned);
    roma_scene_animation_data b = a;
    b.skins = &skin, b.skin_count = 1, b.joint_nodes = &joint, b.inverse_binds = bind, b.joint_total = 1;
    b.vertex_skin = skinned;
    if (skinned)
        FAILS(roma_scene_set_animation_data(scene, &b, &logger), ROMA_ERROR_INVALID_SCENE, &log,
              "joints or weights are missing");
    free(skinned);
    CHECK_RESULT(roma_scene_set_animation_data(scene, NULL, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    roma_scene_get_view(scene, &sv);
    CHECK(sv.animation.nodes == kept && sv.triangle_count > 0);

    roma_camera cam;
    roma_scene_default_camera(scene, 1.0f, NULL);
    roma_scene_default_camera(scene, NAN, &cam);
    roma_camera_frame f;
    CHECK(roma_camera_make_frame(&cam, 8, 8, &f));
}

static void test_effects(roma_scene *scene)
{
    roma_test_log log;
    roma_logger logger = roma_test_logger(&log);
    roma_effect_plan p;
    roma_effect_options bad[] = {
        {.effects = ROMA_EFFECT_GI, .gi_angular = 17},
        {.effects = ROMA_EFFECT_DIRECT, .shadow_angular = 17},
        {.effects = ROMA_EFFECT_LIGHTS, .lights_angular = UINT32_MAX},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        memset(&p, 0xab, sizeof p);
        FAILS(roma_effect_plan_derive(scene, &bad[i], &logger, &p), ROMA_ERROR_INVALID_ARGUMENT, &log, "angular");
        CHECK(p.effects == 0 && p.passes == 0 && p.map_count == 0 && p.many_light_count == 0);
        for (int k = 0; k < ROMA_PASS_COUNT; ++k)
            CHECK(p.pass_map[k] == -1 && !roma_effect_plan_runs(&p, (roma_pass_kind)k));
    }
    roma_effect_options lights = {.effects = ROMA_EFFECT_LIGHTS, .many_light_count = 65537};
    FAILS(roma_effect_plan_derive(scene, &lights, &logger, &p), ROMA_ERROR_INVALID_ARGUMENT, &log, "many lights");
    FAILS(roma_effect_plan_derive(scene, NULL, &logger, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "out_plan");
    lights.many_light_count = 65536;
    CHECK_RESULT(roma_effect_plan_derive(scene, &lights, &logger, &p), ROMA_SUCCESS);
    CHECK(roma_effect_plan_runs(&p, ROMA_PASS_MANY_LIGHTS) && p.many_light_count == 65536);
    /* Out-of-range passes shifted by 32 or more (undefined); a NULL plan was dereferenced. */
    CHECK(!roma_effect_plan_runs(&p, (roma_pass_kind)40));
    CHECK(!roma_effect_plan_runs(&p, (roma_pass_kind)-1));
    CHECK(!roma_effect_plan_runs(&p, ROMA_PASS_COUNT));
    CHECK(!roma_effect_plan_runs(NULL, ROMA_PASS_GBUFFER));
    CHECK(strcmp(roma_pass_name((roma_pass_kind)-1), "unknown") == 0);
    CHECK(strcmp(roma_pass_name(ROMA_PASS_COUNT), "unknown") == 0);
    CHECK(strcmp(roma_log_level_string((roma_log_level)99), "unknown") == 0);
}

static void test_gltf(void)
{
    roma_test_log log;
    roma_gltf_desc desc = {.logger = roma_test_logger(&log)};
    char dir[512];
    roma_test_tmp_path("", dir, sizeof dir);
    roma_scene *s = SENTINEL;
    FAILS(roma_scene_load_gltf(dir, &desc, &s), ROMA_ERROR_IO, &log, dir); /* a directory */
    CHECK(s == NULL);
    s = SENTINEL;
    FAILS(roma_scene_load_gltf("", &desc, &s), ROMA_ERROR_FILE_NOT_FOUND, &log, "cannot open");
    CHECK(s == NULL);
    s = SENTINEL;
    FAILS(roma_scene_load_gltf_memory("{}", 0, NULL, &desc, &s), ROMA_ERROR_PARSE, &log, "empty");
    CHECK(s == NULL);
    FAILS(roma_scene_load_gltf_memory(NULL, 0, NULL, &desc, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "out_scene");
    s = SENTINEL;
    CHECK_RESULT(roma_scene_load_gltf_memory("not json", 8, NULL, NULL, &s), ROMA_ERROR_PARSE); /* NULL desc */
    CHECK(s == NULL);
}

/* --- GPU ---------------------------------------------------------------------------- */

typedef struct gpu {
    roma_context *ctx;
    VkDevice device;
    VkCommandPool pool;
} gpu;

static VkCommandBuffer begin_cmd(gpu *g)
{
    VkCommandBufferAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
        .commandPool = g->pool,
        .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
        .commandBufferCount = 1,
    };
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    if (vkAllocateCommandBuffers(g->device, &alloc, &cmd) != VK_SUCCESS)
        return VK_NULL_HANDLE;
    VkCommandBufferBeginInfo begin = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                      .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    vkBeginCommandBuffer(cmd, &begin);
    return cmd;
}

/* Ends cmd and, if submit, runs it to completion; frees it either way. */
static void end_cmd(gpu *g, VkCommandBuffer cmd, int submit)
{
    CHECK(vkEndCommandBuffer(cmd) == VK_SUCCESS);
    if (submit) {
        VkSubmitInfo info = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1,
                             .pCommandBuffers = &cmd};
        CHECK(vkQueueSubmit(roma_context_queue(g->ctx), 1, &info, VK_NULL_HANDLE) == VK_SUCCESS);
        vkQueueWaitIdle(roma_context_queue(g->ctx));
    }
    vkFreeCommandBuffers(g->device, g->pool, 1, &cmd);
}

static void test_context(gpu *g, roma_context *logged, roma_test_log *log)
{
    roma_test_log own;
    roma_context_desc desc = {.flags = ROMA_CONTEXT_VALIDATION | (1u << 7), .logger = roma_test_logger(&own)};
    roma_context *c = SENTINEL;
    FAILS(roma_context_create(&desc, &c), ROMA_ERROR_INVALID_ARGUMENT, &own, "flags");
    CHECK(c == NULL);
    roma_device_requirements req;
    roma_get_device_requirements(&req);
    roma_external_device ext = {roma_context_instance(g->ctx), roma_context_physical_device(g->ctx),
                                roma_context_device(g->ctx), roma_context_queue_family(g->ctx), VK_NULL_HANDLE,
                                &req.features};
    roma_context_desc ext_desc = {.external = &ext, .logger = desc.logger};
    c = SENTINEL;
    FAILS(roma_context_create(&ext_desc, &c), ROMA_ERROR_INVALID_ARGUMENT, &own, "queue");
    CHECK(c == NULL);

    roma_context_info info;
    memset(&info, 0xab, sizeof info);
    CHECK_RESULT(roma_context_get_info(NULL, &info), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(all_zero(&info, sizeof info));
    FAILS(roma_context_get_info(logged, NULL), ROMA_ERROR_INVALID_ARGUMENT, log, "out_info");
    CHECK(roma_context_validation_error_count(NULL) == 0);
    CHECK(roma_context_instance(NULL) == VK_NULL_HANDLE && roma_context_physical_device(NULL) == VK_NULL_HANDLE);
    CHECK(roma_context_device(NULL) == VK_NULL_HANDLE && roma_context_queue(NULL) == VK_NULL_HANDLE);
    CHECK(roma_context_queue_family(NULL) == UINT32_MAX);
    double ms = 5.0;
    CHECK_RESULT(roma_context_self_test(NULL, &ms), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(ms == 0.0);

    /* Timers. */
    roma_gpu_timer *t = SENTINEL;
    FAILS(roma_gpu_timer_create(logged, 4097, &t), ROMA_ERROR_INVALID_ARGUMENT, log, "scopes");
    CHECK(t == NULL);
    t = SENTINEL;
    CHECK_RESULT(roma_gpu_timer_create(NULL, 4, &t), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(t == NULL);
    FAILS(roma_gpu_timer_create(logged, 4, NULL), ROMA_ERROR_INVALID_ARGUMENT, log, "out_timer");
    CHECK_RESULT(roma_gpu_timer_create(logged, 1, &t), ROMA_SUCCESS);
    if (!t)
        return;
    roma_gpu_timing timing[2];
    uint32_t count = 2;
    CHECK_RESULT(roma_gpu_timer_read(NULL, timing, &count), ROMA_ERROR_INVALID_ARGUMENT);
    FAILS(roma_gpu_timer_read(t, timing, NULL), ROMA_ERROR_INVALID_ARGUMENT, log, "count");
    FAILS(roma_gpu_timer_read(t, NULL, &count), ROMA_ERROR_INVALID_ARGUMENT, log, "out_timings");
    roma_gpu_timer_reset(NULL, VK_NULL_HANDLE);
    roma_gpu_timer_end(NULL, VK_NULL_HANDLE, 0);
    CHECK(roma_gpu_timer_begin(NULL, VK_NULL_HANDLE, "x") == UINT32_MAX);
    CHECK(roma_gpu_timer_begin(t, VK_NULL_HANDLE, "x") == UINT32_MAX);
    VkCommandBuffer cmd = begin_cmd(g);
    if (cmd) {
        roma_gpu_timer_reset(t, cmd);
        uint32_t scope = roma_gpu_timer_begin(t, cmd, NULL); /* NULL name: empty */
        CHECK(scope == 0);
        CHECK(roma_gpu_timer_begin(t, cmd, "over") == UINT32_MAX); /* max_scopes 1 */
        roma_gpu_timer_end(t, cmd, scope);
        /* A second end rewrote the query without a reset (a validation error). */
        roma_gpu_timer_end(t, cmd, scope);
        roma_gpu_timer_end(t, cmd, UINT32_MAX);
        roma_gpu_timer_end(t, cmd, 1);
        end_cmd(g, cmd, 1);
        count = 2;
        CHECK_RESULT(roma_gpu_timer_read(t, timing, &count), ROMA_SUCCESS);
        CHECK(count == 1 && timing[0].name[0] == '\0' && timing[0].milliseconds >= 0.0);
    }
    roma_gpu_timer_destroy(t);
    roma_gpu_timer_destroy(NULL);
    CHECK_RESULT(roma_context_self_test(g->ctx, &ms), ROMA_SUCCESS);
}

static uint64_t popcount_words(const uint32_t *w, uint64_t n)
{
    uint64_t c = 0;
    for (uint64_t i = 0; i < n; ++i)
        c += (uint64_t)__builtin_popcount(w[i]);
    return c;
}

/* From the middle of the closed room every direction hits a wall. */
static int traces_walls(roma_map *map)
{
    roma_ray rays[2] = {{{0.0f, 1.0f, 0.0f}, 0.0f, {0.0f, 0.0f, 1.0f}, INFINITY},
                        {{0.0f, 1.0f, 0.0f}, 0.0f, {0.3f, -0.2f, -1.0f}, INFINITY}};
    roma_hit hits[2];
    return roma_map_trace(map, ROMA_TRACE_SNAPPED_CLOSEST, 0, rays, 2, hits, NULL) == ROMA_SUCCESS &&
           (hits[0].info & ROMA_HIT_FLAG) && (hits[1].info & ROMA_HIT_FLAG) && hits[0].t > 0.0f &&
           isfinite(hits[1].t);
}

static void test_map(gpu *g, roma_context *same_device, roma_context *other_device, roma_scene *scene)
{
    roma_test_log log;
    roma_map_desc desc = {.resolution = 32, .angular = 2, .logger = roma_test_logger(&log)};
    roma_map *map = SENTINEL;
    FAILS(roma_map_create(NULL, &desc, scene, &map), ROMA_ERROR_INVALID_ARGUMENT, &log, "context");
    CHECK(map == NULL);
    map = SENTINEL;
    FAILS(roma_map_create(g->ctx, &desc, NULL, &map), ROMA_ERROR_INVALID_ARGUMENT, &log, "scene");
    CHECK(map == NULL);
    FAILS(roma_map_create(g->ctx, &desc, scene, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "out_map");
    roma_map_desc bad = desc;
    bad.margin_cells = NAN;
    map = SENTINEL;
    FAILS(roma_map_create(g->ctx, &bad, scene, &map), ROMA_ERROR_INVALID_ARGUMENT, &log, "margin_cells");
    CHECK(map == NULL);
    bad = desc;
    bad.bom_mode = (roma_bom_mode)-1;
    FAILS(roma_map_create(g->ctx, &bad, scene, &map), ROMA_ERROR_INVALID_ARGUMENT, &log, "bom_mode");
    bad = desc;
    bad.angular = UINT32_MAX;
    FAILS(roma_map_create(g->ctx, &bad, scene, &map), ROMA_ERROR_INVALID_ARGUMENT, &log, "angular");
    bad = desc;
    bad.resolution = UINT32_MAX;
    FAILS(roma_map_create(g->ctx, &bad, scene, &map), ROMA_ERROR_INVALID_ARGUMENT, &log, "resolution");
    /* Powers of two and multiples of 32 that the maps do not support. */
    const uint32_t unsupported[] = {16, 48, 512};
    for (int i = 0; i < 3; ++i) {
        bad.resolution = unsupported[i];
        FAILS(roma_map_create(g->ctx, &bad, scene, &map), ROMA_ERROR_INVALID_ARGUMENT, &log, "resolution");
    }
    bad = desc;
    bad.angular = 17; /* A goes up to 16 */
    FAILS(roma_map_create(g->ctx, &bad, scene, &map), ROMA_ERROR_INVALID_ARGUMENT, &log, "angular");
    CHECK(map == NULL);

    /* A NULL map: no logger to reach, the code says it. */
    roma_map_frame_desc frame0 = {0};
    roma_ray ray0 = {{0.0f, 0.0f, 0.0f}, 0.0f, {1.0f, 0.0f, 0.0f}, INFINITY};
    roma_hit hit0 = {-1.0f, 0xdeadu};
    uint32_t word0 = 0xdeadu;
    CHECK_RESULT(roma_map_build(NULL, &frame0, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_map_trace(NULL, ROMA_TRACE_SNAPPED_ANY, 0, &ray0, 1, &hit0, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(hit0.t == -1.0f && hit0.info == 0xdeadu);
    CHECK_RESULT(roma_map_download_bom(NULL, &word0, 1), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(word0 == 0xdeadu);
    roma_map_destroy(NULL);

    map = NULL;
    CHECK_RESULT(roma_map_create(g->ctx, &desc, scene, &map), ROMA_SUCCESS);
    if (!map)
        return;
    roma_map_info info;
    CHECK_RESULT(roma_map_get_info(map, &info), ROMA_SUCCESS);
    const uint64_t bom_words = info.bom_bytes / 4, maps_words = info.maps_bytes / 4;
    uint32_t *words = malloc(info.maps_bytes);
    if (!words) {
        roma_map_destroy(map);
        return;
    }

    /* Before the first build: nothing to download; zero rays is still fine. */
    FAILS(roma_map_download_bom(map, words, bom_words), ROMA_ERROR_NOT_READY, &log, "built");
    FAILS(roma_map_download_maps(map, words, maps_words), ROMA_ERROR_NOT_READY, &log, "built");
    roma_ray ray = {{0.0f, 1.0f, 0.0f}, 0.0f, {1.0f, 0.0f, 0.0f}, INFINITY};
    roma_hit hit = {-1.0f, 0xdeadu};
    CHECK_RESULT(roma_map_trace(map, ROMA_TRACE_SNAPPED_ANY, 0, NULL, 0, NULL, NULL), ROMA_SUCCESS);

    /* Timers whose query pool lives on another VkDevice are refused before recording. */
    roma_gpu_timer *foreign = NULL, *shared = NULL;
    CHECK_RESULT(roma_gpu_timer_create(other_device, 4, &foreign), ROMA_SUCCESS);
    CHECK_RESULT(roma_gpu_timer_create(same_device, 4, &shared), ROMA_SUCCESS);
    roma_map_frame_desc frame = {.frame = 1, .seed = 2, .jitter_grid = 1, .jitter_directions = 1};
    if (foreign)
        FAILS(roma_map_build(map, &frame, foreign), ROMA_ERROR_INVALID_ARGUMENT, &log, "timer");
    CHECK_RESULT(roma_map_build(NULL, &frame, NULL), ROMA_ERROR_INVALID_ARGUMENT); /* no logger: stderr */

    /* A timer of another context on the same device (external mode) is fine. */
    CHECK_RESULT(roma_map_build(map, NULL, shared), ROMA_SUCCESS); /* NULL frame: frame 0, no jitter */
    roma_gpu_timing timing[4];
    uint32_t count = 4;
    CHECK_RESULT(roma_gpu_timer_read(shared, timing, &count), ROMA_SUCCESS);
    CHECK(count == 2 && strcmp(timing[0].name, "bom") == 0 && strcmp(timing[1].name, "rotate") == 0);
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);

    /* Recording into the caller's command buffer. */
    VkCommandBuffer cmd = begin_cmd(g);
    if (cmd) {
        roma_trace_desc td = {.mode = ROMA_TRACE_SNAPPED_ANY, .ray_count = 1};
        FAILS(roma_map_record_build(map, VK_NULL_HANDLE, &frame, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "cmd");
        CHECK_RESULT(roma_map_record_build(NULL, cmd, &frame, NULL), ROMA_ERROR_INVALID_ARGUMENT);
        CHECK_RESULT(roma_map_record_trace(NULL, cmd, &td, NULL), ROMA_ERROR_INVALID_ARGUMENT);
        if (foreign)
            FAILS(roma_map_record_build(map, cmd, &frame, foreign), ROMA_ERROR_INVALID_ARGUMENT, &log, "timer");
        FAILS(roma_map_record_trace(map, cmd, NULL, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "desc");
        FAILS(roma_map_record_trace(map, VK_NULL_HANDLE, &td, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "cmd");
        FAILS(roma_map_record_trace(map, cmd, &td, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "rays");
        td.rays = td.hits = 0x1000; /* never dereferenced: refused before recording */
        td.mode = (roma_trace_mode)4;
        FAILS(roma_map_record_trace(map, cmd, &td, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "mode");
        td.ray_count = 0; /* even with nothing to trace */
        FAILS(roma_map_record_trace(map, cmd, &td, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "mode");
        td.mode = ROMA_TRACE_SNAPPED_CLOSEST;
        if (foreign) {
            td.ray_count = 1;
            FAILS(roma_map_record_trace(map, cmd, &td, foreign), ROMA_ERROR_INVALID_ARGUMENT, &log, "timer");
        }
        td.ray_count = 0;
        CHECK_RESULT(roma_map_record_trace(map, cmd, &td, NULL), ROMA_SUCCESS); /* records nothing */
        end_cmd(g, cmd, 0);
    }

    /* Blocking trace: bad arguments leave the hits untouched. */
    FAILS(roma_map_trace(map, (roma_trace_mode)-1, 0, &ray, 1, &hit, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "mode");
    FAILS(roma_map_trace(map, (roma_trace_mode)7, 0, NULL, 0, NULL, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "mode");
    FAILS(roma_map_trace(map, ROMA_TRACE_SNAPPED_ANY, 0, NULL, 1, &hit, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "rays");
    FAILS(roma_map_trace(map, ROMA_TRACE_SNAPPED_ANY, 0, &ray, 1, NULL, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "out_hits");
    if (foreign)
        FAILS(roma_map_trace(map, ROMA_TRACE_SNAPPED_ANY, 0, &ray, 1, &hit, foreign), ROMA_ERROR_INVALID_ARGUMENT, &log, "timer");
    CHECK(hit.t == -1.0f && hit.info == 0xdeadu);
    /* Any max_steps terminates: the walk stops at the map's edge. */
    CHECK_RESULT(roma_map_trace(map, ROMA_TRACE_UNSNAPPED_ANY, UINT32_MAX, &ray, 1, &hit, NULL), ROMA_SUCCESS);
    CHECK(hit.info & ROMA_HIT_FLAG);

    /* Queries. */
    memset(&info, 0xab, sizeof info);
    CHECK_RESULT(roma_map_get_info(NULL, &info), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(all_zero(&info, sizeof info));
    FAILS(roma_map_get_info(map, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "out_info");
    float dir[3] = {7, 7, 7};
    FAILS(roma_map_candidate(map, 4, dir), ROMA_ERROR_INVALID_ARGUMENT, &log, "k = 4");
    CHECK(all_zero(dir, sizeof dir));
    dir[0] = 7.0f;
    FAILS(roma_map_candidate(map, UINT32_MAX, dir), ROMA_ERROR_INVALID_ARGUMENT, &log, "candidates");
    CHECK(dir[0] == 0.0f);
    FAILS(roma_map_candidate(map, 0, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "out_dir");
    CHECK_RESULT(roma_map_candidate(NULL, 0, dir), ROMA_ERROR_INVALID_ARGUMENT);

    /* Downloads: the count must match exactly; a count that wraps when multiplied by 4 was accepted. */
    FAILS(roma_map_download_bom(map, words, bom_words + (1ull << 62)), ROMA_ERROR_INVALID_ARGUMENT, &log, "word_count");
    FAILS(roma_map_download_maps(map, words, bom_words), ROMA_ERROR_INVALID_ARGUMENT, &log, "word_count");
    FAILS(roma_map_download_maps(map, words, 0), ROMA_ERROR_INVALID_ARGUMENT, &log, "word_count");
    FAILS(roma_map_download_maps(map, NULL, maps_words), ROMA_ERROR_INVALID_ARGUMENT, &log, "out_words");
    CHECK_RESULT(roma_map_download_maps(NULL, words, maps_words), ROMA_ERROR_INVALID_ARGUMENT);

    /* Positions. */
    roma_scene_view sv;
    CHECK_RESULT(roma_scene_get_view(scene, &sv), ROMA_SUCCESS);
    roma_map_frame_desc fp = frame;
    fp.positions = sv.positions;
    FAILS(roma_map_build(map, &fp, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "vertices"); /* count 0 */
    fp.vertex_count = UINT32_MAX;
    FAILS(roma_map_build(map, &fp, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "vertices");
    fp.vertex_count = sv.vertex_count;
    fp.gpu_positions = 16;
    FAILS(roma_map_build(map, &fp, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "both");
    fp.positions = NULL;
    FAILS(roma_map_build(map, &fp, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "volume");
    roma_box box = {{0, 0, 0}, {1, 1, 1}};
    fp.volume = &box;
    fp.gpu_position_stride = 6;
    FAILS(roma_map_build(map, &fp, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "stride");
    fp.gpu_position_stride = 0;
    fp.gpu_positions = 18;
    FAILS(roma_map_build(map, &fp, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "aligned");
    fp.gpu_positions = 0;
    box.max[1] = -1.0f;
    FAILS(roma_map_build(map, &fp, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "volume");
    box.max[1] = NAN;
    FAILS(roma_map_build(map, &fp, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "volume");
    fp.volume = NULL;
    fp.slot = 2;
    FAILS(roma_map_build(map, &fp, NULL), ROMA_ERROR_INVALID_ARGUMENT, &log, "slot");
    roma_map_desc too_many_slots = {.frames_in_flight = ROMA_MAX_FRAMES_IN_FLIGHT + 1, .logger = roma_test_logger(&log)};
    roma_map *no_map = NULL;
    FAILS(roma_map_create(g->ctx, &too_many_slots, scene, &no_map), ROMA_ERROR_INVALID_ARGUMENT, &log,
          "frames_in_flight");
    CHECK(no_map == NULL);

    /* After all that the map builds, traces and downloads as before. */
    fp = frame;
    fp.positions = sv.positions, fp.vertex_count = sv.vertex_count, fp.slot = 1;
    CHECK_RESULT(roma_map_build(map, &fp, NULL), ROMA_SUCCESS);
    CHECK(traces_walls(map));
    CHECK_RESULT(roma_map_download_bom(map, words, bom_words), ROMA_SUCCESS);
    CHECK(popcount_words(words, bom_words) > 0);
    CHECK_RESULT(roma_map_download_maps(map, words, maps_words), ROMA_SUCCESS);
    CHECK_RESULT(roma_map_candidate(map, 3, dir), ROMA_SUCCESS);
    CHECK_NEAR(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2], 1.0, 1e-5);
    CHECK_RESULT(roma_map_get_info(map, &info), ROMA_SUCCESS);
    CHECK(info.resolution == 32 && info.map_count == 4 && info.maps_address != 0);

    free(words);
    roma_gpu_timer_destroy(foreign);
    roma_gpu_timer_destroy(shared);
    roma_map_destroy(map);
    roma_map_destroy(NULL);
}

int main(void)
{
    test_camera();
    test_image();
    test_gltf();
    roma_scene *scene = NULL;
    CHECK_RESULT(roma_scene_create_builtin("cornell", NULL, &scene), ROMA_SUCCESS);
    if (!scene)
        return roma_test_finish("test_api_misuse");
    test_scene(scene);
    test_effects(scene);

    gpu g = {roma_test_context(), VK_NULL_HANDLE, VK_NULL_HANDLE};
    if (g.ctx) {
        g.device = roma_context_device(g.ctx);
        VkCommandPoolCreateInfo pool = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                        .flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT,
                                        .queueFamilyIndex = roma_context_queue_family(g.ctx)};
        CHECK(vkCreateCommandPool(g.device, &pool, NULL, &g.pool) == VK_SUCCESS);
        /* A second context on the same device with a recording logger (messages of
         * context-level calls), and one on a device of its own (foreign timers). */
        roma_test_log log;
        roma_device_requirements req;
        roma_get_device_requirements(&req);
        roma_external_device ext = {roma_context_instance(g.ctx), roma_context_physical_device(g.ctx),
                                    g.device, roma_context_queue_family(g.ctx), roma_context_queue(g.ctx),
                                    &req.features};
        roma_context_desc desc = {.external = &ext, .logger = roma_test_logger(&log)};
        roma_context *logged = NULL;
        CHECK_RESULT(roma_context_create(&desc, &logged), ROMA_SUCCESS);
        roma_context *other = roma_test_context();
        if (logged && other && g.pool) {
            test_context(&g, logged, &log);
            test_map(&g, logged, other, scene);
        }
        roma_context_destroy(logged);
        roma_test_context_finish(other);
        if (g.pool)
            vkDestroyCommandPool(g.device, g.pool, NULL);
        roma_test_context_finish(g.ctx);
    }
    /* The scene outlives every failed call unchanged. */
    roma_scene_view v;
    CHECK_RESULT(roma_scene_get_view(scene, &v), ROMA_SUCCESS);
    CHECK(v.triangle_count > 0 && v.positions && strcmp(v.name, "cornell") == 0);
    roma_scene_destroy(scene);
    return roma_test_finish("test_api_misuse");
}
