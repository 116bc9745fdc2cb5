/* glTF loader: the test writes its own files. A scene with instancing, TRS
 * and matrix nodes, a mirrored node, materials with emissive strength,
 * punctual lights and a camera loads (as .gltf with a data URI, as .glb, and
 * with an external .bin) with exact world-space results; a corpus of broken
 * files each fails with its exact code, one error message and no scene, from
 * a path and from memory alike. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "roma/animation.h"
#include "roma/gltf.h"

static int sentinel_storage;
#define SENTINEL ((roma_scene *)(void *)&sentinel_storage)

/* Counts errors without printing: the truncation loops make thousands. */
static void count_errors(roma_log_level level, roma_result code, const char *message, void *user)
{
    (void)message, (void)code;
    *(int *)user += level == ROMA_LOG_ERROR;
}

/* --- file helpers --- */

static void base64(const unsigned char *in, size_t n, char *out)
{
    static const char t[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    size_t o = 0;
    for (size_t i = 0; i < n; i += 3) {
        unsigned v = (unsigned)in[i] << 16 | (i + 1 < n ? (unsigned)in[i + 1] << 8 : 0) | (i + 2 < n ? in[i + 2] : 0);
        out[o++] = t[v >> 18 & 63];
        out[o++] = t[v >> 12 & 63];
        out[o++] = i + 1 < n ? t[v >> 6 & 63] : '=';
        out[o++] = i + 2 < n ? t[v & 63] : '=';
    }
    out[o] = 0;
}

static char *data_uri(const void *bin, size_t n)
{
    static const char prefix[] = "data:application/octet-stream;base64,";
    char *s = malloc(sizeof prefix + 4 * (n / 3 + 1) + 1);
    if (!s)
        return NULL;
    memcpy(s, prefix, sizeof prefix);
    base64(bin, n, s + sizeof prefix - 1);
    return s;
}

static void write_file(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(data, 1, n, f) != n) {
        fprintf(stderr, "cannot write %s\n", path);
        ++roma_test_failures;
    }
    if (f)
        fclose(f);
}

/* Copy of src with the first `from` replaced by `to`; a missing `from` is a test bug. */
static char *subst(const char *src, const char *from, const char *to)
{
    const char *at = strstr(src, from);
    if (!at) {
        fprintf(stderr, "template has no '%s'\n", from);
        ++roma_test_failures;
        at = src + strlen(src);
        from = "";
    }
    size_t head = (size_t)(at - src), n = strlen(src) - strlen(from) + strlen(to) + 1;
    char *out = malloc(n);
    memcpy(out, src, head);
    strcpy(out + head, to);
    strcat(out, at + strlen(from));
    return out;
}

static char *printf_doc(const char *fmt, const char *arg)
{
    size_t n = strlen(fmt) + strlen(arg) + 1;
    char *out = malloc(n);
    snprintf(out, n, fmt, arg);
    return out;
}

/* GLB container: 12-byte header, JSON chunk padded with spaces, BIN chunk padded with zeros. */
static size_t make_glb(unsigned char *out, const char *json, const void *bin, size_t bin_len)
{
    size_t jl = strlen(json), jp = (jl + 3) & ~(size_t)3, bp = (bin_len + 3) & ~(size_t)3;
    uint32_t total = (uint32_t)(12 + 8 + jp + (bin_len ? 8 + bp : 0));
    uint32_t head[5] = {0x46546C67u, 2, total, (uint32_t)jp, 0x4E4F534Au};
    memcpy(out, head, 20);
    memset(out + 20, ' ', jp);
    memcpy(out + 20, json, jl);
    if (bin_len) {
        uint32_t ch[2] = {(uint32_t)bp, 0x004E4942u};
        memcpy(out + 20 + jp, ch, 8);
        memset(out + 28 + jp, 0, bp);
        memcpy(out + 28 + jp, bin, bin_len);
    }
    return total;
}

/* Loads `data` from a file called `name` and from memory; both must agree on
 * the code, leave NULL on failure and log exactly one error then, with that code. */
static roma_result load_case(const char *name, const void *data, size_t n, int *warnings, roma_scene **keep)
{
    char path[1024];
    roma_test_tmp_path(name, path, sizeof path);
    write_file(path, data, n);
    roma_test_log log, mlog;
    roma_gltf_desc desc = {.logger = roma_test_logger(&log)};
    roma_scene *s = SENTINEL, *m = SENTINEL;
    roma_result r = roma_scene_load_gltf(path, &desc, &s);
    desc.logger = roma_test_logger(&mlog);
    roma_result rm = roma_scene_load_gltf_memory(data, n, NULL, &desc, &m);
    int ok = r == ROMA_SUCCESS ? s && s != SENTINEL && log.errors == 0
                               : s == NULL && log.errors == 1 && log.last_code == r && mlog.last_code == rm;
    ok = ok && rm == r && (rm == ROMA_SUCCESS ? m && m != SENTINEL : m == NULL) && mlog.errors == log.errors;
    if (!ok) {
        fprintf(stderr, "%s: file '%s' (%d errors), memory '%s' (%d errors)\n", name, roma_result_string(r),
                log.errors, roma_result_string(rm), mlog.errors);
        ++roma_test_failures;
    }
    if (rm == ROMA_SUCCESS)
        roma_scene_destroy(m);
    if (warnings)
        *warnings = log.warnings;
    if (keep && r == ROMA_SUCCESS)
        *keep = s;
    else if (r == ROMA_SUCCESS)
        roma_scene_destroy(s);
    return r;
}

static void expect_code(const char *name, const void *data, size_t n, roma_result code)
{
    roma_result r = load_case(name, data, n, NULL, NULL);
    if (r != code) {
        fprintf(stderr, "%s: got '%s', expected '%s'\n", name, roma_result_string(r), roma_result_string(code));
        ++roma_test_failures;
    }
}

