/* roma-render: renders the effects of a scene to PFM (exact) and PNG (tone-mapped)
 * and writes a stats JSON. The main job of libroma. */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "app_common.h"
#include "budget.h"
#include "effect_api.h"
#include "reference.h"
#include "roma/builtin_scenes.h"
#include "roma/roma.h"
#include "stats_json.h"

static const char *usage =
    "usage: roma-render [options]\n"
    "  --scene FILE|builtin:NAME   glTF 2.0 file (.gltf/.glb) or a built-in scene (default builtin:cornell)\n"
    "  --camera ex,ey,ez,tx,ty,tz,fovy   eye, target and vertical field of view in degrees\n"
    "                              (y up; default: the scene's camera, else one whose picture the\n"
    "                              scene's bounding box fills to 90%)\n"
    "  --size WxH                  image size in pixels (default 640x480)\n"
    "  --effects LIST              comma-separated: ao,direct,gi,lights (default: what the scene\n"
    "                              calls for: ao, plus direct and gi when it has lights; printed)\n"
    "  --tracer embree|roma        embree = CPU reference (ground truth); roma = ROMA on the GPU\n"
    "                              (gi on ROMA: the direct light at each bounce hit, from every light).\n"
    "                              ROMA runs only the passes the scene calls for (see the stats file)\n"
    "  --res N                     ROMA grid resolution: 32, 64, 128 or 256 (default: the preset's, 128)\n"
    "  --angular A                 ROMA A x A candidate directions for ao and gi, 1..16 (default: the\n"
    "                              preset's, 4)\n"
    "  --preset NAME               ROMA quality preset: low (RES 128, A 2), medium (128, 4, the default),\n"
    "                              high (256, 4), ultra (256, 8): the measured accuracy-time front;\n"
    "                              --res and --angular override it\n"
    "  --budget-ms T               ROMA: the most accurate preset whose time per frame fits T ms here\n"
    "                              (measured once per device, scene, size and effects, then cached)\n"
    "  --budget-cache FILE         where those times are kept (default\n"
    "                              $XDG_CACHE_HOME/libroma/budget.tsv or ~/.cache/libroma/budget.tsv)\n"
    "  --shadow-angular A          ROMA A for shadow rays (direct, lights), 1..16 (default 8)\n"
    "  --max-steps N               ROMA un-snapped shadow rays: texels walked at most (default 8)\n"
    "  --cascades K                ROMA: K nested grids around the camera, each twice the last's size\n"
    "                              (1..8; default: with AO where the grid holding the scene's part\n"
    "                              nearest the camera (the finest, for a camera inside the scene) has\n"
    "                              cells at least twice as fine as one grid over the scene, enough to\n"
    "                              cover it, else 1: one grid; at most 4 for the shadow rays' A 8\n"
    "                              arrays); the public effect passes only\n"
    "  --jitter on|off             ROMA: a new grid placement and new candidate directions each frame\n"
    "                              (on, the default), or the first frame's in every frame (off: maps\n"
    "                              that did not move are kept); the public effect passes only\n"
    "  --finest-extent E           ROMA: the finest cascade grid's edge in scene units (default: RES x\n"
    "                              the AO radius / 30, 30 cells to the radius; with an unbounded\n"
    "                              radius and --cascades K, the edge of the cube around the camera\n"
    "                              that holds the scene / 2^(K-1))\n"
    "  --ao-method roma|voxel-dda|distance-field|naadf|screen-space\n"
    "                              ROMA ao through the ROMA maps (default), or a baseline: every ray\n"
    "                              walked exactly through the voxel grid (the voxelization's own error),\n"
    "                              sphere-traced through a distance field built from it every frame,\n"
    "                              through the NAADF hierarchy built from it every frame (the voxels of\n"
    "                              voxel-dda, empty space skipped a box at a time), or marched in screen\n"
    "                              space against the G-buffer's depth (ao alone); each through the\n"
    "                              public AO pass, on one grid\n"
    "  --shadow-method roma|voxel-dda  ROMA direct light, gi and lights: shadow, bounce and visibility\n"
    "                              rays through the ROMA maps (default), or each walked exactly through\n"
    "                              the voxel grid to its end (the study's baseline); the public passes\n"
    "  --ssao-layers K             screen-space ao: also against K layers of a stochastic depth map\n"
    "                              rasterized every frame (0..8, default 0: the depth buffer alone)\n"
    "  --ray-start walk|surfaces|blind  ROMA rays' skipped start: walked exactly through the voxel\n"
    "                              grid, so that no ray passes a wall it starts next to (default); for\n"
    "                              ao, where that walk meets an occupied cell, the surface grid's\n"
    "                              triangles decide (surfaces: finer geometry, more time); or skipped\n"
    "                              unseen (the rule before, which leaks light at corners)\n"
    "  --ao-trace maps|surfaces    ROMA ao rays past their start: one snapped query through the\n"
    "                              rotated maps (default), or the ray itself walked through the\n"
    "                              surface grid, the maps deciding where a cell holds more triangles\n"
    "                              than the grid keeps (closer to the reference, more time)\n"
    "  --resolution-divisor 1|2|4  the public effects trace one pixel of each 2x2 or 4x4 block a\n"
    "                              frame (a new one each frame) and upsample the rest (default 1)\n"
    "  --pixel-dispatch auto|list|every|shared  the public passes over a list of the covered pixels\n"
    "                              each effect makes, over every pixel (roma_pixel_dispatch), or over\n"
    "                              one list for every effect and frame (roma_pixel_list); auto: shared\n"
    "                              on CPU devices, every pixel on GPUs\n"
    "  --gi-punctual rsm|rays      ROMA gi from point and spot lights: one shadow ray per light at each\n"
    "                              bounce hit (the public GI effect's way, the default), or their\n"
    "                              reflective shadow maps (the ROMA paper's, from the study library;\n"
    "                              docs/accuracy.md compares them)\n"
    "  --skip C                    ROMA shadow rays skip their first C trace cells (default 1)\n"
    "  --ao-skip C                 ROMA ao and gi rays skip their first C trace cells (default 1.6)\n"
    "  --offset C                  ROMA rays start C trace cells off the surface (default 1.5)\n"
    "  --lights-per-frame K        ROMA lights: test K random lights per pixel and frame\n"
    "                              (stochastic, accumulated) instead of all (default: all)\n"
    "  --spp N                     samples per pixel for ao, area lights and gi (default 64)\n"
    "  --frames N                  ROMA: frames accumulated, each with new jitter and new samples\n"
    "                              (frame f uses samples f*spp .. f*spp+spp-1, so the reference with\n"
    "                              --spp spp*frames traces the same directions)\n"
    "  --ao-radius R|inf           AO ray length in scene units (default: 10% of the scene's\n"
    "                              diagonal, printed; inf: unbounded, which is 0 everywhere in a\n"
    "                              closed room)\n"
    "  --lights N                  point lights for the many-lights effect (default 256)\n"
    "  --light SPEC                a light added to the scene (repeatable; the direct and gi effects\n"
    "                              use it): point:x,y,z:r,g,b:candela, spot:x,y,z:dx,dy,dz:r,g,b:\n"
    "                              candela:degrees (outer cone), sun:dx,dy,dz:r,g,b:lux (dx,dy,dz:\n"
    "                              where the light points)\n"
    "  --seed N                    sample-sequence seed (default 1)\n"
    "  --threads N                 CPU threads for the reference (default: all cores)\n"
    "  --out DIR                   output folder (default out); writes DIR/<effect>.<format>,\n"
    "                              coverage (1 where a surface is seen) and distance (from the eye)\n"
    "  --format LIST               output formats, comma-separated: pfm (linear float), png (8-bit\n"
    "                              sRGB), exr (OpenEXR, linear 32-bit float); default pfm,png\n"
    "  --stats FILE.json           write device, scene size, settings, timings and notes\n"
    "  --exposure E                PNG only: linear values times E before sRGB (default 1)\n"
    "  --tonemap clamp|reinhard    PNG only: clip at 1, or c / (1 + c) per channel after the\n"
    "                              exposure, which keeps bright areas apart (default clamp)\n"
    "  --background R,G,B          PNG only: colour (sRGB, 0..1) of pixels that see no geometry\n"
    "                              (default 0.12,0.13,0.16, so white models stand out)\n"
    "  --up +y|-y|+z               the scene's up axis, turned to +y (tabletop.gltf: -y; z-up CAD\n"
    "                              files: +z; default +y)\n"
    "  --time SECONDS              an animated glTF posed at this time of its clip (both tracers;\n"
    "                              default: the rest pose)\n"
    "  --clip N                    which animation --time plays (default 0)\n"
    "  --animation NAME|INDEX      the same by the glTF animation's name or index; without --time,\n"
    "                              the pose at time 0\n"
    "  --gltf-camera N             which of a glTF file's perspective cameras to use (default 0:\n"
    "                              the first; --camera overrides)\n"
    "  --list-scenes               print the built-in scene names\n"
    "  --quiet                     no progress lines (none either when stderr is not a terminal,\n"
    "                              but a line per 10%)\n"
    "  --help\n";

typedef struct options {
    const char *scene, *out, *stats, *tracer;
    roma_camera camera;
    int has_camera;
    uint32_t width, height, effects, spp, frames, lights, seed, threads, res, angular;
    uint32_t shadow_angular, max_steps, lights_per_frame;
    uint32_t cascades;    /* --cascades; 0: unset (one grid) */
    int cascades_auto;    /* 1: cascades chosen (roma_app_auto_cascades) */
    float finest_extent;  /* --finest-extent; 0: derived */
    int jitter_off;       /* --jitter off: every frame's grids and directions the first's */
    float skip, ao_skip; /* < 0: unset (library default) */
    float offset;        /* 0: unset (library default) */
    float ao_radius;
    float time;          /* < 0: unset (rest pose) */
    uint32_t clip;
    int quiet;
    uint32_t formats;    /* FORMAT_* bits */
    float ao_radius_auto; /* 1: ao_radius was derived from the scene */
    float exposure;
    int reinhard;        /* --tonemap reinhard */
    int gi_rays;         /* --gi-punctual rays */
    roma_pixel_dispatch pixel_dispatch; /* --pixel-dispatch */
    int shared_list;     /* --pixel-dispatch shared */
    uint32_t resolution_divisor; /* --resolution-divisor: the public effects trace 1 pixel in d x d */
    int blind_start;     /* --ray-start blind */
    roma_ao_start ao_start; /* --ray-start surfaces */
    roma_ao_trace ao_trace; /* --ao-trace surfaces */
    roma_ao_method ao_method; /* --ao-method */
    roma_shadow_method shadow_method; /* --shadow-method */
    uint32_t ssao_layers;     /* --ssao-layers */
    float background[3];
    roma_light extra_lights[16];
    uint32_t extra_light_count;
    uint32_t given;      /* GIVEN_* bits: options a tracer may ignore */
    const char *up;      /* --up; NULL = +y */
    const char *animation; /* --animation NAME|INDEX; NULL: --clip */
    uint32_t gltf_camera;
    roma_preset preset;  /* --preset; 0: none given */
    double budget_ms;    /* --budget-ms; 0: none */
    const char *budget_cache; /* --budget-cache; NULL: budget_default_cache() */
} options;

