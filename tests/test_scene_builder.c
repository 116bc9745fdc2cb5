/* roma_scene_create: good input round-trips through the view with computed
 * normals, bounds, emissive list and degenerate count; every rejection has its
 * exact code and leaves *out_scene NULL; animation data is validated. */
#include <math.h>
#include <string.h>

#include "harness.h"
#include "roma/scene.h"

#define SENTINEL ((roma_scene *)(void *)&sentinel_storage)
static int sentinel_storage;

/* Flat quad in z = 0 (counter-clockwise from +z), a degenerate triangle, and
 * vertex 5 used by nothing (far away, so bounds prove they skip it). */
static const float quad_pos[] = {0, 0, 0, 2, 0, 0, 2, 1, 0, 0, 1, 0, 1, 0.5f, 0, 100, 100, 100};
static const uint32_t quad_idx[] = {0, 1, 2, 0, 2, 3, 4, 4, 1};
static const uint32_t quad_mat[] = {0, 1, 1};
static const roma_material quad_mats[] = {{{0.5f, 0.5f, 0.5f}, {0, 0, 0}}, {{0.1f, 0.2f, 0.3f}, {1, 0, 0}}};

static roma_scene_desc quad_desc(roma_logger logger)
{
    roma_scene_desc d = {0};
    d.positions = quad_pos;
    d.vertex_count = 6;
    d.indices = quad_idx;
    d.triangle_count = 3;
    d.triangle_materials = quad_mat;
    d.materials = quad_mats;
    d.material_count = 2;
    d.name = "quad";
    d.logger = logger;
    return d;
}

/* Expects `code` with *out NULL and one error logged. */
static void expect_reject(const roma_scene_desc *d, roma_result code, roma_test_log *log, int line)
{
    roma_scene *s = SENTINEL;
    int errors = log->errors;
    roma_result r = roma_scene_create(d, &s);
    if (r != code || s != NULL || log->errors != errors + 1) {
        fprintf(stderr, "line %d: got '%s' (scene %p, %d new errors), expected '%s'\n", line,
                roma_result_string(r), (void *)s, log->errors - errors, roma_result_string(code));
        ++roma_test_failures;
    }
    if (r == ROMA_SUCCESS)
        roma_scene_destroy(s);
}
#define REJECT(desc, code) expect_reject(&(desc), code, &log, __LINE__)