/* --- the good scene --- */

typedef struct good_buffer {
    float quad[12], quad_n[12];
    uint16_t quad_i[6];
    float tri_xz[9], tri_xy[9];
} good_buffer; /* 180 bytes, offsets 0, 48, 96, 108, 144 */

static const good_buffer good_bin = {
    {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0},
    {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1},
    {0, 1, 2, 0, 2, 3},
    {0, 0, 0, 1, 0, 0, 0, 0, 1},
    {0, 0, 0, 1, 0, 0, 0, 1, 0},
};

/* Scene 1 (the default) holds nodes 0 (mesh 0 moved), 1 (TRS, with child 2
 * given as a matrix), 3 (camera), 4 (spot), 5 (point), 6 (mirrored mesh 1).
 * Node 7 sits only in scene 0 and must not appear. */
static const char good_json[] =
    "{\"asset\":{\"version\":\"2.0\"},"
    "\"extensionsUsed\":[\"KHR_lights_punctual\",\"KHR_materials_emissive_strength\"],"
    "\"extensionsRequired\":[\"KHR_materials_emissive_strength\"],"
    "\"scene\":1,\"scenes\":[{\"nodes\":[7]},{\"nodes\":[0,1,3,4,5,6]}],"
    "\"nodes\":["
    "{\"mesh\":0,\"translation\":[10,0,0]},"
    "{\"mesh\":0,\"translation\":[0,5,0],\"rotation\":[0,0,0.70710678118,0.70710678118],\"scale\":[2,2,2],"
    "\"children\":[2]},"
    "{\"mesh\":0,\"matrix\":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,3,1]},"
    "{\"camera\":0,\"translation\":[0,0,10]},"
    "{\"translation\":[1,2,3],\"rotation\":[0.70710678118,0,0,0.70710678118],"
    "\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}},"
    "{\"translation\":[-1,-2,-3],\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}}},"
    "{\"mesh\":1,\"translation\":[0,-10,0],\"scale\":[-1,1,1]},"
    "{\"mesh\":0}],"
    "\"meshes\":[{\"name\":\"quad\",\"primitives\":["
    "{\"attributes\":{\"POSITION\":0,\"NORMAL\":1},\"indices\":2,\"material\":0},"
    "{\"attributes\":{\"POSITION\":3}}]},"
    "{\"name\":\"mirror\",\"primitives\":[{\"attributes\":{\"POSITION\":4}}]}],"
    "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,0.25,0.125,1]},"
    "\"emissiveFactor\":[1,0.5,0.25],"
    "\"extensions\":{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":4}}}],"
    "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.8,\"znear\":0.1}}],"
    "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":["
    "{\"type\":\"spot\",\"color\":[1,0.5,0.25],\"intensity\":7,"
    "\"spot\":{\"innerConeAngle\":0.2,\"outerConeAngle\":0.6}},"
    "{\"type\":\"point\",\"intensity\":3,\"range\":10}]}},"
    "\"accessors\":["
    "{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,0]},"
    "{\"bufferView\":1,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
    "{\"bufferView\":2,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"},"
    "{\"bufferView\":3,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
    "{\"bufferView\":4,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}],"
    "\"bufferViews\":["
    "{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48},"
    "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":48},"
    "{\"buffer\":0,\"byteOffset\":96,\"byteLength\":12},"
    "{\"buffer\":0,\"byteOffset\":108,\"byteLength\":36},"
    "{\"buffer\":0,\"byteOffset\":144,\"byteLength\":36}],"
    "\"buffers\":[%s]}";

/* Where node `node` puts local point p, worked out by hand from the JSON. */
static void expected_world(int node, const float *p, float out[3])
{
    float q[3] = {p[0], p[1], p[2]};
    switch (node) {
    case 0:
        out[0] = q[0] + 10, out[1] = q[1], out[2] = q[2];
        break;
    case 2:
        q[2] += 3; /* then node 1's transform */
        /* fall through */
    case 1: /* scale 2, 90 degrees about z, up 5 */
        out[0] = -2 * q[1], out[1] = 2 * q[0] + 5, out[2] = 2 * q[2];
        break;
    default: /* node 6: mirrored in x, down 10 */
        out[0] = -q[0], out[1] = q[1] - 10, out[2] = q[2];
        break;
    }
}

static void check_vec(const float *got, float x, float y, float z, double tol, int line)
{
    if (fabs(got[0] - x) > tol || fabs(got[1] - y) > tol || fabs(got[2] - z) > tol) {
        fprintf(stderr, "line %d: got (%g, %g, %g), expected (%g, %g, %g)\n", line, got[0], got[1], got[2], x, y, z);
        ++roma_test_failures;
    }
}
#define CHECK_VEC(got, x, y, z) check_vec(got, x, y, z, 1e-5, __LINE__)