/* Options that only one tracer reads (a warning when the other ignores them). */
enum {
    GIVEN_FRAMES = 1u << 0, GIVEN_RES = 1u << 1, GIVEN_ANGULAR = 1u << 2, GIVEN_SHADOW_ANGULAR = 1u << 3,
    GIVEN_MAX_STEPS = 1u << 4, GIVEN_SKIP = 1u << 5, GIVEN_AO_SKIP = 1u << 6, GIVEN_OFFSET = 1u << 7,
    GIVEN_LIGHTS_PER_FRAME = 1u << 8, GIVEN_THREADS = 1u << 9, GIVEN_AO_RADIUS = 1u << 10,
    GIVEN_GI_PUNCTUAL = 1u << 11, GIVEN_EFFECTS = 1u << 12, GIVEN_RAY_START = 1u << 13, GIVEN_AO_METHOD = 1u << 14,
    GIVEN_PRESET = 1u << 15, GIVEN_BUDGET = 1u << 16, GIVEN_PIXEL_DISPATCH = 1u << 18,
    GIVEN_CASCADES = 1u << 19, GIVEN_FINEST_EXTENT = 1u << 20, GIVEN_RESOLUTION_DIVISOR = 1u << 21,
    GIVEN_SHADOW_METHOD = 1u << 22, GIVEN_AO_TRACE = 1u << 23
};

/* How ROMA's images are made (effect_api.h). */

static const char *const option_names[] = {
    "--scene", "--camera", "--size", "--effects", "--tracer", "--res", "--angular", "--shadow-angular",
    "--max-steps", "--cascades", "--finest-extent", "--jitter", "--gi-punctual", "--pixel-dispatch", "--resolution-divisor", "--ray-start", "--ao-trace", "--ao-method", "--shadow-method", "--skip",
    "--ao-skip", "--offset",
    "--lights-per-frame", "--spp", "--frames", "--ao-radius",
    "--lights", "--light", "--seed", "--threads", "--out", "--format", "--stats", "--exposure", "--tonemap",
    "--background",
    "--time", "--clip", "--animation", "--gltf-camera", "--up", "--list-scenes", "--quiet", "--help", "--preset",
    "--budget-ms", "--budget-cache", NULL};

enum { FORMAT_PFM = 1u << 0, FORMAT_PNG = 1u << 1, FORMAT_EXR = 1u << 2 };

static int parse_formats(const char *s, uint32_t *out)
{
    *out = 0;
    char buf[256];
    snprintf(buf, sizeof buf, "%s", s);
    for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        if (strcmp(tok, "pfm") == 0) *out |= FORMAT_PFM;
        else if (strcmp(tok, "png") == 0) *out |= FORMAT_PNG;
        else if (strcmp(tok, "exr") == 0) *out |= FORMAT_EXR;
        else {
            fprintf(stderr, "roma-render: unknown format '%s' (valid: pfm, png, exr)\n", tok);
            return 0;
        }
    }
    return *out != 0;
}

static int parse_u32(const char *s, uint32_t min, uint32_t max, uint32_t *out)
{
    char *end;
    errno = 0;
    unsigned long v = strtoul(s, &end, 10);
    if (errno || end == s || *end || s[0] == '-' || v < min || v > max)
        return 0;
    *out = (uint32_t)v;
    return 1;
}

static int parse_effects(const char *s, uint32_t *out)
{
    static const char *const names[] = {"ao", "direct", "gi", "lights", NULL};
    *out = 0;
    char buf[256];
    snprintf(buf, sizeof buf, "%s", s);
    for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        if (strcmp(tok, "ao") == 0) *out |= ROMA_EFFECT_AO;
        else if (strcmp(tok, "direct") == 0) *out |= ROMA_EFFECT_DIRECT;
        else if (strcmp(tok, "gi") == 0) *out |= ROMA_EFFECT_GI;
        else if (strcmp(tok, "lights") == 0) *out |= ROMA_EFFECT_LIGHTS;
        else {
            const char *near = roma_app_suggest(tok, names);
            fprintf(stderr, "roma-render: unknown effect '%s' (valid: ao, direct, gi, lights)%s%s%s\n", tok,
                    near ? "; did you mean " : "", near ? near : "", near ? "?" : "");
            return 0;
        }
    }
    return *out != 0;
}

/* n comma-separated floats and nothing else. */
static int parse_floats(const char *s, float *v, int n)
{
    for (int i = 0; i < n; ++i) {
        char *end;
        v[i] = strtof(s, &end);
        if (end == s || !isfinite(v[i]))
            return 0;
        s = end;
        if (i + 1 < n && *s++ != ',')
            return 0;
    }
    return *s == '\0';
}

/* point:x,y,z:r,g,b:candela | spot:x,y,z:dx,dy,dz:r,g,b:candela:degrees | sun:dx,dy,dz:r,g,b:lux */
static int parse_light(const char *spec, roma_light *l)
{
    char buf[512];
    snprintf(buf, sizeof buf, "%s", spec);
    char *parts[6] = {0};
    int n = 0;
    for (char *save = NULL, *tok = strtok_r(buf, ":", &save); tok && n < 6; tok = strtok_r(NULL, ":", &save))
        parts[n++] = tok;
    memset(l, 0, sizeof *l);
    int ok = 0;
    if (n == 4 && strcmp(parts[0], "point") == 0) {
        l->type = ROMA_LIGHT_POINT;
        ok = parse_floats(parts[1], l->position, 3) && parse_floats(parts[2], l->color, 3) &&
             parse_floats(parts[3], &l->intensity, 1);
    } else if (n == 6 && strcmp(parts[0], "spot") == 0) {
        float degrees = 0.0f;
        l->type = ROMA_LIGHT_SPOT;
        ok = parse_floats(parts[1], l->position, 3) && parse_floats(parts[2], l->direction, 3) &&
             parse_floats(parts[3], l->color, 3) && parse_floats(parts[4], &l->intensity, 1) &&
             parse_floats(parts[5], &degrees, 1) && degrees > 0.0f && degrees < 90.0f;
        l->outer_cone_angle = degrees * 3.14159265f / 180.0f;
    } else if (n == 4 && strcmp(parts[0], "sun") == 0) {
        l->type = ROMA_LIGHT_DIRECTIONAL;
        ok = parse_floats(parts[1], l->direction, 3) && parse_floats(parts[2], l->color, 3) &&
             parse_floats(parts[3], &l->intensity, 1);
    }
    if (ok && l->type != ROMA_LIGHT_POINT) {
        float len = sqrtf(l->direction[0] * l->direction[0] + l->direction[1] * l->direction[1] +
                          l->direction[2] * l->direction[2]);
        ok = len > 0.0f;
        for (int i = 0; ok && i < 3; ++i)
            l->direction[i] /= len;
    }
    if (!ok)
        fprintf(stderr, "roma-render: bad light '%s' (point:x,y,z:r,g,b:candela, "
                        "spot:x,y,z:dx,dy,dz:r,g,b:candela:degrees or sun:dx,dy,dz:r,g,b:lux)\n", spec);
    return ok && l->intensity > 0.0f;
}

static int parse_camera(const char *s, roma_camera *cam)
{
    float v[7];
    char tail;
    if (sscanf(s, "%f,%f,%f,%f,%f,%f,%f%c", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6], &tail) != 7)
        return 0;
    memset(cam, 0, sizeof *cam);
    for (int i = 0; i < 3; ++i) {
        cam->eye[i] = v[i];
        cam->target[i] = v[3 + i];
    }
    cam->fovy_deg = v[6];
    roma_camera_frame f;
    return roma_camera_make_frame(cam, 1, 1, &f);
}

