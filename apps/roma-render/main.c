/* roma-render: renders the effects of a scene to PFM (exact) and PNG (tone-mapped)
 * and writes a stats JSON. The main job of libroma. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "app_common.h"
#include "passes/effect_render.h"
#include "reference.h"
#include "roma/builtin_scenes.h"
#include "roma/roma.h"
#include "stats_json.h"

static const char *usage =
    "usage: roma-render [options]\n"
    "  --scene FILE|builtin:NAME   glTF 2.0 file (.gltf/.glb) or a built-in scene (default builtin:cornell)\n"
    "  --camera ex,ey,ez,tx,ty,tz,fovy   eye, target and vertical field of view in degrees\n"
    "                              (y up; default: the scene's camera, else one framing its bounds)\n"
    "  --size WxH                  image size in pixels (default 640x480)\n"
    "  --effects LIST              comma-separated: ao,direct,gi,lights (default ao)\n"
    "  --tracer embree|roma        embree = CPU reference (ground truth); roma = ROMA on the GPU\n"
    "                              (gi on ROMA: light of point and spot lights, through their RSMs).\n"
    "                              ROMA runs only the passes the scene calls for (see the stats file)\n"
    "  --res N                     ROMA grid resolution: 32, 64, 128 or 256 (default 128)\n"
    "  --angular A                 ROMA A x A candidate directions for ao, 1..16 (default 4)\n"
    "  --shadow-angular A          ROMA A for shadow rays (direct, lights), 1..16 (default 8)\n"
    "  --max-steps N               ROMA un-snapped shadow rays: texels walked at most (default 8)\n"
    "  --skip C                    ROMA shadow rays skip their first C trace cells (default 1)\n"
    "  --ao-skip C                 ROMA ao and gi rays skip their first C trace cells (default 1.6)\n"
    "  --offset C                  ROMA rays start C trace cells off the surface (default 1.5)\n"
    "  --lights-per-frame K        ROMA lights: test K random lights per pixel and frame\n"
    "                              (stochastic, accumulated) instead of all (default: all)\n"
    "  --spp N                     samples per pixel for ao, area lights and gi (default 64)\n"
    "  --frames N                  ROMA: frames accumulated, each with new jitter and new samples\n"
    "                              (frame f uses samples f*spp .. f*spp+spp-1, so the reference with\n"
    "                              --spp spp*frames traces the same directions)\n"
    "  --ao-radius R               AO ray length in scene units (default: unbounded)\n"
    "  --lights N                  point lights for the many-lights effect (default 256)\n"
    "  --seed N                    sample-sequence seed (default 1)\n"
    "  --threads N                 CPU threads for the reference (default: all cores)\n"
    "  --out DIR                   output folder (default out); writes DIR/<effect>.<format>\n"
    "  --format LIST               output formats, comma-separated: pfm (linear float), png (8-bit\n"
    "                              sRGB), exr (OpenEXR, linear 32-bit float); default pfm,png\n"
    "  --stats FILE.json           write device, scene size, settings and timings\n"
    "  --time SECONDS              an animated glTF posed at this time of its clip (both tracers;\n"
    "                              default: the rest pose)\n"
    "  --clip N                    which animation --time plays (default 0)\n"
    "  --list-scenes               print the built-in scene names\n"
    "  --quiet                     no progress line\n"
    "  --help\n";

typedef struct options {
    const char *scene, *out, *stats, *tracer;
    roma_camera camera;
    int has_camera;
    uint32_t width, height, effects, spp, frames, lights, seed, threads, res, angular;
    uint32_t shadow_angular, max_steps, lights_per_frame;
    float skip, ao_skip; /* < 0: unset (library default) */
    float offset;        /* 0: unset (library default) */
    float ao_radius;
    float time;          /* < 0: unset (rest pose) */
    uint32_t clip;
    int quiet;
    uint32_t formats;    /* FORMAT_* bits */
} options;

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
    *out = 0;
    char buf[256];
    snprintf(buf, sizeof buf, "%s", s);
    for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        if (strcmp(tok, "ao") == 0) *out |= ROMA_EFFECT_AO;
        else if (strcmp(tok, "direct") == 0) *out |= ROMA_EFFECT_DIRECT;
        else if (strcmp(tok, "gi") == 0) *out |= ROMA_EFFECT_GI;
        else if (strcmp(tok, "lights") == 0) *out |= ROMA_EFFECT_LIGHTS;
        else return 0;
    }
    return *out != 0;
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
    o->width = 640, o->height = 480, o->effects = ROMA_EFFECT_AO, o->spp = 64, o->frames = 1;
    o->lights = 256, o->seed = 1, o->res = 128, o->angular = 4, o->shadow_angular = 8, o->max_steps = 8;
    o->skip = o->ao_skip = -1.0f;
    o->formats = FORMAT_PFM | FORMAT_PNG;
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
        else if (strcmp(a, "--stats") == 0) o->stats = v;
        else if (strcmp(a, "--tracer") == 0) o->tracer = v;
        else if (strcmp(a, "--camera") == 0) ok = o->has_camera = parse_camera(v, &o->camera);
        else if (strcmp(a, "--size") == 0) {
            unsigned w = 0, h = 0;
            char tail;
            ok = sscanf(v, "%ux%u%c", &w, &h, &tail) == 2 && w >= 1 && h >= 1 && w <= 16384 && h <= 16384;
            o->width = w, o->height = h;
        } else if (strcmp(a, "--effects") == 0) ok = parse_effects(v, &o->effects);
        else if (strcmp(a, "--spp") == 0) ok = parse_u32(v, 1, 1u << 20, &o->spp);
        else if (strcmp(a, "--frames") == 0) ok = parse_u32(v, 1, 1u << 20, &o->frames);
        else if (strcmp(a, "--lights") == 0) ok = parse_u32(v, 1, 1u << 16, &o->lights);
        else if (strcmp(a, "--seed") == 0) ok = parse_u32(v, 0, UINT32_MAX, &o->seed);
        else if (strcmp(a, "--threads") == 0) ok = parse_u32(v, 1, 1024, &o->threads);
        else if (strcmp(a, "--res") == 0)
            ok = parse_u32(v, 32, 256, &o->res) && (o->res == 32 || o->res == 64 || o->res == 128 || o->res == 256);
        else if (strcmp(a, "--angular") == 0) ok = parse_u32(v, 1, 16, &o->angular);
        else if (strcmp(a, "--shadow-angular") == 0) ok = parse_u32(v, 1, 16, &o->shadow_angular);
        else if (strcmp(a, "--max-steps") == 0) ok = parse_u32(v, 1, 1024, &o->max_steps);
        else if (strcmp(a, "--lights-per-frame") == 0) ok = parse_u32(v, 1, 1u << 16, &o->lights_per_frame);
        else if (strcmp(a, "--offset") == 0) {
            char *end;
            o->offset = strtof(v, &end);
            ok = end != v && !*end && o->offset > 0.0f && o->offset <= 64.0f;
        } else if (strcmp(a, "--skip") == 0 || strcmp(a, "--ao-skip") == 0) {
            char *end;
            float c = strtof(v, &end);
            ok = end != v && !*end && c >= 0.0f && c <= 64.0f;
            *(strcmp(a, "--skip") == 0 ? &o->skip : &o->ao_skip) = c;
        } else if (strcmp(a, "--time") == 0) {
            char *end;
            o->time = strtof(v, &end);
            ok = end != v && !*end && o->time >= 0.0f && isfinite(o->time);
        } else if (strcmp(a, "--clip") == 0) {
            ok = parse_u32(v, 0, UINT32_MAX, &o->clip);
        } else if (strcmp(a, "--ao-radius") == 0) {
            char *end;
            o->ao_radius = strtof(v, &end);
            ok = end != v && !*end && o->ao_radius >= 0.0f && isfinite(o->ao_radius);
        } else {
            fprintf(stderr, "roma-render: unknown option %s (see --help)\n", a);
            return 0;
        }
        if (!ok) {
            fprintf(stderr, "roma-render: bad value for %s: '%s' (see --help)\n", a, v);
            return 0;
        }
        i += used;
    }
    if (strcmp(o->tracer, "embree") != 0 && strcmp(o->tracer, "roma") != 0) {
        fprintf(stderr, "roma-render: unknown tracer '%s' (embree or roma)\n", o->tracer);
        return 0;
    }
    return 1;
}