static void check_good_scene(const char *what, roma_scene *s)
{
    if (!s) {
        fprintf(stderr, "%s: no scene\n", what);
        ++roma_test_failures;
        return;
    }
    roma_scene_view v;
    roma_scene_get_view(s, &v);
    CHECK(v.vertex_count == 24 && v.triangle_count == 10 && v.degenerate_triangle_count == 0);
    if (v.vertex_count != 24 || v.triangle_count != 10) {
        fprintf(stderr, "%s: %u vertices, %u triangles\n", what, v.vertex_count, v.triangle_count);
        return;
    }
    /* Instances in walk order: nodes 0, 1, 2 (quad 4 + triangle 3 vertices), node 6 (3). */
    const int nodes[3] = {0, 1, 2};
    for (int i = 0; i < 3; ++i) {
        float e[3];
        for (int k = 0; k < 4; ++k) {
            expected_world(nodes[i], good_bin.quad + 3 * k, e);
            CHECK_VEC(v.positions + 3 * (7 * i + k), e[0], e[1], e[2]);
            CHECK_VEC(v.normals + 3 * (7 * i + k), 0, 0, 1);
        }
        for (int k = 0; k < 3; ++k) {
            expected_world(nodes[i], good_bin.tri_xz + 3 * k, e);
            CHECK_VEC(v.positions + 3 * (7 * i + 4 + k), e[0], e[1], e[2]);
            /* no normals in the file: computed from the face, then rotated by the node */
            if (i == 0)
                CHECK_VEC(v.normals + 3 * (7 * i + 4 + k), 0, -1, 0);
            else
                CHECK_VEC(v.normals + 3 * (7 * i + 4 + k), 1, 0, 0);
        }
    }
    for (int k = 0; k < 3; ++k) {
        float e[3];
        expected_world(6, good_bin.tri_xy + 3 * k, e);
        CHECK_VEC(v.positions + 3 * (21 + k), e[0], e[1], e[2]);
        CHECK_VEC(v.normals + 3 * (21 + k), 0, 0, 1); /* mirrored, winding flipped back */
    }
    CHECK(v.indices[0] == 0 && v.indices[1] == 1 && v.indices[2] == 2);
    CHECK(v.indices[27] == 21 && v.indices[28] == 23 && v.indices[29] == 22);

    CHECK(v.material_count == 2);
    CHECK_VEC(v.materials[0].base_color, 0.5f, 0.25f, 0.125f);
    CHECK_VEC(v.materials[0].emission, 4, 2, 1);
    CHECK_VEC(v.materials[1].base_color, 0.8f, 0.8f, 0.8f);
    CHECK_VEC(v.materials[1].emission, 0, 0, 0);
    const uint32_t emissive[6] = {0, 1, 3, 4, 6, 7};
    CHECK(v.emissive_triangle_count == 6);
    for (uint32_t i = 0; i < 6 && i < v.emissive_triangle_count; ++i)
        CHECK(v.emissive_triangles[i] == emissive[i]);
    CHECK(v.triangle_materials[2] == 1 && v.triangle_materials[9] == 1 && v.triangle_materials[3] == 0);

    CHECK(v.light_count == 2);
    if (v.light_count == 2) {
        const roma_light *spot = v.lights, *point = v.lights + 1;
        CHECK(spot->type == ROMA_LIGHT_SPOT && point->type == ROMA_LIGHT_POINT);
        CHECK_VEC(spot->position, 1, 2, 3);
        CHECK_VEC(spot->direction, 0, 1, 0); /* (0,0,-1) turned 90 degrees about x */
        CHECK_VEC(spot->color, 1, 0.5f, 0.25f);
        CHECK(spot->intensity == 7.0f && spot->range == 0.0f);
        CHECK_NEAR(spot->inner_cone_angle, 0.2, 1e-7);
        CHECK_NEAR(spot->outer_cone_angle, 0.6, 1e-7);
        CHECK_VEC(point->position, -1, -2, -3);
        CHECK_VEC(point->color, 1, 1, 1);
        CHECK(point->intensity == 3.0f && point->range == 10.0f);
    }
    CHECK(v.has_camera);
    CHECK_VEC(v.camera.eye, 0, 0, 10);
    CHECK_VEC(v.camera.target, 0, 0, 9);
    CHECK_VEC(v.camera.up, 0, 1, 0);
    CHECK_NEAR(v.camera.fovy_deg, 0.8 * 180.0 / 3.14159265358979, 1e-4);
    CHECK(v.animation.node_count == 0 && v.animation.vertex_node == NULL);
}