static int parse_args(int argc, char **argv, options *o)
{
    memset(o, 0, sizeof *o);
    o->time = -1.0f;
    o->scene = "builtin:cornell";
    o->out = "out";
    o->tracer = "embree";
    o->width = 640, o->height = 480, o->effects = ROMA_EFFECT_AO, o->spp = 64, o->frames = 1; /* effects: see say_what_happens */
    o->lights = 256, o->seed = 1, o->res = 128, o->angular = 4, o->shadow_angular = 8;
    o->max_steps = ROMA_DEFAULT_SHADOW_STEPS;
    o->skip = o->ao_skip = -1.0f;
    o->formats = FORMAT_PFM | FORMAT_PNG;
    o->exposure = 1.0f;
    o->background[0] = 0.12f, o->background[1] = 0.13f, o->background[2] = 0.16f;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        int ok = 1, used = 1;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            fputs(usage, stdout);
            exit(0);
        } else if (strcmp(a, "--list-scenes") == 0) {
            for (const char *const *n = roma_builtin_scene_names(); *n; ++n)
                printf("builtin:%s\n", *n);
            exit(0);
        } else if (strcmp(a, "--quiet") == 0) {
            o->quiet = 1, used = 0;
        } else if (!v) {
            fprintf(stderr, "roma-render: %s needs a value (see --help)\n", a);
            return 0;
        } else if (strcmp(a, "--scene") == 0) o->scene = v;
        else if (strcmp(a, "--out") == 0) o->out = v;
        else if (strcmp(a, "--format") == 0) ok = parse_formats(v, &o->formats);
        else if (strcmp(a, "--animation") == 0) o->animation = v;
        else if (strcmp(a, "--gltf-camera") == 0) ok = parse_u32(v, 0, 1u << 20, &o->gltf_camera);
        else if (strcmp(a, "--up") == 0) {
            o->up = v;
            if (!roma_app_valid_up(v)) {
                fprintf(stderr, "roma-render: bad value for --up: '%s' (valid: +y, -y, +z)\n", v);
                return 0;
            }
        }
        else if (strcmp(a, "--exposure") == 0) ok = parse_floats(v, &o->exposure, 1) && o->exposure > 0.0f;
        else if (strcmp(a, "--ssao-layers") == 0) ok = parse_u32(v, 0, ROMA_AO_SSAO_MAX_LAYERS, &o->ssao_layers);
        else if (strcmp(a, "--shadow-method") == 0) {
            o->given |= GIVEN_SHADOW_METHOD;
            o->shadow_method = strcmp(v, "voxel-dda") == 0 ? ROMA_SHADOW_METHOD_VOXEL_DDA : ROMA_SHADOW_METHOD_ROMA;
            if (o->shadow_method == ROMA_SHADOW_METHOD_ROMA && strcmp(v, "roma") != 0) {
                fprintf(stderr, "roma-render: unknown shadow method '%s' (valid: roma, voxel-dda)\n", v);
                return 0;
            }
        } else if (strcmp(a, "--ao-method") == 0) {
            o->given |= GIVEN_AO_METHOD;
            if (strcmp(v, "roma") == 0)
                o->ao_method = ROMA_AO_METHOD_ROMA;
            else if (strcmp(v, "voxel-dda") == 0)
                o->ao_method = ROMA_AO_METHOD_VOXEL_DDA;
            else if (strcmp(v, "distance-field") == 0)
                o->ao_method = ROMA_AO_METHOD_DISTANCE_FIELD;
            else if (strcmp(v, "screen-space") == 0)
                o->ao_method = ROMA_AO_METHOD_SCREEN_SPACE;
            else if (strcmp(v, "naadf") == 0)
                o->ao_method = ROMA_AO_METHOD_NAADF;
            else {
                fprintf(stderr, "roma-render: unknown ao method '%s' (valid: roma, voxel-dda, distance-field, "
                        "naadf, screen-space)\n", v);
                return 0;
            }
        }
        else if (strcmp(a, "--ray-start") == 0) {
            o->blind_start = strcmp(v, "blind") == 0;
            o->ao_start = strcmp(v, "surfaces") == 0 ? ROMA_AO_START_SURFACES : ROMA_AO_START_VOXELS;
            o->given |= GIVEN_RAY_START;
            if (!o->blind_start && strcmp(v, "walk") != 0 && strcmp(v, "surfaces") != 0) {
                fprintf(stderr, "roma-render: unknown ray start '%s' (valid: walk, surfaces, blind)\n", v);
                return 0;
            }
        }
        else if (strcmp(a, "--ao-trace") == 0) {
            if (strcmp(v, "maps") != 0 && strcmp(v, "surfaces") != 0) {
                fprintf(stderr, "roma-render: unknown ao trace '%s' (valid: maps, surfaces)\n", v);
                return 0;
            }
            o->ao_trace = strcmp(v, "surfaces") == 0 ? ROMA_AO_TRACE_SURFACES : ROMA_AO_TRACE_MAPS;
            o->given |= GIVEN_AO_TRACE;
        }
        else if (strcmp(a, "--pixel-dispatch") == 0) {
            int k = strcmp(v, "auto") == 0    ? 0
                    : strcmp(v, "list") == 0  ? 1
                    : strcmp(v, "every") == 0 ? 2
                    : strcmp(v, "shared") == 0 ? 3
                                               : -1;
            if (k < 0) {
                fprintf(stderr, "roma-render: unknown pixel dispatch '%s' (valid: auto, list, every, shared)\n", v);
                return 0;
            }
            o->pixel_dispatch = k == 1 ? ROMA_PIXEL_DISPATCH_LIST
                                : k == 2 ? ROMA_PIXEL_DISPATCH_EVERY_PIXEL : ROMA_PIXEL_DISPATCH_AUTO;
            o->shared_list = k == 3;
            o->given |= GIVEN_PIXEL_DISPATCH;
        }
        else if (strcmp(a, "--gi-punctual") == 0) {
            o->gi_rays = strcmp(v, "rays") == 0;
            o->given |= GIVEN_GI_PUNCTUAL;
            if (!o->gi_rays && strcmp(v, "rsm") != 0) {
                fprintf(stderr, "roma-render: unknown gi route '%s' (valid: rsm, rays)\n", v);
                return 0;
            }
        }
        else if (strcmp(a, "--tonemap") == 0) {
            o->reinhard = strcmp(v, "reinhard") == 0;
            if (!o->reinhard && strcmp(v, "clamp") != 0) {
                fprintf(stderr, "roma-render: unknown tone map '%s' (valid: clamp, reinhard)\n", v);
                return 0;
            }
        }
        else if (strcmp(a, "--background") == 0)
            ok = parse_floats(v, o->background, 3) && o->background[0] >= 0.0f && o->background[1] >= 0.0f &&
                 o->background[2] >= 0.0f && o->background[0] <= 1.0f && o->background[1] <= 1.0f &&
                 o->background[2] <= 1.0f;
        else if (strcmp(a, "--light") == 0) {
            if (o->extra_light_count == sizeof o->extra_lights / sizeof o->extra_lights[0]) {
                fprintf(stderr, "roma-render: at most 16 --light options\n");
                return 0;
            }
            if (!parse_light(v, &o->extra_lights[o->extra_light_count]))
                return 0;
            ++o->extra_light_count;
        }
        else if (strcmp(a, "--stats") == 0) o->stats = v;
        else if (strcmp(a, "--tracer") == 0) o->tracer = v;
        else if (strcmp(a, "--camera") == 0) ok = o->has_camera = parse_camera(v, &o->camera);
        else if (strcmp(a, "--size") == 0) {
            unsigned w = 0, h = 0;
            char tail;
            ok = sscanf(v, "%ux%u%c", &w, &h, &tail) == 2 && w >= 1 && h >= 1 && w <= 16384 && h <= 16384;
            o->width = w, o->height = h;
        } else if (strcmp(a, "--effects") == 0) ok = parse_effects(v, &o->effects), o->given |= GIVEN_EFFECTS;
        else if (strcmp(a, "--spp") == 0) ok = parse_u32(v, 1, 1u << 20, &o->spp);
        else if (strcmp(a, "--frames") == 0) ok = parse_u32(v, 1, 1u << 20, &o->frames), o->given |= GIVEN_FRAMES;
        else if (strcmp(a, "--lights") == 0) ok = parse_u32(v, 1, 1u << 16, &o->lights);
        else if (strcmp(a, "--seed") == 0) ok = parse_u32(v, 0, UINT32_MAX, &o->seed);
        else if (strcmp(a, "--threads") == 0) ok = parse_u32(v, 1, 1024, &o->threads), o->given |= GIVEN_THREADS;
        else if (strcmp(a, "--resolution-divisor") == 0) {
            ok = parse_u32(v, 1, 4, &o->resolution_divisor) && o->resolution_divisor != 3;
            if (!ok) {
                fprintf(stderr, "roma-render: bad value for --resolution-divisor: '%s' (valid: 1, 2, 4)\n", v);
                return 0;
            }
            o->given |= GIVEN_RESOLUTION_DIVISOR;
        } else if (strcmp(a, "--res") == 0) {
            ok = parse_u32(v, 32, 256, &o->res) && (o->res == 32 || o->res == 64 || o->res == 128 || o->res == 256);
            o->given |= GIVEN_RES;
            if (!ok) {
                fprintf(stderr, "roma-render: bad value for --res: '%s' (valid: 32, 64, 128, 256)\n", v);
                return 0;
            }
        } else if (strcmp(a, "--angular") == 0) ok = parse_u32(v, 1, 16, &o->angular), o->given |= GIVEN_ANGULAR;
        else if (strcmp(a, "--preset") == 0) {
            o->given |= GIVEN_PRESET;
            if (roma_preset_parse(v, &o->preset) != ROMA_SUCCESS) {
                fprintf(stderr, "roma-render: bad value for --preset: '%s' (valid: low, medium, high, ultra)\n", v);
                return 0;
            }
        } else if (strcmp(a, "--budget-ms") == 0) {
            o->given |= GIVEN_BUDGET;
            char *end = NULL;
            o->budget_ms = strtod(v, &end);
            ok = end != v && !*end && o->budget_ms > 0.0 && isfinite(o->budget_ms);
        } else if (strcmp(a, "--budget-cache") == 0) {
            o->budget_cache = v;
            ok = *v != '\0';
        }
        else if (strcmp(a, "--shadow-angular") == 0)
            ok = parse_u32(v, 1, 16, &o->shadow_angular), o->given |= GIVEN_SHADOW_ANGULAR;
        else if (strcmp(a, "--max-steps") == 0) ok = parse_u32(v, 1, 1024, &o->max_steps), o->given |= GIVEN_MAX_STEPS;
        else if (strcmp(a, "--cascades") == 0)
            ok = parse_u32(v, 1, ROMA_MAX_LEVELS, &o->cascades), o->given |= GIVEN_CASCADES;
        else if (strcmp(a, "--jitter") == 0) {
            ok = strcmp(v, "on") == 0 || strcmp(v, "off") == 0;
            o->jitter_off = strcmp(v, "off") == 0;
        }
        else if (strcmp(a, "--finest-extent") == 0) {
            char *end = NULL;
            o->finest_extent = strtof(v, &end);
            ok = end && *end == '\0' && o->finest_extent > 0.0f && isfinite(o->finest_extent);
            o->given |= GIVEN_FINEST_EXTENT;
        }
        else if (strcmp(a, "--lights-per-frame") == 0)
            ok = parse_u32(v, 1, 1u << 16, &o->lights_per_frame), o->given |= GIVEN_LIGHTS_PER_FRAME;
        else if (strcmp(a, "--offset") == 0) {
            o->given |= GIVEN_OFFSET;
            char *end;
            o->offset = strtof(v, &end);
            ok = end != v && !*end && o->offset > 0.0f && o->offset <= 64.0f;
        } else if (strcmp(a, "--skip") == 0 || strcmp(a, "--ao-skip") == 0) {
            char *end;
            float c = strtof(v, &end);
            ok = end != v && !*end && c >= 0.0f && c <= 64.0f;
            *(strcmp(a, "--skip") == 0 ? &o->skip : &o->ao_skip) = c;
            o->given |= strcmp(a, "--skip") == 0 ? GIVEN_SKIP : GIVEN_AO_SKIP;
        } else if (strcmp(a, "--time") == 0) {
            char *end;
            o->time = strtof(v, &end);
            ok = end != v && !*end && o->time >= 0.0f && isfinite(o->time);
        } else if (strcmp(a, "--clip") == 0) {
            ok = parse_u32(v, 0, UINT32_MAX, &o->clip);
        } else if (strcmp(a, "--ao-radius") == 0) {
            o->given |= GIVEN_AO_RADIUS;
            if (strcmp(v, "inf") == 0 || strcmp(v, "unbounded") == 0) {
                o->ao_radius = 0.0f; /* the library's "unbounded" */
            } else {
                char *end;
                o->ao_radius = strtof(v, &end);
                ok = end != v && !*end && o->ao_radius > 0.0f && isfinite(o->ao_radius);
            }
        } else {
            const char *near = roma_app_suggest(a, option_names);
            fprintf(stderr, "roma-render: unknown option %s%s%s%s (see --help)\n", a, near ? "; did you mean " : "",
                    near ? near : "", near ? "?" : "");
            return 0;
        }
        if (!ok) {
            fprintf(stderr, "roma-render: bad value for %s: '%s' (see --help)\n", a, v);
            return 0;
        }
        i += used;
    }
    if (strcmp(o->tracer, "embree") != 0 && strcmp(o->tracer, "roma") != 0) {
        fprintf(stderr, "roma-render: unknown tracer '%s' (valid: embree, roma)\n", o->tracer);
        return 0;
    }
    if (o->ao_method == ROMA_AO_METHOD_SCREEN_SPACE && (o->given & GIVEN_EFFECTS) && o->effects != ROMA_EFFECT_AO) {
        fprintf(stderr, "roma-render: --ao-method screen-space renders AO alone: give --effects ao\n");
        return 0;
    }
    if (o->shadow_method == ROMA_SHADOW_METHOD_VOXEL_DDA && o->blind_start) {
        fprintf(stderr, "roma-render: --shadow-method voxel-dda walks the voxel grid that --ray-start blind leaves "
                "unread\n");
        return 0;
    }
    if (o->ao_trace == ROMA_AO_TRACE_SURFACES && (o->blind_start || o->ao_method != ROMA_AO_METHOD_ROMA)) {
        fprintf(stderr, "roma-render: --ao-trace surfaces is ROMA's public AO pass: not with --ray-start blind or "
                "another --ao-method\n");
        return 0;
    }
    if (o->ssao_layers && o->ao_method != ROMA_AO_METHOD_SCREEN_SPACE) {
        fprintf(stderr, "roma-render: --ssao-layers is for --ao-method screen-space\n");
        return 0;
    }
    if (o->ao_method == ROMA_AO_METHOD_SCREEN_SPACE && (o->given & GIVEN_AO_RADIUS) && !(o->ao_radius > 0.0f)) {
        fprintf(stderr, "roma-render: --ao-method screen-space needs a bounded --ao-radius\n");
        return 0;
    }
    if ((o->given & GIVEN_BUDGET) && (o->given & (GIVEN_PRESET | GIVEN_RES | GIVEN_ANGULAR))) {
        fprintf(stderr, "roma-render: --budget-ms chooses the preset: give it without --preset, --res or --angular\n");
        return 0;
    }
    if (o->given & GIVEN_PRESET) { /* the preset's RES and A, unless given */
        roma_preset_map_settings(o->preset, (o->given & GIVEN_RES) ? NULL : &o->res,
                                 (o->given & GIVEN_ANGULAR) ? NULL : &o->angular);
    }
    return 1;
}