typedef struct progress_state {
    const char *what;
    int quiet;
    int last_percent;
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
    if (tty)
        fprintf(stderr, "\rroma-render: %s %3d%%%s", p->what, percent, percent >= 100 ? "\n" : "");
    else
        fprintf(stderr, "roma-render: %s %3d%%\n", p->what, percent);
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

typedef struct run_record {
    const char *device_kind, *device_name;
    uint32_t threads;
    pass_record passes[16];
    int pass_count;
    const roma_effect_stats *roma; /* ROMA tracer only */
} run_record;

static void add_pass(run_record *run, const char *name, const char *clock, double ms)
{
    if (run->pass_count < 16)
        run->passes[run->pass_count++] = (pass_record){name, clock, ms, 0};
}

static int write_outputs(const options *o, const char *name, const roma_image *img, roma_png_mode mode,
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
        r = roma_app_write_png(img, path, mode, scale);
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
    if (coverage->pixels && !write_outputs(o, "coverage", coverage, ROMA_PNG_SRGB, 1.0f))
        return 0;
    if (!direct->pixels || !gi->pixels)
        return 1;
    roma_image composed = {0};
    if (roma_image_alloc(&composed, direct->width, direct->height, 3) != ROMA_SUCCESS)
        return 0;
    for (size_t i = 0; i < (size_t)direct->width * direct->height * 3; ++i)
        composed.pixels[i] = direct->pixels[i] + gi->pixels[i];
    int ok = write_outputs(o, "composed", &composed, ROMA_PNG_SRGB, 1.0f);
    roma_image_free(&composed);
    return ok;
}

static int write_stats(const options *o, const roma_scene_view *sv, const roma_camera *cam,
                       const run_record *run)
{
    FILE *f = fopen(o->stats, "w");
    if (!f) {
        fprintf(stderr, "roma-render: cannot write %s\n", o->stats);
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
    roma_json_int(&j, "many_lights", o->lights);
    roma_json_int(&j, "seed", o->seed);
    if (strcmp(o->tracer, "roma") == 0) {
        roma_json_int(&j, "resolution", o->res);
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
    if (run->roma) {
        /* The ROMA arrays the plan built every frame (one per distinct RES, A). */
        const roma_effect_stats *st = run->roma;
        roma_json_begin_array(&j, "roma_arrays");
        for (uint32_t i = 0; i < st->plan.map_count; ++i) {
            const roma_map_info *m = &st->map_info[i];
            roma_json_begin_object(&j, NULL);
            roma_json_int(&j, "resolution", m->resolution);
            roma_json_int(&j, "angular", m->angular);
            roma_json_int(&j, "maps", m->map_count);
            roma_json_int(&j, "bom_bytes", (long long)m->bom_bytes);
            roma_json_int(&j, "maps_bytes", (long long)m->maps_bytes);
            roma_json_int(&j, "params_bytes", (long long)m->params_bytes);
            roma_json_int(&j, "geometry_bytes", (long long)m->geometry_bytes);
            roma_json_string(&j, "clock", "gpu_timestamp");
            roma_json_number(&j, "build_ms", st->build_ms[i]);
            roma_json_end_object(&j);
        }
        roma_json_end_array(&j);
    }
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
    if (ferror(f) | fclose(f)) {
        fprintf(stderr, "roma-render: error while writing %s\n", o->stats);
        return 0;
    }
    printf("wrote %s\n", o->stats);
    return 1;
}

int main(int argc, char **argv)
{
    options o;
    if (!parse_args(argc, argv, &o))
        return 2;
    roma_scene *scene = NULL;
    roma_result r = roma_app_load_scene(o.scene, NULL, &scene);
    if (r != ROMA_SUCCESS) {
        fprintf(stderr, "roma-render: cannot load scene '%s': %s\n", o.scene, roma_result_string(r));
        return 1;
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
    roma_scene_view sv;
    roma_scene_get_view(scene, &sv);
    roma_camera cam = o.camera;
    if (!o.has_camera)
        roma_scene_default_camera(scene, (float)o.width / (float)o.height, &cam);
    struct stat out_stat;
    const int out_existed = stat(o.out, &out_stat) == 0;
    if (!roma_app_make_dir(o.out)) {
        fprintf(stderr, "roma-render: cannot create output folder %s\n", o.out);
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
    if (!o.quiet)
        fprintf(stderr, "roma-render: %s, %u triangles, %ux%u, %u spp\n", sv.name ? sv.name : o.scene,
                sv.triangle_count, o.width, o.height, o.spp);

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

    run_record run = {.device_kind = "cpu", .device_name = "Embree 3 reference (CPU)",
                      .threads = o.threads ? o.threads : (uint32_t)sysconf(_SC_NPROCESSORS_ONLN)};
    add_pass(&run, "embree_scene_build", "cpu_wall", build_ms);
    int status = 0;
    roma_context *ctx = NULL;
    roma_context_info ctx_info;
    roma_effect_stats roma_stats;
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
            roma_effect_render_desc desc = {
                .camera = cam, .width = o.width, .height = o.height,
                .options = {.effects = o.effects, .resolution = o.res, .ao_angular = o.angular,
                            .gi_angular = o.angular, .shadow_angular = o.shadow_angular,
                            .lights_angular = o.shadow_angular, .many_light_count = o.lights},
                .spp = o.spp, .frames = o.frames, .seed = o.seed, .ao_radius = o.ao_radius,
                .max_steps = o.max_steps, .lights_per_frame = o.lights_per_frame,
                /* The library takes 0 as its default and a negative value as none. */
                .skip_cells = o.skip < 0.0f ? 0.0f : o.skip == 0.0f ? -1.0f : o.skip,
                .ao_skip_cells = o.ao_skip < 0.0f ? 0.0f : o.ao_skip == 0.0f ? -1.0f : o.ao_skip,
                .offset_cells = o.offset,
                .many_light_positions = light_positions,
            };
            roma_effect_images images;
            double start = roma_app_now_ms();
            r = roma_effect_render(ctx, scene, &desc, &images, &roma_stats);
            add_pass(&run, "roma_total", "cpu_wall", roma_app_now_ms() - start);
            if (r != ROMA_SUCCESS) {
                fprintf(stderr, "roma-render: ROMA rendering failed: %s\n", roma_result_string(r));
                status = 1;
            } else {
                for (int p = 0; p < ROMA_PASS_COUNT; ++p) {
                    if (!roma_effect_plan_runs(&roma_stats.plan, (roma_pass_kind)p))
                        continue;
                    add_pass(&run, roma_pass_name((roma_pass_kind)p), "gpu_timestamp", roma_stats.pass_ms[p]);
                    run.passes[run.pass_count - 1].bytes = roma_stats.pass_bytes[p];
                }
                run.roma = &roma_stats;
                if ((o.effects & ROMA_EFFECT_AO) && !write_outputs(&o, "ao", &images.ao, ROMA_PNG_SRGB, 1.0f))
                    status = 1;
                if ((o.effects & ROMA_EFFECT_DIRECT) &&
                    !write_outputs(&o, "direct", &images.direct, ROMA_PNG_SRGB, 1.0f))
                    status = 1;
                if ((o.effects & ROMA_EFFECT_GI) && !write_outputs(&o, "gi", &images.gi, ROMA_PNG_SRGB, 1.0f))
                    status = 1;
                if ((o.effects & ROMA_EFFECT_LIGHTS) &&
                    !write_outputs(&o, "lights", &images.lights, ROMA_PNG_SRGB, 1.0f / (float)o.lights))
                    status = 1;
                if (status == 0 && !write_extras(&o, &images.coverage, &images.direct, &images.gi))
                    status = 1;
                roma_effect_images_free(&images);
            }
        }
    }
    roma_image kept_coverage = {0}, kept_direct = {0}, kept_gi = {0};
    effect_output effects[4] = {{"ao", ROMA_EFFECT_AO, 0}, {"direct", ROMA_EFFECT_DIRECT, 0},
                                {"gi", ROMA_EFFECT_GI, 0}, {"lights", ROMA_EFFECT_LIGHTS, 0}};
    for (int e = 0; e < 4 && status == 0 && !ctx; ++e) {
        if (!(o.effects & effects[e].bit))
            continue;
        /* One effect per call so that each gets its own time and progress line. */
        progress_state progress = {effects[e].name, o.quiet, -1};
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
        case ROMA_EFFECT_AO: ok = write_outputs(&o, "ao", &images.ao, ROMA_PNG_SRGB, 1.0f); break;
        case ROMA_EFFECT_DIRECT: ok = write_outputs(&o, "direct", &images.direct, ROMA_PNG_SRGB, 1.0f); break;
        case ROMA_EFFECT_GI: ok = write_outputs(&o, "gi", &images.gi, ROMA_PNG_SRGB, 1.0f); break;
        case ROMA_EFFECT_LIGHTS:
            ok = write_outputs(&o, "lights", &images.lights, ROMA_PNG_SRGB, 1.0f / (float)o.lights);
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
    if (status == 0 && o.stats && !write_stats(&o, &sv, &cam, &run))
        status = 1;
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