static void test_good(void)
{
    char *uri = data_uri(&good_bin, sizeof good_bin);
    char buffer[8192];
    snprintf(buffer, sizeof buffer, "{\"byteLength\":%zu,\"uri\":\"%s\"}", sizeof good_bin, uri);
    char *gltf = printf_doc(good_json, buffer);
    roma_scene *s = NULL;
    CHECK_RESULT(load_case("good.gltf", gltf, strlen(gltf), NULL, &s), ROMA_SUCCESS);
    check_good_scene("good.gltf", s);
    roma_scene_destroy(s);

    snprintf(buffer, sizeof buffer, "{\"byteLength\":%zu}", sizeof good_bin);
    char *glb_json = printf_doc(good_json, buffer);
    unsigned char *glb = malloc(strlen(glb_json) + sizeof good_bin + 64);
    size_t glb_len = make_glb(glb, glb_json, &good_bin, sizeof good_bin);
    s = NULL;
    CHECK_RESULT(load_case("good.glb", glb, glb_len, NULL, &s), ROMA_SUCCESS);
    check_good_scene("good.glb", s);
    roma_scene_destroy(s);

    /* Every cut of the GLB fails cleanly (header, JSON chunk, BIN chunk). */
    int bad_cuts = 0;
    for (size_t n = 0; n < glb_len; ++n) {
        int errors = 0;
        roma_gltf_desc desc = {.logger = {count_errors, &errors}};
        roma_scene *t = SENTINEL;
        roma_result r = roma_scene_load_gltf_memory(glb, n, NULL, &desc, &t);
        if (r != ROMA_ERROR_PARSE || t != NULL || errors != 1) {
            if (bad_cuts++ < 5)
                fprintf(stderr, "GLB cut at %zu: '%s'\n", n, roma_result_string(r));
            if (r == ROMA_SUCCESS)
                roma_scene_destroy(t);
        }
    }
    CHECK(bad_cuts == 0);
    expect_code("truncated.glb", glb, glb_len / 2, ROMA_ERROR_PARSE);

    /* Broken containers. */
    unsigned char *bad = malloc(glb_len);
    uint32_t u;
    memcpy(bad, glb, glb_len);
    memcpy(&u, bad + 12, 4), u += 4, memcpy(bad + 12, &u, 4); /* JSON chunk 4 bytes too long */
    expect_code("json_chunk_length.glb", bad, glb_len, ROMA_ERROR_PARSE);
    size_t bin_at = 20 + ((strlen(glb_json) + 3) & ~(size_t)3);
    memcpy(bad, glb, glb_len);
    memcpy(&u, bad + bin_at, 4), u += 4, memcpy(bad + bin_at, &u, 4); /* BIN chunk past the end */
    expect_code("bin_chunk_length.glb", bad, glb_len, ROMA_ERROR_PARSE);
    memcpy(bad, glb, glb_len);
    memcpy(&u, bad + 8, 4), u += 4, memcpy(bad + 8, &u, 4); /* header length past the end */
    expect_code("total_length.glb", bad, glb_len, ROMA_ERROR_PARSE);
    memcpy(bad, glb, glb_len);
    bad[4] = 1; /* GLB version 1 */
    expect_code("version1.glb", bad, glb_len, ROMA_ERROR_UNSUPPORTED);
    free(bad);
    /* Buffer longer than the BIN chunk. */
    snprintf(buffer, sizeof buffer, "{\"byteLength\":%zu}", sizeof good_bin + 16);
    char *long_json = printf_doc(good_json, buffer);
    unsigned char *glb2 = malloc(strlen(long_json) + sizeof good_bin + 64);
    size_t glb2_len = make_glb(glb2, long_json, &good_bin, sizeof good_bin);
    expect_code("buffer_past_bin.glb", glb2, glb2_len, ROMA_ERROR_PARSE);
    free(glb2);
    free(long_json);

    /* External .bin beside the .gltf: found from a path or a base directory,
     * refused from memory without one. */
    char path[1024], dir[1024];
    roma_test_tmp_path("good.bin", path, sizeof path);
    write_file(path, &good_bin, sizeof good_bin);
    snprintf(buffer, sizeof buffer, "{\"byteLength\":%zu,\"uri\":\"good.bin\"}", sizeof good_bin);
    char *ext = printf_doc(good_json, buffer);
    roma_test_tmp_path("good_external.gltf", path, sizeof path);
    write_file(path, ext, strlen(ext));
    roma_gltf_desc quiet = {0};
    s = NULL;
    CHECK_RESULT(roma_scene_load_gltf(path, &quiet, &s), ROMA_SUCCESS);
    check_good_scene("good_external.gltf", s);
    roma_scene_destroy(s);
    roma_test_tmp_path("", dir, sizeof dir);
    s = NULL;
    CHECK_RESULT(roma_scene_load_gltf_memory(ext, strlen(ext), dir, NULL, &s), ROMA_SUCCESS);
    check_good_scene("good_external.gltf from memory", s);
    roma_scene_destroy(s);
    s = SENTINEL;
    roma_test_log log;
    roma_gltf_desc desc = {.logger = roma_test_logger(&log)};
    CHECK_RESULT(roma_scene_load_gltf_memory(ext, strlen(ext), NULL, &desc, &s), ROMA_ERROR_FILE_NOT_FOUND);
    CHECK(s == NULL && log.errors == 1);
    snprintf(buffer, sizeof buffer, "{\"byteLength\":%zu,\"uri\":\"missing.bin\"}", sizeof good_bin);
    char *missing = printf_doc(good_json, buffer);
    expect_code("missing_buffer.gltf", missing, strlen(missing), ROMA_ERROR_FILE_NOT_FOUND);

    free(missing);
    free(ext);
    free(glb);
    free(glb_json);
    free(gltf);
    free(uri);
}

/* --- the broken corpus: variations of a one-triangle file --- */

static const char tri_json[] =
    "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
    "\"nodes\":[{\"mesh\":0}],"
    "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
    "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
    "{\"bufferView\":1,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}],"
    "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":36},"
    "{\"buffer\":0,\"byteOffset\":36,\"byteLength\":6}],"
    "\"buffers\":[{\"byteLength\":44,\"uri\":\"%s\"}]}";

typedef struct tri_buffer {
    float pos[9];
    uint16_t idx[4]; /* 3 + padding */
} tri_buffer;

static const tri_buffer tri_bin = {{0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2, 0}};

static char *tri_doc(const char *from, const char *to, const tri_buffer *bin)
{
    char *json = subst(tri_json, from ? from : "", to ? to : "");
    char *uri = data_uri(bin ? bin : &tri_bin, sizeof tri_bin);
    char *doc = printf_doc(json, uri);
    free(json);
    free(uri);
    return doc;
}

typedef struct bad_case {
    const char *name, *from, *to;
    roma_result code;
} bad_case;