static void test_good(roma_logger logger, roma_test_log *log)
{
    roma_scene_desc d = quad_desc(logger);
    roma_light lights[2] = {{0}};
    lights[0].type = ROMA_LIGHT_SPOT;
    lights[0].direction[1] = -4.0f; /* normalised by the scene */
    lights[0].color[0] = 1.0f;
    lights[0].intensity = 2.0f;
    lights[1].type = ROMA_LIGHT_DIRECTIONAL;
    lights[1].direction[0] = 3.0f;
    lights[1].direction[2] = 4.0f;
    d.lights = lights;
    d.light_count = 2;
    roma_camera cam = {{1, 2, 3}, {0, 0, 0}, {0, 1, 0}, 50.0f};
    d.camera = &cam;
    d.cameras = &cam;
    d.camera_count = 1;

    roma_scene *s = NULL;
    CHECK_RESULT(roma_scene_create(&d, &s), ROMA_SUCCESS);
    CHECK(s != NULL);
    CHECK(log->errors == 0);
    if (!s)
        return;
    roma_scene_view v;
    CHECK_RESULT(roma_scene_get_view(s, &v), ROMA_SUCCESS);
    CHECK(strcmp(v.name, "quad") == 0 && v.name != d.name);
    CHECK(v.vertex_count == 6 && v.triangle_count == 3);
    CHECK(v.positions != quad_pos && memcmp(v.positions, quad_pos, sizeof quad_pos) == 0);
    CHECK(memcmp(v.indices, quad_idx, sizeof quad_idx) == 0);
    CHECK(memcmp(v.triangle_materials, quad_mat, sizeof quad_mat) == 0);
    CHECK(v.material_count == 2 && v.materials[1].emission[0] == 1.0f);
    CHECK(v.degenerate_triangle_count == 1);
    /* Only triangle 1 emits: triangle 2 uses the emissive material but has no area. */
    CHECK(v.emissive_triangle_count == 1 && v.emissive_triangles[0] == 1);
    for (int i = 0; i < 4; ++i) {
        CHECK_NEAR(v.normals[3 * i + 0], 0.0, 1e-7);
        CHECK_NEAR(v.normals[3 * i + 1], 0.0, 1e-7);
        CHECK_NEAR(v.normals[3 * i + 2], 1.0, 1e-7);
    }
    /* vertex 4 only has a zero-area triangle, vertex 5 none: no normal */
    for (int i = 12; i < 18; ++i)
        CHECK(v.normals[i] == 0.0f);
    CHECK(v.bounds_min[0] == 0.0f && v.bounds_min[1] == 0.0f && v.bounds_min[2] == 0.0f);
    CHECK(v.bounds_max[0] == 2.0f && v.bounds_max[1] == 1.0f && v.bounds_max[2] == 0.0f);
    CHECK(v.light_count == 2);
    CHECK_NEAR(v.lights[0].direction[1], -1.0, 1e-7);
    CHECK_NEAR(v.lights[0].outer_cone_angle, 3.14159265 / 4, 1e-6); /* 0 means pi/4 */
    CHECK_NEAR(v.lights[1].direction[0], 0.6, 1e-6);
    CHECK_NEAR(v.lights[1].direction[2], 0.8, 1e-6);
    CHECK(v.has_camera && v.camera.eye[1] == 2.0f && v.camera.fovy_deg == 50.0f);
    CHECK(v.camera_count == 1 && v.cameras != d.cameras && v.cameras[0].eye[2] == 3.0f); /* copied */
    CHECK(v.animation.node_count == 0 && v.animation.nodes == NULL);

    roma_camera out;
    roma_scene_default_camera(s, 1.5f, &out);
    CHECK(memcmp(&out, &cam, sizeof cam) == 0);
    roma_scene_destroy(s);

    /* No camera: the default frames the bounds, exactly as roma_camera_frame_bounds does. */
    d.camera = NULL;
    d.lights = NULL;
    d.light_count = 0;
    CHECK_RESULT(roma_scene_create(&d, &s), ROMA_SUCCESS);
    if (s) {
        roma_camera framed;
        const float bmin[3] = {0, 0, 0}, bmax[3] = {2, 1, 0};
        roma_camera_frame_bounds(bmin, bmax, 1.5f, &framed);
        roma_scene_default_camera(s, 1.5f, &out);
        CHECK(memcmp(&out, &framed, sizeof out) == 0);
        roma_scene_get_view(s, &v);
        CHECK(!v.has_camera);
        roma_scene_destroy(s);
    }

    /* Given normals are normalised; a zero one falls back to the face normal with one warning. */
    float normals[18] = {0, 0, 5, 0, 0, 0, 3, 0, 4, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    d.normals = normals;
    int warnings = log->warnings;
    CHECK_RESULT(roma_scene_create(&d, &s), ROMA_SUCCESS);
    CHECK(log->warnings == warnings + 1);
    if (s) {
        roma_scene_get_view(s, &v);
        CHECK_NEAR(v.normals[2], 1.0, 1e-7);
        CHECK_NEAR(v.normals[5], 1.0, 1e-7); /* was zero: face normal */
        CHECK_NEAR(v.normals[6], 0.6, 1e-6);
        CHECK_NEAR(v.normals[8], 0.8, 1e-6);
        roma_scene_destroy(s);
    }

    /* Defaults: no materials means one grey material. */
    d = quad_desc(logger);
    d.materials = NULL;
    d.material_count = 0;
    d.triangle_materials = NULL;
    CHECK_RESULT(roma_scene_create(&d, &s), ROMA_SUCCESS);
    if (s) {
        roma_scene_get_view(s, &v);
        CHECK(v.material_count == 1 && v.materials[0].base_color[0] == 0.8f);
        CHECK(v.emissive_triangle_count == 0 && v.triangle_materials[2] == 0);
        roma_scene_destroy(s);
    }
}

static void test_rejects(void)
{
    roma_test_log log;
    roma_logger logger = roma_test_logger(&log);
    roma_scene *s = SENTINEL;
    CHECK_RESULT(roma_scene_create(NULL, &s), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(s == NULL);
    roma_scene_desc d = quad_desc(logger);
    CHECK_RESULT(roma_scene_create(&d, NULL), ROMA_ERROR_INVALID_ARGUMENT);

    d = quad_desc(logger), d.positions = NULL;
    REJECT(d, ROMA_ERROR_INVALID_ARGUMENT);
    d = quad_desc(logger), d.indices = NULL;
    REJECT(d, ROMA_ERROR_INVALID_ARGUMENT);
    d = quad_desc(logger), d.materials = NULL;
    REJECT(d, ROMA_ERROR_INVALID_ARGUMENT);
    d = quad_desc(logger), d.light_count = 1;
    REJECT(d, ROMA_ERROR_INVALID_ARGUMENT);
    d = quad_desc(logger), d.camera_count = 1; /* cameras NULL */
    REJECT(d, ROMA_ERROR_INVALID_ARGUMENT);
    roma_camera cams[2] = {{{1, 2, 3}, {0, 0, 0}, {0, 1, 0}, 50.0f}, {{1, 2, 3}, {0, 0, 0}, {0, 1, 0}, NAN}};
    d = quad_desc(logger), d.cameras = cams, d.camera_count = 2;
    REJECT(d, ROMA_ERROR_INVALID_SCENE);

    d = quad_desc(logger), d.triangle_count = 0;
    REJECT(d, ROMA_ERROR_EMPTY_SCENE);
    d = quad_desc(logger), d.indices = quad_idx + 6, d.triangle_count = 1; /* only the degenerate one */
    REJECT(d, ROMA_ERROR_EMPTY_SCENE);
    const float line_pos[] = {0, 0, 0, 1, 1, 1, 2, 2, 2};
    const uint32_t line_idx[] = {0, 1, 2};
    d = quad_desc(logger), d.positions = line_pos, d.vertex_count = 3, d.indices = line_idx,
    d.triangle_count = 1, d.triangle_materials = NULL;
    REJECT(d, ROMA_ERROR_EMPTY_SCENE);

    const uint32_t bad_idx[] = {0, 1, 6};
    d = quad_desc(logger), d.indices = bad_idx, d.triangle_count = 1;
    REJECT(d, ROMA_ERROR_INVALID_SCENE);
    const uint32_t bad_mat[] = {0, 2, 0};
    d = quad_desc(logger), d.triangle_materials = bad_mat;
    REJECT(d, ROMA_ERROR_INVALID_SCENE);
    d = quad_desc(logger), d.materials = NULL, d.material_count = 0; /* material 1 of the default 1 */
    REJECT(d, ROMA_ERROR_INVALID_SCENE);

    float pos[18];
    memcpy(pos, quad_pos, sizeof pos);
    d = quad_desc(logger), d.positions = pos;
    pos[4] = NAN;
    REJECT(d, ROMA_ERROR_INVALID_SCENE);
    pos[4] = INFINITY;
    REJECT(d, ROMA_ERROR_INVALID_SCENE);
    pos[4] = 0.0f;
    pos[16] = -INFINITY; /* unused vertices are checked too */
    REJECT(d, ROMA_ERROR_INVALID_SCENE);

    float normals[18] = {0};
    normals[7] = NAN;
    d = quad_desc(logger), d.normals = normals;
    REJECT(d, ROMA_ERROR_INVALID_SCENE);

    roma_material mats[2];
    memcpy(mats, quad_mats, sizeof mats);
    d = quad_desc(logger), d.materials = mats;
    mats[1].base_color[2] = -0.1f;
    REJECT(d, ROMA_ERROR_INVALID_SCENE);
    mats[1].base_color[2] = 1.5f;
    REJECT(d, ROMA_ERROR_INVALID_SCENE);
    mats[1].base_color[2] = 0.3f;
    mats[1].emission[1] = -1.0f;
    REJECT(d, ROMA_ERROR_INVALID_SCENE);
    mats[1].emission[1] = NAN;
    REJECT(d, ROMA_ERROR_INVALID_SCENE);

    roma_light light = {0};
    d = quad_desc(logger), d.lights = &light, d.light_count = 1;
    light.type = (roma_light_type)0;
    REJECT(d, ROMA_ERROR_INVALID_SCENE);
    light.type = ROMA_LIGHT_POINT;
    light.position[0] = NAN;
    REJECT(d, ROMA_ERROR_INVALID_SCENE);
    light.position[0] = 0.0f;
    light.color[1] = -1.0f;
    REJECT(d, ROMA_ERROR_INVALID_SCENE);
    light.color[1] = 1.0f;
    light.intensity = INFINITY;
    REJECT(d, ROMA_ERROR_INVALID_SCENE);
    light.intensity = 1.0f;
    light.type = ROMA_LIGHT_SPOT; /* zero direction */
    REJECT(d, ROMA_ERROR_INVALID_SCENE);
    light.type = ROMA_LIGHT_DIRECTIONAL;
    REJECT(d, ROMA_ERROR_INVALID_SCENE);
    light.type = ROMA_LIGHT_SPOT;
    light.direction[2] = -1.0f;
    light.inner_cone_angle = 0.5f;
    light.outer_cone_angle = 0.4f;
    REJECT(d, ROMA_ERROR_INVALID_SCENE);
    light.inner_cone_angle = 0.9f; /* above the default outer angle pi/4 */
    light.outer_cone_angle = 0.0f;
    REJECT(d, ROMA_ERROR_INVALID_SCENE);
    light.inner_cone_angle = 0.3f;
    roma_scene *ok = NULL;
    CHECK_RESULT(roma_scene_create(&d, &ok), ROMA_SUCCESS); /* the same light, now valid */
    roma_scene_destroy(ok);
    /* Directions whose squares overflow (1e30) or vanish (1e-30) are still directions
     * (the fuzzer found 1e20-long ones stored as zero, so the scene's own view was
     * refused); all-subnormal ones count as zero. */
    const float lengths[] = {1e30f, 1e-30f, 1e-41f};
    for (int i = 0; i < 3; ++i) {
        light.direction[0] = 0.0f, light.direction[1] = 0.0f, light.direction[2] = -lengths[i];
        ok = NULL;
        CHECK_RESULT(roma_scene_create(&d, &ok), i < 2 ? ROMA_SUCCESS : ROMA_ERROR_INVALID_SCENE);
        if (ok) {
            roma_scene_view lv;
            roma_scene_get_view(ok, &lv);
            CHECK(lv.light_count == 1 && lv.lights[0].direction[2] == -1.0f && lv.lights[0].direction[0] == 0.0f);
            roma_scene_destroy(ok);
        }
    }

    roma_camera cam = {{0, 0, NAN}, {0, 0, 0}, {0, 1, 0}, 45.0f};
    d = quad_desc(logger), d.camera = &cam;
    REJECT(d, ROMA_ERROR_INVALID_SCENE);

    roma_scene_view v;
    CHECK_RESULT(roma_scene_get_view(NULL, &v), ROMA_ERROR_INVALID_ARGUMENT);
    roma_scene_destroy(NULL);
    roma_camera out = {{1, 1, 1}, {0}, {0}, 0};
    roma_scene_default_camera(NULL, 1.0f, &out); /* must not crash */
}

static void test_animation(roma_logger logger, roma_test_log *log)
{
    roma_scene_desc d = quad_desc(logger);
    roma_scene *s = NULL;
    CHECK_RESULT(roma_scene_create(&d, &s), ROMA_SUCCESS);
    if (!s)
        return;
    roma_scene_node nodes[2] = {{-1, -1, {0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1}, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}},
                                {0, 0, {0, 1, 0}, {0, 0, 0, 1}, {1, 1, 1}, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 1, 0, 1}}};
    roma_scene_skin skin = {0, 2};
    uint32_t joint_nodes[2] = {0, 1};
    float binds[32] = {0};
    for (int m = 0; m < 2; ++m)
        for (int i = 0; i < 16; i += 5)
            binds[16 * m + i] = 1.0f;
    uint32_t vnode[6] = {1, 1, 1, 1, 1, 1};
    int32_t vskin[6] = {0, 0, 0, 0, -1, -1};
    uint16_t vjoints[24] = {0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0};
    float vweights[24] = {0.5f, 0.5f, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    roma_scene_anim_channel ch[2] = {{0, 1, ROMA_ANIM_TRANSLATION, ROMA_ANIM_LINEAR, 2, 3, 0, 0},
                                     {0, 1, ROMA_ANIM_ROTATION, ROMA_ANIM_CUBICSPLINE, 2, 4, 0, 6}};
    float times[2] = {0.0f, 1.0f};
    float values[6 + 2 * 3 * 4] = {0, 0, 0, 0, 2, 0};
    roma_scene_animation_data a = {0};
    a.nodes = nodes, a.node_count = 2, a.skins = &skin, a.skin_count = 1, a.joint_nodes = joint_nodes;
    a.inverse_binds = binds, a.joint_total = 2, a.vertex_node = vnode, a.vertex_skin = vskin;
    a.vertex_joints = vjoints, a.vertex_weights = vweights, a.vertex_rest_local = quad_pos;
    a.channels = ch, a.channel_count = 2, a.animation_count = 1, a.times = times, a.values = values;

    CHECK_RESULT(roma_scene_set_animation_data(s, &a, &logger), ROMA_SUCCESS);
    roma_scene_view v;
    roma_scene_get_view(s, &v);
    CHECK(v.animation.node_count == 2 && v.animation.nodes != nodes && v.animation.nodes[1].translation[1] == 1.0f);
    CHECK(v.animation.joint_total == 2 && v.animation.inverse_binds[15] == 1.0f);
    CHECK(v.animation.channel_count == 2 && v.animation.channels[1].first_value == 6);
    CHECK(v.animation.values != values && v.animation.values[4] == 2.0f);
    CHECK(v.animation.vertex_joints[4] == 1 && v.animation.vertex_rest_local[3] == 2.0f);
    nodes[1].translation[1] = 7.0f; /* deep copy: later edits do not leak in */
    CHECK(v.animation.nodes[1].translation[1] == 1.0f);
    nodes[1].translation[1] = 1.0f;

    /* Every rejection keeps the data already attached. */
    const roma_scene_node *kept = v.animation.nodes;
#define BAD(field, bad, code)                                                                       \
    do {                                                                                            \
        roma_scene_animation_data b = a;                                                            \
        b.field = bad;                                                                              \
        int errors_ = log->errors;                                                                  \
        CHECK_RESULT(roma_scene_set_animation_data(s, &b, &logger), code);                         \
        CHECK(log->errors == errors_ + 1);                                                          \
        roma_scene_get_view(s, &v);                                                                 \
        CHECK(v.animation.nodes == kept);                                                           \
    } while (0)
    BAD(nodes, NULL, ROMA_ERROR_INVALID_ARGUMENT);
    BAD(times, NULL, ROMA_ERROR_INVALID_ARGUMENT);
    BAD(joint_total, 1, ROMA_ERROR_INVALID_SCENE); /* the skin's 2 joints do not fit */
    BAD(animation_count, 0, ROMA_ERROR_INVALID_SCENE);
    BAD(skin_count, 0, ROMA_ERROR_INVALID_SCENE); /* node 1 and vertices use skin 0 */
    BAD(node_count, 1, ROMA_ERROR_INVALID_SCENE);

    roma_scene_node cyc[2];
    memcpy(cyc, nodes, sizeof cyc);
    cyc[0].parent = 1;
    BAD(nodes, cyc, ROMA_ERROR_INVALID_SCENE);
    cyc[0].parent = 5;
    BAD(nodes, cyc, ROMA_ERROR_INVALID_SCENE);
    cyc[0].parent = -1;
    cyc[1].world[3] = NAN;
    BAD(nodes, cyc, ROMA_ERROR_INVALID_SCENE);

    roma_scene_skin big = {1, 2};
    BAD(skins, &big, ROMA_ERROR_INVALID_SCENE);
    uint32_t bad_joint_nodes[2] = {0, 2};
    BAD(joint_nodes, bad_joint_nodes, ROMA_ERROR_INVALID_SCENE);
    uint32_t bad_vnode[6] = {1, 1, 1, 1, 1, 2};
    BAD(vertex_node, bad_vnode, ROMA_ERROR_INVALID_SCENE);
    uint16_t bad_joints[24] = {0, 2};
    BAD(vertex_joints, bad_joints, ROMA_ERROR_INVALID_SCENE);
    float bad_weights[24] = {-1.0f};
    BAD(vertex_weights, bad_weights, ROMA_ERROR_INVALID_SCENE);
    float bad_values[30];
    memcpy(bad_values, values, sizeof bad_values);
    bad_values[29] = INFINITY; /* last value of the cubic-spline channel: in range 6 + 2*3*4 */
    BAD(values, bad_values, ROMA_ERROR_INVALID_SCENE);
    roma_scene_anim_channel bad_ch[2];
    memcpy(bad_ch, ch, sizeof bad_ch);
    bad_ch[0].components = 4; /* translation needs 3 */
    BAD(channels, bad_ch, ROMA_ERROR_INVALID_SCENE);
    memcpy(bad_ch, ch, sizeof bad_ch);
    bad_ch[1].node = 2;
    BAD(channels, bad_ch, ROMA_ERROR_INVALID_SCENE);
    memcpy(bad_ch, ch, sizeof bad_ch);
    bad_ch[1].key_count = 0;
    BAD(channels, bad_ch, ROMA_ERROR_INVALID_SCENE);
#undef BAD
    CHECK_RESULT(roma_scene_set_animation_data(NULL, &a, &logger), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_scene_set_animation_data(s, NULL, &logger), ROMA_ERROR_INVALID_ARGUMENT);

    /* Empty data replaces what was attached. */
    roma_scene_animation_data none = {0};
    CHECK_RESULT(roma_scene_set_animation_data(s, &none, &logger), ROMA_SUCCESS);
    roma_scene_get_view(s, &v);
    CHECK(v.animation.node_count == 0 && v.animation.vertex_node == NULL);
    roma_scene_destroy(s);
}

int main(void)
{
    roma_test_log log;
    roma_logger logger = roma_test_logger(&log);
    test_good(logger, &log);
    test_rejects();
    test_animation(logger, &log);
    return roma_test_finish("test_scene_builder");
}