typedef struct progress_state {
    const char *what;
    int quiet;
    int last_percent;
    double start_ms; /* 0: set at the first call */
} progress_state;

/* One line per 10% in logs; an updating line on a terminal. */
static void on_progress(float fraction, void *user)
{
    progress_state *p = user;
    int percent = (int)(fraction * 100.0f + 0.5f);
    int tty = isatty(fileno(stderr));
    if (p->quiet || percent == p->last_percent || (!tty && percent / 10 == p->last_percent / 10))
        return;
    p->last_percent = percent;
    double now = roma_app_now_ms();
    if (p->start_ms == 0.0)
        p->start_ms = now;
    double elapsed = (now - p->start_ms) / 1000.0;
    double left = fraction > 0.0f ? elapsed * (1.0 - fraction) / fraction : 0.0;
    char timing[64] = "";
    if (fraction > 0.0f && fraction < 1.0f)
        snprintf(timing, sizeof timing, " (%.1f s, about %.1f s left)", elapsed, left);
    else if (fraction >= 1.0f)
        snprintf(timing, sizeof timing, " (%.1f s)", elapsed);
    if (tty)
        fprintf(stderr, "\rroma-render: %s %3d%%%s%s", p->what, percent, timing, percent >= 100 ? "\n" : "   ");
    else
        fprintf(stderr, "roma-render: %s %3d%%%s\n", p->what, percent, timing);
    fflush(stderr);
}

typedef struct effect_output {
    const char *name;
    uint32_t bit;
    double cpu_ms;
} effect_output;

/* One timed pass in the stats file. */
typedef struct pass_record {
    const char *name;
    const char *clock; /* "cpu_wall" or "gpu_timestamp" */
    double ms;
    uint64_t bytes;    /* GPU memory of the pass's own buffers (0 for CPU passes) */
} pass_record;

/* Warnings a person should see: an effect with nothing to do, an option a tracer ignores,
 * a default chosen for them. Printed, and listed in the stats ("notes"). */
typedef struct notes {
    char text[16][256];
    int count;
} notes;