static const bad_case cases[] = {
    {"accessor_past_view.gltf", "\"count\":3,\"type\":\"VEC3\"", "\"count\":4,\"type\":\"VEC3\"",
     ROMA_ERROR_INVALID_SCENE},
    {"view_past_buffer.gltf", "\"byteOffset\":36,\"byteLength\":6", "\"byteOffset\":40,\"byteLength\":6",
     ROMA_ERROR_INVALID_SCENE},
    {"position_vec2.gltf", "\"type\":\"VEC3\"", "\"type\":\"VEC2\"", ROMA_ERROR_INVALID_SCENE},
    {"position_ushort.gltf", "\"componentType\":5126", "\"componentType\":5123", ROMA_ERROR_INVALID_SCENE},
    {"indices_float.gltf", "\"componentType\":5123", "\"componentType\":5126", ROMA_ERROR_INVALID_SCENE},
    {"stride_too_small.gltf", "\"byteLength\":36}", "\"byteLength\":36,\"byteStride\":8}",
     ROMA_ERROR_INVALID_SCENE},
    {"no_buffer_view.gltf", "{\"bufferView\":0,", "{", ROMA_ERROR_EMPTY_SCENE}, /* zeros: no area */
    {"sparse.gltf", "\"type\":\"VEC3\"",
     "\"type\":\"VEC3\",\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":1,\"componentType\":5123},"
     "\"values\":{\"bufferView\":0}}",
     ROMA_ERROR_UNSUPPORTED},
    {"points_only.gltf", "\"indices\":1}", "\"indices\":1,\"mode\":0}", ROMA_ERROR_EMPTY_SCENE},
    {"bad_mode.gltf", "\"indices\":1}", "\"indices\":1,\"mode\":9}", ROMA_ERROR_INVALID_SCENE},
    {"draco.gltf", "{\"asset\"", "{\"extensionsRequired\":[\"KHR_draco_mesh_compression\"],\"asset\"",
     ROMA_ERROR_UNSUPPORTED},
    {"meshopt.gltf", "{\"asset\"", "{\"extensionsRequired\":[\"EXT_meshopt_compression\"],\"asset\"",
     ROMA_ERROR_UNSUPPORTED},
    {"quantization.gltf", "{\"asset\"", "{\"extensionsRequired\":[\"KHR_mesh_quantization\"],\"asset\"",
     ROMA_ERROR_UNSUPPORTED},
    {"gltf1.gltf", "\"version\":\"2.0\"", "\"version\":\"1.0\"", ROMA_ERROR_UNSUPPORTED},
    {"node_cycle.gltf", "\"nodes\":[{\"mesh\":0}]", "\"nodes\":[{\"mesh\":0,\"children\":[1]},{\"children\":[0]}]",
     ROMA_ERROR_INVALID_SCENE},
    {"self_child.gltf", "{\"mesh\":0}", "{\"mesh\":0,\"children\":[0]}", ROMA_ERROR_INVALID_SCENE},
    {"two_parents.gltf", "\"nodes\":[{\"mesh\":0}]",
     "\"nodes\":[{\"mesh\":0,\"children\":[2]},{\"children\":[2]},{}]", ROMA_ERROR_INVALID_SCENE},
    {"bad_child.gltf", "{\"mesh\":0}", "{\"mesh\":0,\"children\":[5]}", ROMA_ERROR_INVALID_SCENE},
    {"bad_mesh.gltf", "{\"mesh\":0}", "{\"mesh\":4}", ROMA_ERROR_INVALID_SCENE},
    {"bad_scene.gltf", "\"scene\":0", "\"scene\":2", ROMA_ERROR_INVALID_SCENE},
    {"bad_material.gltf", "\"indices\":1}", "\"indices\":1,\"material\":3}", ROMA_ERROR_INVALID_SCENE},
    {"bad_light.gltf", "{\"mesh\":0}", "{\"mesh\":0,\"extensions\":{\"KHR_lights_punctual\":{\"light\":3}}}",
     ROMA_ERROR_INVALID_SCENE},
    {"negative_colour.gltf", "\"indices\":1}]}],",
     "\"indices\":1,\"material\":0}]}],\"materials\":[{\"pbrMetallicRoughness\":"
     "{\"baseColorFactor\":[-1,0,0,1]}}],",
     ROMA_ERROR_INVALID_SCENE},
    {"number_overflow.gltf", "{\"mesh\":0}", "{\"mesh\":0,\"scale\":[1,1e999,1]}", ROMA_ERROR_PARSE},
    /* Huge and negative counts, sizes and offsets. */
    {"huge_count.gltf", "\"count\":3,\"type\":\"VEC3\"", "\"count\":4294967295,\"type\":\"VEC3\"",
     ROMA_ERROR_INVALID_SCENE},
    {"huge_index_count.gltf", "\"count\":3,\"type\":\"SCALAR\"", "\"count\":4294967295,\"type\":\"SCALAR\"",
     ROMA_ERROR_INVALID_SCENE},
    {"count_2_64.gltf", "\"count\":3,\"type\":\"VEC3\"", "\"count\":18446744073709551615,\"type\":\"VEC3\"",
     ROMA_ERROR_INVALID_SCENE},
    {"negative_count.gltf", "\"count\":3,\"type\":\"VEC3\"", "\"count\":-3,\"type\":\"VEC3\"",
     ROMA_ERROR_PARSE},
    {"zero_count.gltf", "\"count\":3,\"type\":\"VEC3\"", "\"count\":0,\"type\":\"VEC3\"",
     ROMA_ERROR_INVALID_SCENE},
    {"huge_buffer.gltf", "\"byteLength\":44,", "\"byteLength\":1000000000000000,", ROMA_ERROR_PARSE},
    {"huge_view.gltf", "\"byteOffset\":0,\"byteLength\":36", "\"byteOffset\":0,\"byteLength\":4294967296",
     ROMA_ERROR_INVALID_SCENE},
    {"negative_offset.gltf", "\"byteOffset\":36,\"byteLength\":6", "\"byteOffset\":-36,\"byteLength\":6",
     ROMA_ERROR_PARSE},
    {"huge_offset.gltf", "\"byteOffset\":36,\"byteLength\":6",
     "\"byteOffset\":18446744073709551600,\"byteLength\":6", ROMA_ERROR_INVALID_SCENE},
    {"accessor_offset_wraps.gltf", "{\"bufferView\":0,", "{\"bufferView\":0,\"byteOffset\":18446744073709551612,",
     ROMA_ERROR_INVALID_SCENE},
    {"huge_stride.gltf", "\"byteLength\":36}", "\"byteLength\":36,\"byteStride\":4294967296}",
     ROMA_ERROR_PARSE},
    /* Trailing indices are dropped with a warning, as other loaders do. */
    {"indices_not_triangles.gltf", "\"count\":3,\"type\":\"SCALAR\"", "\"count\":2,\"type\":\"SCALAR\"",
     ROMA_ERROR_EMPTY_SCENE},
    {"negative_index.gltf", "\"indices\":1}", "\"indices\":-1}", ROMA_ERROR_PARSE},
    {"negative_attribute.gltf", "\"POSITION\":0", "\"POSITION\":-2", ROMA_ERROR_PARSE},
    {"negative_node.gltf", "\"nodes\":[0]", "\"nodes\":[-1]", ROMA_ERROR_PARSE},
    {"negative_mode.gltf", "\"indices\":1}", "\"indices\":1,\"mode\":-1}", ROMA_ERROR_PARSE},
    {"negative_child.gltf", "{\"mesh\":0}", "{\"mesh\":0,\"children\":[-4]}", ROMA_ERROR_PARSE},
    {"negative_in_extras.gltf", "{\"mesh\":0}", "{\"mesh\":0,\"extras\":{\"count\":-1}}", ROMA_SUCCESS},
    /* Transforms whose product overflows float: every factor is finite, the world
     * positions are not. */
    {"scale_overflow.gltf", "\"nodes\":[{\"mesh\":0}]",
     "\"nodes\":[{\"children\":[1],\"scale\":[1e30,1e30,1e30]},{\"mesh\":0,\"scale\":[1e30,1e30,1e30]}]",
     ROMA_ERROR_INVALID_SCENE},
    {"translation_overflow.gltf", "\"nodes\":[{\"mesh\":0}]",
     "\"nodes\":[{\"children\":[1],\"translation\":[3e38,0,0]},{\"mesh\":0,\"translation\":[3e38,0,0]}]",
     ROMA_ERROR_INVALID_SCENE},
    /* Skins and animations with dangling references. */
    {"skin_bad_joint.gltf", "\"nodes\":[{\"mesh\":0}],", "\"nodes\":[{\"mesh\":0}],\"skins\":[{\"joints\":[7]}],",
     ROMA_ERROR_INVALID_SCENE},
    {"skin_bad_matrices.gltf", "\"nodes\":[{\"mesh\":0}],",
     "\"nodes\":[{\"mesh\":0}],\"skins\":[{\"joints\":[0],\"inverseBindMatrices\":9}],",
     ROMA_ERROR_INVALID_SCENE},
    {"animation_bad_node.gltf", "\"nodes\":[{\"mesh\":0}],",
     "\"nodes\":[{\"mesh\":0}],\"animations\":[{\"channels\":[{\"sampler\":0,\"target\":"
     "{\"node\":9,\"path\":\"translation\"}}],\"samplers\":[{\"input\":1,\"output\":0}]}],",
     ROMA_ERROR_INVALID_SCENE},
    {"animation_bad_sampler.gltf", "\"nodes\":[{\"mesh\":0}],",
     "\"nodes\":[{\"mesh\":0}],\"animations\":[{\"channels\":[{\"sampler\":5,\"target\":"
     "{\"node\":0,\"path\":\"translation\"}}],\"samplers\":[{\"input\":1,\"output\":0}]}],",
     ROMA_ERROR_INVALID_SCENE},
};