static void note(notes *n, int quiet, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void note(notes *n, int quiet, const char *fmt, ...)
{
    if (n->count == 16)
        return;
    va_list args;
    va_start(args, fmt);
    vsnprintf(n->text[n->count], sizeof n->text[0], fmt, args);
    va_end(args);
    if (!quiet)
        fprintf(stderr, "roma-render: note: %s\n", n->text[n->count]);
    ++n->count;
}

typedef struct run_record {
    const char *device_kind, *device_name;
    uint32_t threads;
    pass_record passes[16];
    notes notes;
    int pass_count;
    const effect_api_result *api;  /* ROMA tracer, public effect passes */
    roma_pixel_dispatch pixel_dispatch; /* the public passes': resolved, never AUTO */
    int shared_list;                    /* resolved: the pixels listed once (roma_pixel_list) */
    const budget_choice *budget;   /* --budget-ms only */
} run_record;

static void add_pass(run_record *run, const char *name, const char *clock, double ms)
{
    if (run->pass_count < 16)
        run->passes[run->pass_count++] = (pass_record){name, clock, ms, 0};
}

static float srgb_to_linear(float c)
{
    return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

/* The PNG's picture: exposure applied, and the background colour where the coverage says
 * no geometry was seen (the PFM and EXR keep the exact values). */
static roma_result write_png(const options *o, const roma_image *img, const roma_image *coverage, float scale,
                             const char *path)
{
    roma_image shown = {0};
    roma_result r = roma_image_alloc(&shown, img->width, img->height, 3);
    if (r != ROMA_SUCCESS)
        return r;
    float exposure = scale * o->exposure;
    int mask = coverage && coverage->pixels && coverage->width == img->width && coverage->height == img->height;
    for (size_t i = 0; i < (size_t)img->width * img->height; ++i)
        for (uint32_t c = 0; c < 3; ++c) {
            float v = exposure * img->pixels[i * img->channels + (img->channels == 1 ? 0 : c)];
            if (o->reinhard)
                v = v > 0.0f ? v / (1.0f + v) : 0.0f;
            shown.pixels[3 * i + c] =
                mask && !(coverage->pixels[i * coverage->channels] > 0.0f) ? srgb_to_linear(o->background[c]) : v;
        }
    r = roma_app_write_png(&shown, path, ROMA_PNG_SRGB, 1.0f);
    roma_image_free(&shown);
    return r;
}

static int write_outputs(const options *o, const char *name, const roma_image *img, const roma_image *coverage,
                         float scale)
{
    char path[4096];
    roma_result r = ROMA_SUCCESS;
    if (o->formats & FORMAT_PFM) {
        snprintf(path, sizeof path, "%s/%s.pfm", o->out, name);
        r = roma_image_write_pfm(img, path);
    }
    if (r == ROMA_SUCCESS && (o->formats & FORMAT_PFM))
        printf("wrote %s\n", path);
    if (r == ROMA_SUCCESS && (o->formats & FORMAT_EXR)) {
        snprintf(path, sizeof path, "%s/%s.exr", o->out, name);
        r = roma_app_write_exr(img, path);
        if (r == ROMA_SUCCESS)
            printf("wrote %s\n", path);
    }
    if (r == ROMA_SUCCESS && (o->formats & FORMAT_PNG)) {
        snprintf(path, sizeof path, "%s/%s.png", o->out, name);
        r = write_png(o, img, coverage, scale, path);
        if (r == ROMA_SUCCESS)
            printf("wrote %s\n", path);
    }
    if (r != ROMA_SUCCESS) {
        fprintf(stderr, "roma-render: cannot write %s: %s\n", path, roma_result_string(r));
        return 0;
    }
    return 1;
}

/* coverage.pfm (1 where the primary ray hit geometry: the mask for error
 * figures) and, when both are there, composed.pfm = direct + gi. */
static int write_extras(const options *o, const roma_image *coverage, const roma_image *direct,
                        const roma_image *gi)
{
    if (coverage->pixels && !write_outputs(o, "coverage", coverage, NULL, 1.0f))
        return 0;
    if (!direct->pixels || !gi->pixels)
        return 1;
    roma_image composed = {0};
    if (roma_image_alloc(&composed, direct->width, direct->height, 3) != ROMA_SUCCESS)
        return 0;
    for (size_t i = 0; i < (size_t)direct->width * direct->height * 3; ++i)
        composed.pixels[i] = direct->pixels[i] + gi->pixels[i];
    int ok = write_outputs(o, "composed", &composed, coverage, 1.0f);
    roma_image_free(&composed);
    return ok;
}

/* distance.pfm: how far from the eye the surface each pixel sees is (0 where none), from
 * Embree's primary rays whatever the tracer: with roma-compare --mask distance.pfm --mask-max D,
 * the error over the surfaces within D of the camera. The PNG shows 0 to the farthest. */
static int write_distance(const options *o, const roma_ref *ref, const roma_camera *cam)
{
    const size_t n = (size_t)o->width * o->height;
    float *planes = malloc(sizeof(float) * 15 * n);
    roma_image distance = {0};
    roma_result r = planes ? roma_image_alloc(&distance, o->width, o->height, 1) : ROMA_ERROR_OUT_OF_HOST_MEMORY;
    if (r == ROMA_SUCCESS) {
        const roma_ref_gbuffer g = {planes, planes + 4 * n, planes + 8 * n, planes + 12 * n};
        r = roma_ref_render_gbuffer(ref, cam, o->width, o->height, &g);
    }
    float farthest = 0.0f;
    for (size_t i = 0; i < n && r == ROMA_SUCCESS; ++i) {
        float d2 = 0.0f;
        for (int c = 0; c < 3; ++c) {
            const float d = planes[4 * i + c] - cam->eye[c];
            d2 += d * d;
        }
        distance.pixels[i] = planes[4 * i + 3] > 0.0f ? sqrtf(d2) : 0.0f;
        farthest = fmaxf(farthest, distance.pixels[i]);
    }
    int ok = r == ROMA_SUCCESS;
    if (!ok)
        fprintf(stderr, "roma-render: the distance image: %s\n", roma_result_string(r));
    else
        ok = write_outputs(o, "distance", &distance, &distance, farthest > 0.0f ? 1.0f / farthest : 1.0f);
    roma_image_free(&distance);
    free(planes);
    return ok;
}

/* The ROMA arrays the plan built every frame (one per distinct RES, A). */
static void write_arrays(roma_json *j, const roma_effect_plan *plan, const roma_map_info *info, const double *build_ms)
{
    roma_json_begin_array(j, "roma_arrays");
    for (uint32_t i = 0; i < plan->map_count; ++i) {
        const roma_map_info *m = &info[i];
        roma_json_begin_object(j, NULL);
        roma_json_int(j, "resolution", m->resolution);
        roma_json_int(j, "angular", m->angular);
        roma_json_int(j, "maps", m->map_count);
        roma_json_int(j, "levels", m->levels);
        roma_json_int(j, "bom_bytes", (long long)m->bom_bytes);
        roma_json_int(j, "maps_bytes", (long long)m->maps_bytes);
        roma_json_int(j, "params_bytes", (long long)m->params_bytes);
        roma_json_int(j, "geometry_bytes", (long long)m->geometry_bytes);
        roma_json_string(j, "clock", "gpu_timestamp");
        roma_json_number(j, "build_ms", build_ms[i]);
        roma_json_end_object(j);
    }
    roma_json_end_array(j);
}

static int write_stats(const options *o, const roma_scene_view *sv, const roma_camera *cam,
                       const run_record *run)
{
    FILE *f = fopen(o->stats, "w");
    if (!f) {
        fprintf(stderr, "roma-render: cannot write %s: %s\n", o->stats, strerror(errno));
        return 0;
    }
    roma_json j = {.f = f};
    roma_json_begin_object(&j, NULL);
    roma_json_string(&j, "tool", "roma-render");
    roma_json_begin_object(&j, "device");
    roma_json_string(&j, "tracer", o->tracer);
    roma_json_string(&j, "kind", run->device_kind);
    roma_json_string(&j, "name", run->device_name);
    roma_json_int(&j, "cpu_threads", run->threads);
    if (strcmp(run->device_kind, "cpu_vulkan") == 0)
        roma_json_string(&j, "note", "on Mesa lavapipe, timestamp queries do not cover compute dispatches: "
                                     "gpu_timestamp times of compute passes read near zero (docs/benchmark.md)");
    roma_json_end_object(&j);
    roma_json_begin_object(&j, "scene");
    roma_json_string(&j, "source", o->scene);
    roma_json_string(&j, "name", sv->name ? sv->name : "");
    roma_json_int(&j, "triangles", sv->triangle_count);
    roma_json_int(&j, "degenerate_triangles", sv->degenerate_triangle_count);
    roma_json_int(&j, "vertices", sv->vertex_count);
    if (o->time >= 0.0f) { /* posed on the host before rendering (roma_scene_pose) */
        roma_json_number(&j, "pose_time", o->time);
        roma_json_int(&j, "pose_clip", o->clip);
    }
    roma_json_int(&j, "materials", sv->material_count);
    roma_json_int(&j, "punctual_lights", sv->light_count);
    roma_json_int(&j, "emissive_triangles", sv->emissive_triangle_count);
    roma_json_begin_array(&j, "bounds_min");
    for (int i = 0; i < 3; ++i) roma_json_number(&j, NULL, sv->bounds_min[i]);
    roma_json_end_array(&j);
    roma_json_begin_array(&j, "bounds_max");
    for (int i = 0; i < 3; ++i) roma_json_number(&j, NULL, sv->bounds_max[i]);
    roma_json_end_array(&j);
    roma_json_end_object(&j);
    roma_json_begin_object(&j, "settings");
    roma_json_int(&j, "width", o->width);
    roma_json_int(&j, "height", o->height);
    roma_json_int(&j, "spp", o->spp);
    roma_json_int(&j, "frames", o->frames);
    roma_json_number(&j, "ao_radius", o->ao_radius > 0.0f ? o->ao_radius : INFINITY);
    roma_json_string(&j, "ao_radius_from", o->ao_radius_auto ? "10% of the scene's diagonal" : "--ao-radius");
    roma_json_int(&j, "added_lights", o->extra_light_count);
    roma_json_int(&j, "many_lights", o->lights);
    roma_json_int(&j, "seed", o->seed);
    char effects[64] = "";
    static const char *const effect_names[] = {"ao", "direct", "gi", "lights"};
    for (int e = 0; e < 4; ++e)
        if (o->effects & (1u << e))
            snprintf(effects + strlen(effects), sizeof effects - strlen(effects), "%s%s", effects[0] ? "," : "",
                     effect_names[e]);
    roma_json_string(&j, "effects", effects);
    if (strcmp(o->tracer, "roma") == 0) {
        if (o->given & (GIVEN_PRESET | GIVEN_BUDGET))
            roma_json_string(&j, "preset", roma_preset_name(o->preset));
        if (run->budget) { /* --budget-ms: the choice and the times it was made from */
            roma_json_begin_object(&j, "budget");
            roma_json_number(&j, "ms", o->budget_ms);
            roma_json_int(&j, "fits", run->budget->fits);
            roma_json_begin_object(&j, "ms_per_frame");
            for (unsigned p = ROMA_PRESET_LOW; p <= ROMA_PRESET_COUNT; ++p)
                if (run->budget->ms[p] >= 0.0)
                    roma_json_number(&j, roma_preset_name((roma_preset)p), run->budget->ms[p]);
            roma_json_end_object(&j);
            roma_json_end_object(&j);
        }
        roma_json_string(&j, "jitter", o->jitter_off ? "off" : "on");
        if (run->api)
            roma_json_string(&j, "pixel_dispatch", run->shared_list ? "shared"
                                                   : run->pixel_dispatch == ROMA_PIXEL_DISPATCH_LIST ? "list"
                                                                                                     : "every");
        roma_json_int(&j, "resolution", o->res);
        roma_json_int(&j, "resolution_divisor", o->resolution_divisor ? o->resolution_divisor : 1);
        roma_json_int(&j, "angular", o->angular);
        roma_json_int(&j, "shadow_angular", o->shadow_angular);
        roma_json_int(&j, "max_steps", o->max_steps);
        roma_json_number(&j, "skip_cells", o->skip < 0.0f ? 1.0f : o->skip);
        roma_json_number(&j, "ao_skip_cells", o->ao_skip < 0.0f ? ROMA_DEFAULT_AO_SKIP_CELLS : o->ao_skip);
        roma_json_number(&j, "offset_cells", o->offset > 0.0f ? o->offset : ROMA_DEFAULT_OFFSET_CELLS);
        roma_json_int(&j, "lights_per_frame", o->lights_per_frame ? o->lights_per_frame : o->lights);
    }
    roma_json_begin_object(&j, "camera");
    roma_json_begin_array(&j, "eye");
    for (int i = 0; i < 3; ++i) roma_json_number(&j, NULL, cam->eye[i]);
    roma_json_end_array(&j);
    roma_json_begin_array(&j, "target");
    for (int i = 0; i < 3; ++i) roma_json_number(&j, NULL, cam->target[i]);
    roma_json_end_array(&j);
    roma_json_number(&j, "fovy_deg", cam->fovy_deg);
    roma_json_end_object(&j);
    roma_json_end_object(&j);
    if (run->api) {
        write_arrays(&j, &run->api->plan, run->api->map_info, run->api->build_ms);
        /* The passes the effect plan runs: only those the scene calls for (roma/effects.h). */
        roma_json_begin_array(&j, "plan");
        for (int p = 0; p < ROMA_PASS_COUNT; ++p)
            if (roma_effect_plan_runs(&run->api->plan, (roma_pass_kind)p))
                roma_json_string(&j, NULL, roma_pass_name((roma_pass_kind)p));
        roma_json_end_array(&j);
        /* roma-render's own G-buffer, output and transfer memory (the passes' own is libroma's) */
        roma_json_int(&j, "api_images_bytes", (long long)run->api->effect_bytes);
    }
    roma_json_begin_array(&j, "notes");
    for (int i = 0; i < run->notes.count; ++i)
        roma_json_string(&j, NULL, run->notes.text[i]);
    roma_json_end_array(&j);
    /* CPU passes carry wall-clock times, GPU passes timestamp-query times. */
    roma_json_begin_array(&j, "passes");
    for (int i = 0; i < run->pass_count; ++i) {
        roma_json_begin_object(&j, NULL);
        roma_json_string(&j, "name", run->passes[i].name);
        roma_json_string(&j, "clock", run->passes[i].clock);
        roma_json_number(&j, "ms", run->passes[i].ms);
        if (strcmp(run->passes[i].clock, "gpu_timestamp") == 0)
            roma_json_int(&j, "bytes", (long long)run->passes[i].bytes);
        roma_json_end_object(&j);
    }
    roma_json_end_array(&j);
    roma_json_end_object(&j);
    if (j.failed | ferror(f) | fclose(f)) {
        fprintf(stderr, "roma-render: error while writing %s\n", o->stats);
        return 0;
    }
    printf("wrote %s\n", o->stats);
    return 1;
}

static const char *ao_method_name(roma_ao_method method)
{
    static const char *const names[] = {"roma", "voxel-dda", "distance-field", "screen-space", "naadf"};
    return (unsigned)method < sizeof names / sizeof names[0] ? names[method] : "?";
}

/* What the public passes will render, noted (printed and in the stats); -1 when the request
 * cannot be rendered. */
static int note_route(options *o, notes *n)
{
    if (strcmp(o->tracer, "roma") != 0)
        return 0;
    /* The study's AO baselines trace one grid (study/study_ao.h). */
    const int baseline = (o->effects & ROMA_EFFECT_AO) && o->ao_method != ROMA_AO_METHOD_ROMA;
    if (o->cascades > 1 && baseline && o->cascades_auto) {
        note(n, o->quiet, "cascades: none after all: --ao-method %s traces one grid", ao_method_name(o->ao_method));
        o->cascades = 1;
    } else if (o->cascades > 1 && baseline) {
        fprintf(stderr, "roma-render: --cascades: --ao-method %s traces one grid\n", ao_method_name(o->ao_method));
        return -1;
    }
    if (o->given & GIVEN_THREADS)
        note(n, o->quiet,
             "--threads sets the CPU threads of the G-buffer's primary rays; the passes run on the device");
    note(n, o->quiet, "ROMA through libroma's public effect passes on a G-buffer of primary rays%s",
         !(o->effects & ROMA_EFFECT_GI)                         ? ""
         : (o->given & GIVEN_GI_PUNCTUAL) && !o->gi_rays ? "; gi from point and spot lights through their RSMs "
                                                            "(the study's route on the public GI pass)"
                                                          : "; gi from point and spot lights by shadow rays");
    return 0;
}

/* The images from effect_api_render, written; the passes' times in run. */
/* --budget-ms: one preset's time per frame through the public passes, the difference between
 * renders of 3 frames and of 1 (what a frame adds beyond the set-up). */
typedef struct budget_probe {
    roma_context *ctx;
    const roma_scene *scene;
    const roma_ref *ref;
    effect_api_desc desc; /* the run's, without progress */
} budget_probe;

static double budget_measure(roma_preset preset, void *user)
{
    budget_probe *b = user;
    effect_api_desc d = b->desc;
    d.options.resolution = 0, d.options.ao_angular = 0, d.options.gi_angular = 0;
    d.options.preset = preset;
    double ms[2];
    const uint32_t frames[2] = {1, 3};
    for (int i = 0; i < 2; ++i) {
        d.frames = frames[i];
        effect_api_result result;
        double start = roma_app_now_ms();
        roma_result r = effect_api_render(b->ctx, b->scene, b->ref, &d, &result);
        ms[i] = roma_app_now_ms() - start;
        if (r != ROMA_SUCCESS) {
            fprintf(stderr, "roma-render: measuring the %s preset failed: %s\n", roma_preset_name(preset),
                    roma_result_string(r));
            return -1.0;
        }
        effect_api_result_free(&result);
    }
    /* On a tiny image the difference can drown in the noise: then the mean of the 3 frames. */
    return ms[1] > ms[0] ? (ms[1] - ms[0]) / 2.0 : ms[1] / 3.0;
}

/* Chooses the preset for o->budget_ms (budget.h) and sets desc's RES and A from it. */
static int apply_budget(options *o, roma_context *ctx, const roma_scene *scene, const roma_ref *ref,
                        effect_api_desc *desc, budget_choice *choice)
{
    roma_context_info info;
    if (roma_context_get_info(ctx, &info) != ROMA_SUCCESS)
        return 0;
    char key[1024];
    /* Whatever else changes the work of a frame is in the key too; "api": times of the public
     * passes (a cache from before they calibrated holds the internal renderer's). */
    snprintf(key, sizeof key,
             "api|%s|%s|%ux%u|effects %u|spp %u|radius %g|lights %u/%u|shadow A %u|steps %u|divisor %u|list %d/%d|"
             "levels %u|jitter %d|ao start %d trace %d",
             info.device_name, o->scene, o->width, o->height, o->effects, o->spp, (double)o->ao_radius, o->lights,
             o->lights_per_frame, o->shadow_angular, o->max_steps, o->resolution_divisor, desc->shared_list,
             (int)desc->pixel_dispatch, desc->cascades, !o->jitter_off, (int)desc->ao_start, (int)desc->ao_trace);
    for (char *c = key; *c; ++c)
        if (*c == '\t' || *c == '\n' || *c == '\r')
            *c = ' ';
    budget_probe probe = {ctx, scene, ref, *desc};
    probe.desc.progress = NULL;
    const char *cache = o->budget_cache ? o->budget_cache : budget_default_cache();
    if (!budget_choose(o->budget_ms, key, cache, budget_measure, &probe, choice))
        return 0;
    o->preset = choice->preset;
    roma_preset_map_settings(choice->preset, &o->res, &o->angular);
    desc->options.resolution = o->res, desc->options.ao_angular = o->angular, desc->options.gi_angular = o->angular;
    if (!o->quiet) {
        fprintf(stderr, "roma-render: --budget-ms %g: %s (RES %u, A %u)%s; ms a frame:", o->budget_ms,
                roma_preset_name(choice->preset), o->res, o->angular,
                choice->fits ? "" : ", the fastest preset, over the budget");
        for (unsigned p = ROMA_PRESET_LOW; p <= ROMA_PRESET_COUNT; ++p)
            if (choice->ms[p] >= 0.0)
                fprintf(stderr, " %s %.1f%s", roma_preset_name((roma_preset)p), choice->ms[p],
                        choice->cached[p] ? " (cached)" : "");
        fprintf(stderr, "%s%s\n", cache ? "; cache " : "", cache ? cache : "");
    }
    return 1;
}

static int render_api(options *o, roma_context *ctx, const roma_scene *scene, const roma_ref *ref,
                      const float *light_positions, const roma_camera *cam, run_record *run,
                      budget_choice *budget, effect_api_result *res)
{
    progress_state frames_progress = {"frames", o->quiet, -1, 0.0};
    on_progress(0.0f, &frames_progress);
    /* AUTO as the library resolves it (the list on CPU devices), for the stats; and on CPU
     * devices one list for every effect and frame: the G-buffer does not change. */
    roma_context_info info;
    run->pixel_dispatch = o->pixel_dispatch;
    run->shared_list = o->shared_list;
    if (run->pixel_dispatch == ROMA_PIXEL_DISPATCH_AUTO && roma_context_get_info(ctx, &info) == ROMA_SUCCESS) {
        const int cpu = info.device_type == VK_PHYSICAL_DEVICE_TYPE_CPU;
        run->pixel_dispatch = cpu ? ROMA_PIXEL_DISPATCH_LIST : ROMA_PIXEL_DISPATCH_EVERY_PIXEL;
        run->shared_list = run->shared_list || (cpu && !(o->given & GIVEN_PIXEL_DISPATCH));
    }
    effect_api_desc d = {
        .camera = *cam, .width = o->width, .height = o->height,
        .options = {.effects = o->effects, .resolution = o->res, .ao_angular = o->angular, .gi_angular = o->angular,
                    .shadow_angular = o->shadow_angular, .lights_angular = o->shadow_angular,
                    .many_light_count = o->effects & ROMA_EFFECT_LIGHTS ? o->lights : 0},
        .spp = o->spp, .frames = o->frames, .seed = o->seed, .ao_radius = o->ao_radius, .offset_cells = o->offset,
        /* The library takes 0 as its default and a negative value as none. */
        .skip_cells = o->skip < 0.0f ? 0.0f : o->skip == 0.0f ? -1.0f : o->skip,
        .ao_skip_cells = o->ao_skip < 0.0f ? 0.0f : o->ao_skip == 0.0f ? -1.0f : o->ao_skip,
        .max_steps = o->max_steps, .pixel_dispatch = o->pixel_dispatch, .shared_list = run->shared_list,
        .resolution_divisor = o->resolution_divisor, .many_light_positions = light_positions,
        .lights_per_frame = o->lights_per_frame,
        .progress = on_progress,
        .progress_user_data = &frames_progress, .cascades = o->cascades, .finest_extent = o->finest_extent,
        .jitter_off = o->jitter_off, .ao_method = o->ao_method,
        .shadow_method = o->shadow_method, .blind_start = o->blind_start, .ao_start = o->ao_start,
        .ao_trace = o->ao_trace,
        .gi_rsm = (o->given & GIVEN_GI_PUNCTUAL) && !o->gi_rays, .ssao_layers = o->ssao_layers};
    if (o->given & GIVEN_BUDGET) {
        if (!apply_budget(o, ctx, scene, ref, &d, budget))
            return 1;
        run->budget = budget;
    }
    double start = roma_app_now_ms();
    roma_result r = effect_api_render(ctx, scene, ref, &d, res);
    add_pass(run, "roma_total", "cpu_wall", roma_app_now_ms() - start);
    if (r != ROMA_SUCCESS) {
        fprintf(stderr, "roma-render: ROMA rendering failed: %s\n", roma_result_string(r));
        return 1;
    }
    run->api = res;
    add_pass(run, "gbuffer", "cpu_wall", res->gbuffer_ms);
    if (run->shared_list)
        add_pass(run, "pixel_list", "gpu_timestamp", res->list_ms);
    if (res->ao.pixels)
        add_pass(run, "ao", "gpu_timestamp", res->ao_ms);
    if (res->ao.pixels && (o->ao_method == ROMA_AO_METHOD_DISTANCE_FIELD || o->ao_method == ROMA_AO_METHOD_NAADF)) {
        /* the baseline's generation, part of the ao pass's time */
        add_pass(run, o->ao_method == ROMA_AO_METHOD_NAADF ? "naadf_build" : "distance_field_build", "gpu_timestamp",
                 res->baseline_build_ms);
        run->passes[run->pass_count - 1].bytes = res->baseline_bytes;
    }
    if (roma_effect_plan_runs(&res->plan, ROMA_PASS_PUNCTUAL_LIGHTS) ||
        roma_effect_plan_runs(&res->plan, ROMA_PASS_SOFT_SHADOWS))
        add_pass(run, "direct", "gpu_timestamp", res->direct_ms);
    if (res->ao.pixels && o->ssao_layers) { /* the stochastic depth map's rasterization, beside the ao pass */
        add_pass(run, "depth_layers", "gpu_timestamp", res->depth_layers_ms);
        run->passes[run->pass_count - 1].bytes = res->depth_layers_bytes;
    }
    if (roma_effect_plan_runs(&res->plan, ROMA_PASS_RSM)) {
        add_pass(run, "rsm", "gpu_timestamp", res->rsm_ms);
        run->passes[run->pass_count - 1].bytes = res->rsm_bytes;
    }
    if (roma_effect_plan_runs(&res->plan, ROMA_PASS_GI))
        add_pass(run, "gi", "gpu_timestamp", res->gi_ms);
    if (roma_effect_plan_runs(&res->plan, ROMA_PASS_MANY_LIGHTS))
        add_pass(run, "lights", "gpu_timestamp", res->lights_ms);
    if ((o->effects & ROMA_EFFECT_AO) && !write_outputs(o, "ao", &res->ao, &res->coverage, 1.0f))
        return 1;
    if ((o->effects & ROMA_EFFECT_DIRECT) && !write_outputs(o, "direct", &res->direct, &res->coverage, 1.0f))
        return 1;
    if ((o->effects & ROMA_EFFECT_GI) && !write_outputs(o, "gi", &res->gi, &res->coverage, 1.0f))
        return 1;
    if ((o->effects & ROMA_EFFECT_LIGHTS) &&
        !write_outputs(o, "lights", &res->lights, &res->coverage, 1.0f / (float)o->lights))
        return 1;
    return write_extras(o, &res->coverage, &res->direct, &res->gi) ? 0 : 1;
}

/* The default camera of a scene without one: libroma's direction (front, upper right) and
 * target (the bounds' centre), at the distance where the vertices fill 90% of the picture in
 * its tighter direction (the bounding sphere, libroma's rule, leaves a model covering about
 * 15% of the pixels). */
static roma_camera frame_tight(const roma_scene_view *sv, float aspect)
{
    roma_camera cam;
    roma_camera_frame_bounds(sv->bounds_min, sv->bounds_max, aspect, &cam);
    roma_camera_frame f;
    if (!roma_camera_make_frame(&cam, 1, 1, &f) || sv->vertex_count == 0)
        return cam;
    float t_y = tanf(0.5f * cam.fovy_deg * 3.14159265f / 180.0f), t_x = t_y * aspect;
    float centre[3] = {cam.target[0], cam.target[1], cam.target[2]}, distance = 0.0f;
    /* Twice: the distance that fits every vertex, then the centre moved sideways to the middle
     * of what the picture shows, and the distance again. */
    for (int pass = 0; pass < 2; ++pass) {
        distance = 0.0f;
        for (uint32_t k = 0; k < sv->vertex_count; ++k) {
            float o[3];
            for (int i = 0; i < 3; ++i)
                o[i] = sv->positions[3 * k + i] - centre[i];
            float x = fabsf(o[0] * f.right[0] + o[1] * f.right[1] + o[2] * f.right[2]);
            float y = fabsf(o[0] * f.up[0] + o[1] * f.up[1] + o[2] * f.up[2]);
            float z = o[0] * f.forward[0] + o[1] * f.forward[1] + o[2] * f.forward[2];
            /* its depth, distance + z, must be at least x / (0.9 t_x) and y / (0.9 t_y) */
            distance = fmaxf(distance, fmaxf(x / (0.9f * t_x), y / (0.9f * t_y)) - z);
        }
        if (!(distance > 0.0f) || !isfinite(distance))
            return cam;
        if (pass == 1)
            break;
        float lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
        for (uint32_t k = 0; k < sv->vertex_count; ++k) {
            float o[3];
            for (int i = 0; i < 3; ++i)
                o[i] = sv->positions[3 * k + i] - centre[i];
            float depth = distance + o[0] * f.forward[0] + o[1] * f.forward[1] + o[2] * f.forward[2];
            float p[2] = {(o[0] * f.right[0] + o[1] * f.right[1] + o[2] * f.right[2]) / depth,
                          (o[0] * f.up[0] + o[1] * f.up[1] + o[2] * f.up[2]) / depth};
            for (int a = 0; a < 2; ++a)
                lo[a] = fminf(lo[a], p[a]), hi[a] = fmaxf(hi[a], p[a]);
        }
        for (int i = 0; i < 3; ++i)
            centre[i] += distance * (0.5f * (lo[0] + hi[0]) * f.right[i] + 0.5f * (lo[1] + hi[1]) * f.up[i]);
    }
    for (int i = 0; i < 3; ++i) {
        cam.target[i] = centre[i];
        cam.eye[i] = centre[i] - f.forward[i] * distance;
    }
    return cam;
}

/* --animation NAME|INDEX: the clip by the glTF animation's name or index (then --time, or 0). */
static int resolve_animation(options *o, const roma_scene *scene)
{
    roma_scene_view v;
    roma_scene_get_view(scene, &v);
    const roma_scene_animation_data *a = &v.animation;
    if (a->animation_count == 0) {
        fprintf(stderr, "roma-render: --animation %s: the scene has no animations\n", o->animation);
        return 0;
    }
    char *end;
    unsigned long index = strtoul(o->animation, &end, 10);
    int found = 0;
    if (end != o->animation && !*end && o->animation[0] != '-') {
        found = index < a->animation_count;
    } else {
        for (uint32_t i = 0; a->animation_names && i < a->animation_count && !found; ++i)
            if (strcmp(a->animation_names[i], o->animation) == 0)
                index = i, found = 1;
    }
    if (!found) {
        fprintf(stderr, "roma-render: no animation '%s'; the scene has %u:", o->animation, a->animation_count);
        for (uint32_t i = 0; i < a->animation_count; ++i)
            fprintf(stderr, " %u%s%s%s", i, a->animation_names && a->animation_names[i][0] ? " (" : "",
                    a->animation_names ? a->animation_names[i] : "",
                    a->animation_names && a->animation_names[i][0] ? ")" : "");
        fprintf(stderr, "\n");
        const char **names = a->animation_names ? calloc(a->animation_count + 1, sizeof *names) : NULL;
        if (names) { /* a NULL-terminated list for the suggestion */
            memcpy(names, a->animation_names, sizeof *names * a->animation_count);
            const char *near = roma_app_suggest(o->animation, names);
            if (near)
                fprintf(stderr, "did you mean %s?\n", near);
            free(names);
        }
        return 0;
    }
    o->clip = (uint32_t)index;
    if (o->time < 0.0f)
        o->time = 0.0f;
    return 1;
}

/* A copy of scene with lights appended (--light). */
static roma_result with_lights(const roma_scene *scene, const roma_light *extra, uint32_t count, roma_scene **out)
{
    roma_scene_view v;
    roma_result r = roma_scene_get_view(scene, &v);
    if (r != ROMA_SUCCESS)
        return r;
    roma_light *lights = malloc(sizeof *lights * (v.light_count + count));
    if (!lights)
        return ROMA_ERROR_OUT_OF_HOST_MEMORY;
    memcpy(lights, v.lights, sizeof *lights * v.light_count);
    memcpy(lights + v.light_count, extra, sizeof *lights * count);
    roma_scene_desc d = {.positions = v.positions, .normals = v.normals, .vertex_count = v.vertex_count,
                         .indices = v.indices, .triangle_count = v.triangle_count,
                         .triangle_materials = v.triangle_materials, .materials = v.materials,
                         .material_count = v.material_count, .lights = lights, .light_count = v.light_count + count,
                         .camera = v.has_camera ? &v.camera : NULL, .cameras = v.cameras,
                         .camera_count = v.camera_count, .name = v.name};
    r = roma_scene_create(&d, out);
    free(lights);
    return r;
}

/* Defaults chosen for the user and effects or options with nothing to do, said once. */
static void say_what_happens(options *o, const roma_scene_view *sv, const float eye[3], notes *n)
{
    int roma = strcmp(o->tracer, "roma") == 0;
    float dx = sv->bounds_max[0] - sv->bounds_min[0], dy = sv->bounds_max[1] - sv->bounds_min[1],
          dz = sv->bounds_max[2] - sv->bounds_min[2];
    int lights = sv->light_count > 0, emitters = sv->emissive_triangle_count > 0;
    if (!(o->given & GIVEN_EFFECTS) && roma && o->ao_method == ROMA_AO_METHOD_SCREEN_SPACE) {
        o->effects = ROMA_EFFECT_AO;
        note(n, o->quiet, "effects: ao (--ao-method screen-space renders AO alone)");
    } else if (!(o->given & GIVEN_EFFECTS)) {
        /* What the scene calls for; many lights are synthetic, so only on request. */
        o->effects = ROMA_EFFECT_AO | (lights || emitters ? ROMA_EFFECT_DIRECT | ROMA_EFFECT_GI : 0u);
        note(n, o->quiet, "effects: %s (what the scene calls for%s; --effects to choose, lights for many "
             "synthetic point lights)", o->effects & ROMA_EFFECT_GI ? "ao, direct, gi" : "ao",
             o->effects & ROMA_EFFECT_GI ? ": it has lights" : ": it has no light, so no direct or gi");
    }
    if ((o->effects & ROMA_EFFECT_AO) && !(o->given & GIVEN_AO_RADIUS)) {
        o->ao_radius = 0.1f * sqrtf(dx * dx + dy * dy + dz * dz);
        o->ao_radius_auto = 1;
        note(n, o->quiet, "AO radius %.4g: 10%% of the scene's diagonal (--ao-radius R to choose, --ao-radius inf "
             "for unbounded rays)", (double)o->ao_radius);
    }
    /* A scene much larger than the AO radius seen from inside (a game level): one grid over it has
     * cells too large for the radius; cascade levels around the camera instead
     * (roma_app_auto_cascades). */
    const float longest = fmaxf(dx, fmaxf(dy, dz));
    const uint32_t res = o->res ? o->res : o->preset == ROMA_PRESET_HIGH || o->preset == ROMA_PRESET_ULTRA ? 256 : 128;
    float finest = 0.0f;
    const uint32_t levels =
        roma_app_auto_cascades(sv->bounds_min, sv->bounds_max, eye, res, o->ao_radius, o->finest_extent, &finest);
    if (roma && !(o->given & GIVEN_CASCADES) && (o->effects & ROMA_EFFECT_AO) && levels > 1) {
        o->cascades = levels;
        o->cascades_auto = 1;
        char why[64];
        if (o->finest_extent > 0.0f)
            snprintf(why, sizeof why, "--finest-extent");
        else
            snprintf(why, sizeof why, "%d cells to the AO radius %.3g", ROMA_APP_FINEST_CELLS, (double)o->ao_radius);
        note(n, o->quiet, "cascades: %u grids around the camera, the finest %.3g wide (%s), the coarsest %.3g, for a "
             "scene %.3g wide (--cascades 1 for one grid over it)", o->cascades, (double)finest, why,
             (double)finest * (float)(1u << (o->cascades - 1)), (double)longest);
    }
    /* Levels of a given finest edge reach finest * 2^(K-2) from the camera: geometry beyond is
     * not traced (without an edge, the library's coarsest level holds the whole scene). Said,
     * not changed: for a short AO radius a level that reached it would be coarse for the radius
     * and darken more than the untraced part brightens (docs/accuracy.md, cascades). */
    const float finest_edge = o->finest_extent > 0.0f ? o->finest_extent : roma_app_finest_extent(res, o->ao_radius);
    const int baseline_ao = (o->effects & ROMA_EFFECT_AO) && o->ao_method != ROMA_AO_METHOD_ROMA; /* one grid */
    if (roma && o->cascades > 1 && finest_edge > 0.0f && !baseline_ao) {
        float reach = 0.0f;
        for (int a = 0; a < 3; ++a)
            reach = fmaxf(reach, fmaxf(eye[a] - sv->bounds_min[a], sv->bounds_max[a] - eye[a]));
        const float half = 0.5f * finest_edge * (float)(1u << (o->cascades - 1));
        if (half < reach)
            note(n, o->quiet, "cascades: the coarsest grid reaches %.3g from the camera and the scene %.3g: geometry "
                 "farther away is not traced (nothing there occludes)", (double)half, (double)reach);
    }
    if ((o->effects & ROMA_EFFECT_DIRECT) && !lights && !emitters)
        note(n, o->quiet, "direct: the scene has no light (no punctual light, no emissive triangle): direct.pfm is "
             "black; add one with --light");
    if ((o->effects & ROMA_EFFECT_GI) && !lights && !emitters)
        note(n, o->quiet, "gi: the scene has no light to bounce: gi.pfm is black; add one with --light");
    static const struct { uint32_t bit; const char *name; } roma_only[] = {
        {GIVEN_FRAMES, "--frames"}, {GIVEN_RES, "--res"}, {GIVEN_ANGULAR, "--angular"},
        {GIVEN_SHADOW_ANGULAR, "--shadow-angular"}, {GIVEN_MAX_STEPS, "--max-steps"}, {GIVEN_SKIP, "--skip"},
        {GIVEN_AO_SKIP, "--ao-skip"}, {GIVEN_OFFSET, "--offset"}, {GIVEN_LIGHTS_PER_FRAME, "--lights-per-frame"},
        {GIVEN_GI_PUNCTUAL, "--gi-punctual"}, {GIVEN_RAY_START, "--ray-start"}, {GIVEN_AO_METHOD, "--ao-method"},
        {GIVEN_AO_TRACE, "--ao-trace"},
        {GIVEN_SHADOW_METHOD, "--shadow-method"},
        {GIVEN_PRESET, "--preset"}, {GIVEN_BUDGET, "--budget-ms"},
        {GIVEN_CASCADES, "--cascades"}, {GIVEN_FINEST_EXTENT, "--finest-extent"},
        {GIVEN_RESOLUTION_DIVISOR, "--resolution-divisor"}};
    for (size_t i = 0; i < sizeof roma_only / sizeof roma_only[0]; ++i)
        if (!roma && (o->given & roma_only[i].bit))
            note(n, o->quiet, "%s is a ROMA setting: --tracer embree ignores it%s", roma_only[i].name,
                 roma_only[i].bit == GIVEN_FRAMES ? " (the reference takes all its samples at once: --spp)" : "");
}

int main(int argc, char **argv)
{
    options o;
    if (!parse_args(argc, argv, &o))
        return 2;
    roma_scene *scene = NULL;
    double started = roma_app_now_ms();
    roma_result r = roma_app_load_scene(o.scene, NULL, o.gltf_camera, &scene);
    if (r != ROMA_SUCCESS) {
        fprintf(stderr, "roma-render: cannot load scene '%s': %s\n", o.scene, roma_result_string(r));
        return 1;
    }
    if (o.animation && !resolve_animation(&o, scene)) {
        roma_scene_destroy(scene);
        return 2;
    }
    if (o.time >= 0.0f) { /* both tracers render the same posed triangles */
        roma_scene *posed = NULL;
        r = roma_scene_pose(scene, &(roma_animator_pose){.clip = o.clip, .time = o.time}, NULL, &posed);
        roma_scene_destroy(scene);
        if (r != ROMA_SUCCESS) {
            fprintf(stderr, "roma-render: cannot pose '%s' at clip %u, %g s: %s\n", o.scene, o.clip, (double)o.time,
                    roma_result_string(r));
            return 1;
        }
        scene = posed;
    }
    if (o.up && strcmp(o.up, "+y") != 0) { /* --up: turned after posing, before lights are added */
        roma_scene *turned = NULL;
        r = roma_app_reorient(scene, o.up, &turned);
        roma_scene_destroy(scene);
        if (r != ROMA_SUCCESS) {
            fprintf(stderr, "roma-render: cannot turn the scene (--up %s): %s\n", o.up, roma_result_string(r));
            return 1;
        }
        scene = turned;
    }
    if (o.extra_light_count) { /* --light: the scene with the lights added */
        roma_scene *lit = NULL;
        r = with_lights(scene, o.extra_lights, o.extra_light_count, &lit);
        roma_scene_destroy(scene);
        if (r != ROMA_SUCCESS) {
            fprintf(stderr, "roma-render: cannot add the --light lights: %s\n", roma_result_string(r));
            return 1;
        }
        scene = lit;
    }
    roma_scene_view sv;
    roma_scene_get_view(scene, &sv);
    run_record run = {.device_kind = "cpu", .device_name = "Embree 3 reference (CPU)",
                      .threads = o.threads ? o.threads : (uint32_t)sysconf(_SC_NPROCESSORS_ONLN)};
    roma_camera cam = o.camera;
    if (!o.has_camera && sv.has_camera)
        cam = sv.camera;
    else if (!o.has_camera)
        cam = frame_tight(&sv, (float)o.width / (float)o.height);
    say_what_happens(&o, &sv, cam.eye, &run.notes);
    if (note_route(&o, &run.notes) < 0) {
        roma_scene_destroy(scene);
        return 2;
    }
    struct stat out_stat;
    const int out_existed = stat(o.out, &out_stat) == 0;
    if (!roma_app_make_dir(o.out)) {
        fprintf(stderr, "roma-render: cannot create output folder %s: %s\n", o.out, strerror(errno));
        roma_scene_destroy(scene);
        return 1;
    }

    double t0 = roma_app_now_ms();
    roma_ref *ref = NULL;
    roma_ref_desc ref_desc = {.thread_count = o.threads};
    r = roma_ref_create(scene, &ref_desc, &ref);
    double build_ms = roma_app_now_ms() - t0;
    if (r != ROMA_SUCCESS) {
        fprintf(stderr, "roma-render: reference tracer: %s\n", roma_result_string(r));
        roma_scene_destroy(scene);
        return 1;
    }
    int roma = strcmp(o.tracer, "roma") == 0;
    if (!o.quiet)
        fprintf(stderr, "roma-render: %s, %u triangles, %ux%u, %s, %u samples per pixel%s\n",
                sv.name ? sv.name : o.scene, sv.triangle_count, o.width, o.height, roma ? "ROMA" : "Embree",
                roma ? o.spp * o.frames : o.spp, roma && o.frames > 1 ? " (spp x frames)" : "");

    float *light_positions = NULL;
    if (o.effects & ROMA_EFFECT_LIGHTS) {
        light_positions = malloc(sizeof(float) * 3 * o.lights);
        if (!light_positions) {
            roma_ref_destroy(ref);
            roma_scene_destroy(scene);
            return 1;
        }
        roma_many_lights_positions(sv.bounds_min, sv.bounds_max, o.lights, o.seed, light_positions);
    }

    add_pass(&run, "embree_scene_build", "cpu_wall", build_ms);
    int status = 0;
    roma_context *ctx = NULL;
    roma_context_info ctx_info;
    effect_api_result api_result = {0};
    budget_choice budget;
    if (strcmp(o.tracer, "roma") == 0) {
        roma_context_desc ctx_desc = {0};
        r = roma_context_create(&ctx_desc, &ctx);
        if (r != ROMA_SUCCESS) {
            fprintf(stderr, "roma-render: no Vulkan context: %s\n", roma_result_string(r));
            status = 1;
        } else {
            roma_context_get_info(ctx, &ctx_info);
            run.device_kind = ctx_info.device_type == VK_PHYSICAL_DEVICE_TYPE_CPU ? "cpu_vulkan" : "gpu";
            run.device_name = ctx_info.device_name;
        }
        if (ctx)
            status = render_api(&o, ctx, scene, ref, light_positions, &cam, &run, &budget, &api_result);
    }
    roma_image kept_coverage = {0}, kept_direct = {0}, kept_gi = {0};
    effect_output effects[4] = {{"ao", ROMA_EFFECT_AO, 0}, {"direct", ROMA_EFFECT_DIRECT, 0},
                                {"gi", ROMA_EFFECT_GI, 0}, {"lights", ROMA_EFFECT_LIGHTS, 0}};
    for (int e = 0; e < 4 && status == 0 && !ctx; ++e) {
        if (!(o.effects & effects[e].bit))
            continue;
        /* One effect per call so that each gets its own time and progress line. */
        progress_state progress = {effects[e].name, o.quiet, -1, 0.0};
        on_progress(0.0f, &progress);
        roma_ref_render_desc desc = {
            .camera = cam, .width = o.width, .height = o.height, .effects = effects[e].bit,
            .spp = o.spp, .ao_radius = o.ao_radius, .seed = o.seed,
            .many_light_positions = light_positions, .many_light_count = o.lights,
            .progress = on_progress, .progress_user_data = &progress,
        };
        roma_ref_images images;
        double start = roma_app_now_ms();
        r = roma_ref_render(ref, &desc, &images);
        effects[e].cpu_ms = roma_app_now_ms() - start;
        if (r != ROMA_SUCCESS) {
            fprintf(stderr, "roma-render: rendering %s failed: %s\n", effects[e].name, roma_result_string(r));
            status = 1;
            break;
        }
        int ok = 1;
        switch (effects[e].bit) {
        case ROMA_EFFECT_AO: ok = write_outputs(&o, "ao", &images.ao, &images.coverage, 1.0f); break;
        case ROMA_EFFECT_DIRECT: ok = write_outputs(&o, "direct", &images.direct, &images.coverage, 1.0f); break;
        case ROMA_EFFECT_GI: ok = write_outputs(&o, "gi", &images.gi, &images.coverage, 1.0f); break;
        case ROMA_EFFECT_LIGHTS:
            ok = write_outputs(&o, "lights", &images.lights, &images.coverage, 1.0f / (float)o.lights);
            break;
        }
        /* Kept for the coverage mask and the composed image. */
        if (!kept_coverage.pixels) {
            kept_coverage = images.coverage;
            images.coverage = (roma_image){0};
        }
        if (effects[e].bit == ROMA_EFFECT_DIRECT) {
            kept_direct = images.direct;
            images.direct = (roma_image){0};
        }
        if (effects[e].bit == ROMA_EFFECT_GI) {
            kept_gi = images.gi;
            images.gi = (roma_image){0};
        }
        roma_ref_images_free(&images);
        if (!ok)
            status = 1;
        add_pass(&run, effects[e].name, "cpu_wall", effects[e].cpu_ms);
    }
    if (status == 0 && !ctx && !write_extras(&o, &kept_coverage, &kept_direct, &kept_gi))
        status = 1;
    roma_image_free(&kept_coverage);
    roma_image_free(&kept_direct);
    roma_image_free(&kept_gi);
    if (status == 0 && !write_distance(&o, ref, &cam))
        status = 1;
    if (status == 0 && o.stats && !write_stats(&o, &sv, &cam, &run))
        status = 1;
    const uint32_t validation_errors = roma_context_validation_error_count(ctx);
    if (validation_errors) {
        fprintf(stderr, "roma-render: %u Vulkan validation error%s (above)\n", validation_errors,
                validation_errors == 1 ? "" : "s");
        status = 1;
    }
    effect_api_result_free(&api_result);
    if (status == 0 && !o.quiet)
        fprintf(stderr, "roma-render: done in %.1f s\n", (roma_app_now_ms() - started) / 1000.0);
    roma_context_destroy(ctx);
    free(light_positions);
    roma_ref_destroy(ref);
    roma_scene_destroy(scene);
    /* A run that failed before writing anything leaves no empty folder behind
     * (rmdir removes only an empty one: outputs already written stay). */
    if (status != 0 && !out_existed)
        rmdir(o.out);
    return status;
}