static void test_corpus(void)
{
    /* The template itself is fine. */
    char *doc = tri_doc(NULL, NULL, NULL);
    roma_scene *s = NULL;
    CHECK_RESULT(load_case("tri.gltf", doc, strlen(doc), NULL, &s), ROMA_SUCCESS);
    if (s) {
        roma_scene_view v;
        roma_scene_get_view(s, &v);
        CHECK(v.triangle_count == 1 && v.vertex_count == 3 && v.material_count == 1);
        roma_scene_destroy(s);
    }

    /* Every proper prefix of valid JSON is a parse error. */
    int bad_cuts = 0;
    size_t len = strlen(doc);
    for (size_t n = 0; n < len; ++n) {
        int errors = 0;
        roma_gltf_desc desc = {.logger = {count_errors, &errors}};
        roma_scene *t = SENTINEL;
        roma_result r = roma_scene_load_gltf_memory(doc, n, NULL, &desc, &t);
        if (r != ROMA_ERROR_PARSE || t != NULL || errors != 1) {
            if (bad_cuts++ < 5)
                fprintf(stderr, "JSON cut at %zu: '%s'\n", n, roma_result_string(r));
            if (r == ROMA_SUCCESS)
                roma_scene_destroy(t);
        }
    }
    CHECK(bad_cuts == 0);
    expect_code("truncated.gltf", doc, len / 2, ROMA_ERROR_PARSE);
    free(doc);

    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        doc = tri_doc(cases[i].from, cases[i].to, NULL);
        expect_code(cases[i].name, doc, strlen(doc), cases[i].code);
        free(doc);
    }

    /* Binary-level breakage. */
    tri_buffer bin = tri_bin;
    bin.idx[2] = 7;
    doc = tri_doc(NULL, NULL, &bin);
    expect_code("index_out_of_range.gltf", doc, strlen(doc), ROMA_ERROR_INVALID_SCENE);
    free(doc);
    bin = tri_bin;
    bin.pos[4] = NAN;
    doc = tri_doc(NULL, NULL, &bin);
    expect_code("nan_position.gltf", doc, strlen(doc), ROMA_ERROR_INVALID_SCENE);
    free(doc);
    bin = tri_bin;
    bin.pos[8] = INFINITY;
    doc = tri_doc(NULL, NULL, &bin);
    expect_code("inf_position.gltf", doc, strlen(doc), ROMA_ERROR_INVALID_SCENE);
    free(doc);

    /* Warnings: a lone POINTS primitive says why the scene is empty; a LINES
     * primitive beside a triangle one is skipped and the rest loads. */
    int warnings = 0;
    doc = tri_doc("\"indices\":1}", "\"indices\":1,\"mode\":0}", NULL);
    CHECK_RESULT(load_case("points_warn.gltf", doc, strlen(doc), &warnings, NULL), ROMA_ERROR_EMPTY_SCENE);
    CHECK(warnings == 1);
    free(doc);
    doc = tri_doc("\"indices\":1}]", "\"indices\":1},{\"attributes\":{\"POSITION\":0},\"mode\":1}]", NULL);
    s = NULL;
    CHECK_RESULT(load_case("mixed_modes.gltf", doc, strlen(doc), &warnings, &s), ROMA_SUCCESS);
    CHECK(warnings == 1);
    if (s) {
        roma_scene_view v;
        roma_scene_get_view(s, &v);
        CHECK(v.triangle_count == 1);
        roma_scene_destroy(s);
    }
    free(doc);

    /* Strips and fans become triangles; a node with no scene list loads all roots. */
    const char *modes[2] = {"\"indices\":1,\"mode\":5}", "\"indices\":1,\"mode\":6}"};
    for (int m = 0; m < 2; ++m) {
        doc = tri_doc("\"indices\":1}", modes[m], NULL);
        s = NULL;
        CHECK_RESULT(load_case(m ? "fan.gltf" : "strip.gltf", doc, strlen(doc), NULL, &s), ROMA_SUCCESS);
        if (s) {
            roma_scene_view v;
            roma_scene_get_view(s, &v);
            CHECK(v.triangle_count == 1);
            roma_scene_destroy(s);
        }
        free(doc);
    }
    doc = tri_doc("\"scene\":0,\"scenes\":[{\"nodes\":[0]}],", "", NULL);
    s = NULL;
    CHECK_RESULT(load_case("no_scenes.gltf", doc, strlen(doc), NULL, &s), ROMA_SUCCESS);
    roma_scene_destroy(s);
    free(doc);

    /* Not glTF at all. */
    const char *junk[] = {"", "hello, this is not JSON", "[1, 2, 3]", "{\"asset\":{}}", "{\"asset\":{\"version\":\"2.0\"}"};
    for (int i = 0; i < 5; ++i) {
        char name[64];
        snprintf(name, sizeof name, "junk%d.gltf", i);
        expect_code(name, junk[i], strlen(junk[i]), ROMA_ERROR_PARSE);
    }
    /* Deep nesting stops at a limit instead of the stack. */
    size_t depth = 100000;
    char *deep = malloc(2 * depth + 64);
    strcpy(deep, "{\"asset\":{\"version\":\"2.0\"},\"extras\":");
    size_t at = strlen(deep);
    memset(deep + at, '[', depth);
    memset(deep + at + depth, ']', depth);
    strcpy(deep + at + 2 * depth, "}");
    expect_code("deep.gltf", deep, strlen(deep), ROMA_ERROR_PARSE);
    free(deep);

    /* A valid chain of 100,000 nodes, each the child of the one before: the node
     * walk is iterative, so this loads (no recursion to overflow the stack). */
    const uint32_t chain = 100000;
    char *nodes = malloc((size_t)chain * 64 + 64); /* each node takes under 64 characters */
    size_t at_node = 0;
    at_node += (size_t)sprintf(nodes + at_node, "\"nodes\":[");
    for (uint32_t i = 0; i + 1 < chain; ++i)
        at_node += (size_t)sprintf(nodes + at_node, "{\"children\":[%u],\"translation\":[0,0,1e-5]},", i + 1);
    sprintf(nodes + at_node, "{\"mesh\":0}]");
    doc = tri_doc("\"nodes\":[{\"mesh\":0}]", nodes, NULL);
    free(nodes);
    s = NULL;
    CHECK_RESULT(load_case("node_chain.gltf", doc, strlen(doc), NULL, &s), ROMA_SUCCESS);
    if (s) {
        roma_scene_view v;
        roma_scene_get_view(s, &v);
        CHECK(v.triangle_count == 1);
        /* The translations add up along the chain: z = 99,999 * 1e-5. */
        CHECK_NEAR(v.positions[2], 0.99999, 1e-3);
        roma_scene_destroy(s);
    }
    free(doc);

    /* Missing file and bad arguments. */
    char path[1024];
    roma_test_log log;
    roma_gltf_desc desc = {.logger = roma_test_logger(&log)};
    s = SENTINEL;
    CHECK_RESULT(roma_scene_load_gltf(roma_test_tmp_path("does_not_exist.glb", path, sizeof path), &desc, &s),
                 ROMA_ERROR_FILE_NOT_FOUND);
    CHECK(s == NULL && log.errors == 1);
    s = SENTINEL;
    CHECK_RESULT(roma_scene_load_gltf(NULL, &desc, &s), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(s == NULL);
    CHECK_RESULT(roma_scene_load_gltf(path, &desc, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    s = SENTINEL;
    CHECK_RESULT(roma_scene_load_gltf_memory(NULL, 10, NULL, &desc, &s), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(s == NULL);
    s = SENTINEL;
    CHECK_RESULT(roma_scene_load_gltf_memory(NULL, 0, NULL, &desc, &s), ROMA_ERROR_PARSE);
    CHECK(s == NULL);
}

/* A few bytes of glTF can describe gigabytes: accessors without data, and
 * instances of one mesh. Both are refused before anything is allocated. */
static void test_size_limits(void)
{
    /* One zero accessor of 2^23 + 1 elements used twice (POSITION and NORMAL):
     * more than 2^24 zero elements in all. */
    char *json = subst(tri_json, "\"attributes\":{\"POSITION\":0},\"indices\":1}",
                       "\"attributes\":{\"POSITION\":2,\"NORMAL\":2}}");
    char *json2 = subst(json, "\"type\":\"SCALAR\"}]",
                        "\"type\":\"SCALAR\"},{\"componentType\":5126,\"count\":8388609,\"type\":\"VEC3\"}]");
    char *uri = data_uri(&tri_bin, sizeof tri_bin);
    char *doc = printf_doc(json2, uri);
    expect_code("zero_accessor_twice.gltf", doc, strlen(doc), ROMA_ERROR_INVALID_SCENE);
    free(doc), free(uri), free(json2), free(json);

    /* Two instances of the one-triangle mesh: 6 vertices, 2 triangles. */
    doc = tri_doc("\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}]",
                  "\"scenes\":[{\"nodes\":[0,1]}],\"nodes\":[{\"mesh\":0},{\"mesh\":0}]", NULL);
    struct {
        uint32_t max_vertices, max_triangles;
        roma_result expect;
    } limits[] = {{5, 0, ROMA_ERROR_UNSUPPORTED}, {0, 1, ROMA_ERROR_UNSUPPORTED}, {6, 2, ROMA_SUCCESS}};
    for (int i = 0; i < 3; ++i) {
        int errors = 0;
        roma_gltf_desc desc = {.logger = {count_errors, &errors},
                               .max_vertices = limits[i].max_vertices,
                               .max_triangles = limits[i].max_triangles};
        roma_scene *s = SENTINEL;
        roma_result r = roma_scene_load_gltf_memory(doc, strlen(doc), NULL, &desc, &s);
        CHECK_RESULT(r, limits[i].expect);
        if (r == ROMA_SUCCESS) {
            roma_scene_view v;
            roma_scene_get_view(s, &v);
            CHECK(v.triangle_count == 2 && v.vertex_count == 6 && errors == 0);
            roma_scene_destroy(s);
        } else {
            CHECK(s == NULL && errors == 1);
        }
    }
    free(doc);
}

/* roma_gltf_desc.camera_index picks among a file's perspective cameras (2CylinderEngine
 * has one; a file with two, each with its own placement and field of view, all of them
 * listed in roma_scene_view.cameras); the animations keep their names (Fox: Survey, Walk,
 * Run), also in a posed copy. */
static void test_cameras_and_names(void)
{
    char *two = subst(tri_json, "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],",
                      "\"scenes\":[{\"nodes\":[0,1,2]}],\"nodes\":[{\"mesh\":0},"
                      "{\"camera\":0,\"translation\":[0,0,5]},"
                      "{\"camera\":1,\"translation\":[3,0,0],\"rotation\":[0,0.70710678118,0,0.70710678118]}],"
                      "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.5,\"znear\":0.1}},"
                      "{\"type\":\"perspective\",\"perspective\":{\"yfov\":1.0,\"znear\":0.1}}],");
    char *uri = data_uri(&tri_bin, sizeof tri_bin);
    char *doc = printf_doc(two, uri);
    const double deg = 180.0 / 3.14159265358979;
    for (uint32_t k = 0; k < 2; ++k) {
        roma_scene *s = NULL;
        CHECK_RESULT(roma_scene_load_gltf_memory(doc, strlen(doc), NULL, &(roma_gltf_desc){.camera_index = k}, &s),
                     ROMA_SUCCESS);
        roma_scene_view v;
        roma_scene_get_view(s, &v);
        CHECK(s && v.has_camera && v.camera_count == 2);
        if (!s || v.camera_count != 2)
            continue;
        /* Camera 1 is turned a quarter about y: it looks along -x. */
        if (k == 0) {
            CHECK_VEC(v.camera.eye, 0, 0, 5);
            CHECK_VEC(v.camera.target, 0, 0, 4);
        } else {
            CHECK_VEC(v.camera.eye, 3, 0, 0);
            CHECK_VEC(v.camera.target, 2, 0, 0);
        }
        CHECK_NEAR(v.camera.fovy_deg, (k ? 1.0 : 0.5) * deg, 1e-4);
        CHECK_VEC(v.cameras[0].eye, 0, 0, 5);
        CHECK_NEAR(v.cameras[0].fovy_deg, 0.5 * deg, 1e-4);
        CHECK_VEC(v.cameras[1].eye, 3, 0, 0);
        CHECK_NEAR(v.cameras[1].fovy_deg, 1.0 * deg, 1e-4);
        roma_scene_destroy(s);
    }
    free(doc);
    free(uri);
    free(two);

    char path[1024];
    if (roma_test_scene_file("2CylinderEngine.glb", path, sizeof path)) {
        roma_scene *s = NULL;
        CHECK_RESULT(roma_scene_load_gltf(path, &(roma_gltf_desc){.camera_index = 0}, &s), ROMA_SUCCESS);
        roma_scene_view v;
        roma_scene_get_view(s, &v);
        CHECK(s && v.has_camera);
        roma_scene_destroy(s);
        int errors = 0;
        s = SENTINEL;
        CHECK_RESULT(roma_scene_load_gltf(path, &(roma_gltf_desc){.logger = {count_errors, &errors}, .camera_index = 1},
                                          &s),
                     ROMA_ERROR_INVALID_ARGUMENT);
        CHECK(s == NULL && errors == 1);
    }
    if (roma_test_scene_file("Fox.glb", path, sizeof path)) {
        roma_scene *s = NULL;
        CHECK_RESULT(roma_scene_load_gltf(path, NULL, &s), ROMA_SUCCESS);
        roma_scene_view v;
        roma_scene_get_view(s, &v);
        const char *want[3] = {"Survey", "Walk", "Run"};
        CHECK(v.animation.animation_count == 3 && v.animation.animation_names);
        for (int i = 0; v.animation.animation_names && i < 3; ++i)
            CHECK(strcmp(v.animation.animation_names[i], want[i]) == 0);
        roma_scene *posed = NULL;
        CHECK_RESULT(roma_scene_pose(s, &(roma_animator_pose){.clip = 1, .time = 0.5f}, NULL, &posed), ROMA_SUCCESS);
        roma_scene_view pv;
        roma_scene_get_view(posed, &pv);
        CHECK(pv.animation.animation_names && strcmp(pv.animation.animation_names[2], "Run") == 0);
        roma_scene_destroy(posed);
        roma_scene_destroy(s);
    }
}

int main(void)
{
    test_good();
    test_corpus();
    test_size_limits();
    test_cameras_and_names();
    return roma_test_finish("test_gltf_loader");
}
