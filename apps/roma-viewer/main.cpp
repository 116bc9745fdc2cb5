// roma-viewer: the interactive viewer of libroma, built on the public API only (the
// installed libraries roma::roma, roma::gltf and roma::tools, the public headers and the
// public GLSL), as an engine would use it: its own instance, device, swapchain and
// G-buffer; libroma's map build, animator, AO and light effects recorded into its command
// buffers with two frames in flight; its own compute pass tracing ROMA rays for the debug
// views. --headless renders without a window (tests, scripts).
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>
#include <stb_image_write.h>

#include <roma/animation.h>
#include <roma/ao_effect.h>
#include <roma/builtin_scenes.h>
#include <roma/gltf.h>
#include <roma/image.h>
#include <roma/gi_effect.h>
#include <roma/light_effect.h>
#include <roma/roma.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "app_common.h"
#include "gbuffer_pass.h"
#include "many_lights.h"
#include "compose_pass.h"
#include "swapchain.h"
#include "reference_job.h"
#include "script.h"
#include "stats_json.h"
#include "ui.h"

namespace {

constexpr uint32_t kSlots = 2;      // frames in flight
constexpr uint32_t kStamps = 6;     // timestamps per frame
constexpr uint32_t kHistory = 240;  // frame-time graph

const char *kUsage =
    "usage: roma-viewer [--scene builtin:NAME|FILE.gltf|FILE.glb] [options]\n"
    "  --scene S            a built-in scene (default builtin:cornell) or a glTF 2.0 file;\n"
    "                       a glTF file dropped on the window opens too\n"
    "  --camera ex,ey,ez,tx,ty,tz,fovy   start camera (the string roma-render takes)\n"
    "  --size WxH           window or image size (default 1280x720)\n"
    "  --up +y|-y|+z        the scene's up axis (tabletop.gltf: -y; static scenes only)\n"
    "  --gltf-camera N      which of a glTF file's perspective cameras to start from (default 0)\n"
    "  --view NAME          composed, ao, direct, gi, albedo, normal, map, hit-distance, steps,\n"
    "                       rotated-map (--map K: which of the A x A maps, default 0), ray-start,\n"
    "                       levels (the cascade level of each point)\n"
    "  --res R --angular A  ROMA array (default 128, 4)\n"
    "  --preset NAME        ROMA array of a quality preset: low (128, 2), medium (128, 4), high\n"
    "                       (256, 4), ultra (256, 8); a later --res or --angular overrides it\n"    "  --cascades K         K cascade levels around the camera, each twice the last's size (default\n"
    "                       0: several for a scene much wider than the AO radius, else 1)\n"
    "  --finest-extent E    the finest level's edge (default: RES x the AO radius / 30)\n"
    "  --ao-samples N       AO rays per pixel and frame (default 4)\n"
    "  --ao-radius R        AO ray length (default: 10% of the scene's diagonal)\n"
    "  --area-samples N     area-light samples per pixel and frame (default 4)\n"
    "  --many-lights N      N synthetic point lights added to the direct light (default 0)\n"
    "  --lights-per-frame K of them, traced per pixel and frame (default 8; the scene's\n"
    "                       own lights are traced every frame)\n"
    "  --max-steps N        texels an un-snapped shadow ray walks (default 8, the paper's)\n"
    "  --ao-skip C --offset C   AO rays' skip and every ray's origin offset, in trace cells\n"
    "                       (default: the library's, 1.6 and 1.5)\n"
    "  --exposure E         (default 1.2)\n"    "  --sky S              sky radiance the composed view scales by AO (default: 0.2 where the\n"
    "                       scene has lights, 1 where it has none, so that it opens readable)\n"
    "  --time T --clip N    animation time and clip; --play starts playing\n"
    "  --headless           no window: render --frames frames and exit\n"
    "  --frames N           exit after N frames (default: run until closed; headless 16)\n"
    "  --screenshot F.png   after the last frame: the picture (8-bit) to F.png\n"
    "  --linear F.pfm|F.exr after the last frame: the accumulated linear values of the view\n"
    "  --slice-axis x|y|z --slice-depth D   the layer the bom-slice view shows (headless: the\n"
    "                       occupancy map is captured after the first frame)\n"
    "  --compare-reference  headless, AO or direct view: after the last frame, render the\n"
    "                       same view with the Embree reference (roma-render beside the\n"
    "                       viewer, --reference-spp samples, default 64) and print the MAE\n"
    "  --script FILE        input events for tests and demos (apps/roma-viewer/script.h)\n"
    "  --stats FILE.json    at exit: frames, the passes of the last frame, timings, messages\n"
    "  --validation         Khronos validation layer on; exit status 1 on any message\n"
    "  --device NAME        a device whose name contains NAME\n"
    "Keys: F frame the scene, Tab orbit/fly, F12 screenshot (roma-viewer-N.png), Esc quit.\n";

struct options {
    std::string scene = "builtin:cornell";
    roma_camera camera{};
    bool has_camera = false;
    uint32_t width = 1280, height = 720;
    bool headless = false, validation = false, play = false, compare_reference = false;
    uint32_t frames = 0;
    std::string screenshot, linear, device, up = "+y", script, stats;
    uint32_t gltf_camera = 0;
    bool sky_given = false; // --sky: else each scene's default (sky_for_scene)
    viewer_settings settings;
};

bool parse_u32(const char *s, uint32_t lo, uint32_t hi, uint32_t &out)
{
    char *end;
    unsigned long v = std::strtoul(s, &end, 10);
    if (end == s || *end || s[0] == '-' || v < lo || v > hi)
        return false;
    out = static_cast<uint32_t>(v);
    return true;
}

bool parse_float(const char *s, float lo, float hi, float &out)
{
    char *end;
    float v = std::strtof(s, &end);
    if (end == s || *end || !(v >= lo && v <= hi))
        return false;
    out = v;
    return true;
}

const char *kViewNames[VIEW_COUNT] = {"composed", "ao",        "direct",    "albedo",    "normal",    "map",
                                     "hit-distance", "bom-slice", "reference", "difference", "gi", "steps",
                                     "rotated-map", "ray-start", "levels"};

int parse_args(int argc, char **argv, options &o)
{
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : nullptr;
        bool ok = true, used = true;
        if (a == "--help" || a == "-h") {
            std::fputs(kUsage, stdout);
            return 0;
        } else if (a == "--headless") {
            o.headless = true, used = false;
        } else if (a == "--validation") {
            o.validation = true, used = false;
        } else if (a == "--play") {
            o.play = true, used = false;
        } else if (a == "--compare-reference") {
            o.compare_reference = true, used = false;
        } else if (!v) {
            std::fprintf(stderr, "roma-viewer: %s needs a value (see --help)\n", a.c_str());
            return 2;
        } else if (a == "--scene") {
            o.scene = v;
        } else if (a == "--camera") {
            ok = o.has_camera = camera_from_string(v, o.camera);
        } else if (a == "--size") {
            unsigned w = 0, h = 0;
            char tail;
            ok = std::sscanf(v, "%ux%u%c", &w, &h, &tail) == 2 && w >= 8 && h >= 8 && w <= 8192 && h <= 8192;
            o.width = w, o.height = h;
        } else if (a == "--view") {
            ok = false;
            for (uint32_t k = 0; k < VIEW_COUNT; ++k)
                if (!std::strcmp(v, kViewNames[k]))
                    o.settings.view = static_cast<view_mode>(k), ok = true;
            if (!ok) {
                std::string valid; // the reference views need a reference first: not from here
                for (uint32_t k = 0; k < VIEW_COUNT; ++k)
                    if (k != VIEW_REFERENCE && k != VIEW_DIFFERENCE)
                        valid += std::string(valid.empty() ? "" : ", ") + kViewNames[k];
                std::fprintf(stderr, "roma-viewer: unknown view '%s' (valid: %s)\n", v, valid.c_str());
                return 2;
            }
        } else if (a == "--res") {
            ok = parse_u32(v, 32, 256, o.settings.res) && (o.settings.res & (o.settings.res - 1)) == 0;
        } else if (a == "--angular") {
            ok = parse_u32(v, 1, 16, o.settings.angular);
        } else if (a == "--cascades") {
            ok = parse_u32(v, 0, ROMA_MAX_LEVELS, o.settings.cascades);
        } else if (a == "--finest-extent") {
            ok = parse_float(v, 1e-6f, 1e30f, o.settings.finest_extent);
        } else if (a == "--preset") {
            roma_preset p = ROMA_PRESET_DEFAULT;
            ok = roma_preset_parse(v, &p) == ROMA_SUCCESS &&
                 roma_preset_map_settings(p, &o.settings.res, &o.settings.angular) == ROMA_SUCCESS;
        } else if (a == "--ao-samples") {
            ok = parse_u32(v, 1, 256, o.settings.ao_samples);
        } else if (a == "--ao-skip" || a == "--offset") {
            ok = parse_float(v, 0.01f, 16.0f, a == "--offset" ? o.settings.offset : o.settings.ao_skip);
        } else if (a == "--map") {
            ok = parse_u32(v, 0, 255, o.settings.map_index);
        } else if (a == "--max-steps") {
            ok = parse_u32(v, 1, 1024, o.settings.max_steps);
        } else if (a == "--area-samples") {
            ok = parse_u32(v, 1, 1024, o.settings.area_samples);
        } else if (a == "--many-lights") {
            ok = parse_u32(v, 0, 65536, o.settings.many_lights);
        } else if (a == "--lights-per-frame") {
            ok = parse_u32(v, 1, 65536, o.settings.lights_per_frame);
        } else if (a == "--ao-radius") {
            ok = parse_float(v, 1e-6f, 1e30f, o.settings.ao_radius);
        } else if (a == "--sky") {
            ok = parse_float(v, 0.0f, 1e6f, o.settings.ambient);
            o.sky_given = ok;
        } else if (a == "--exposure") {
            ok = parse_float(v, 1e-6f, 1e6f, o.settings.exposure);
        } else if (a == "--time") {
            ok = parse_float(v, 0.0f, 1e6f, o.settings.time);
        } else if (a == "--clip") {
            ok = parse_u32(v, 0, 1u << 20, o.settings.clip);
        } else if (a == "--slice-axis") {
            ok = std::strlen(v) == 1 && v[0] >= 'x' && v[0] <= 'z';
            o.settings.slice_axis = ok ? uint32_t(v[0] - 'x') : 0;
        } else if (a == "--slice-depth") {
            ok = parse_u32(v, 0, 255, o.settings.slice_depth);
        } else if (a == "--reference-spp") {
            ok = parse_u32(v, 1, 1u << 16, o.settings.reference_spp);
        } else if (a == "--frames") {
            ok = parse_u32(v, 1, 1u << 30, o.frames);
        } else if (a == "--screenshot") {
            o.screenshot = v;
        } else if (a == "--linear") {
            o.linear = v;
        } else if (a == "--gltf-camera") {
            ok = parse_u32(v, 0, 1u << 20, o.gltf_camera);
        } else if (a == "--up") {
            o.up = v;
            if (!roma_app_valid_up(v)) {
                std::fprintf(stderr, "roma-viewer: bad value for --up: '%s' (valid: +y, -y, +z)\n", v);
                return 2;
            }
        } else if (a == "--script") {
            o.script = v;
        } else if (a == "--stats") {
            o.stats = v;
        } else if (a == "--device") {
            o.device = v;
        } else {
            std::fprintf(stderr, "roma-viewer: unknown option %s (see --help)\n", a.c_str());
            return 2;
        }
        if (!ok) {
            std::fprintf(stderr, "roma-viewer: bad value for %s: '%s' (see --help)\n", a.c_str(), v);
            return 2;
        }
        if (used)
            ++i;
    }
    if (o.headless && !o.frames)
        o.frames = 16;
    if (o.headless && o.settings.view == VIEW_BOM_SLICE && o.frames < 2) {
        // The slice shows the BOM captured after the first frame's build: a second frame draws it.
        std::fprintf(stderr, "roma-viewer: the bom-slice view draws from the second frame: 2 frames\n");
        o.frames = 2;
    }
    if (o.headless && !o.script.empty()) {
        std::fprintf(stderr, "roma-viewer: --script drives the window; without --headless (Xvfb works)\n");
        return 2;
    }
    if (o.settings.view == VIEW_REFERENCE || o.settings.view == VIEW_DIFFERENCE) {
        std::fprintf(stderr, "roma-viewer: the reference views need a reference first (--compare-reference)\n");
        return 2;
    }
    if (o.compare_reference && (!o.headless || (o.settings.view != VIEW_AO && o.settings.view != VIEW_DIRECT))) {
        std::fprintf(stderr, "roma-viewer: --compare-reference needs --headless and --view ao or --view direct "
                             "(in the window: the button under \"What the rays see\")\n");
        return 2;
    }
    return -1;
}

struct gpu_scene {
    vk_buffer positions, indices, albedo;
    uint32_t vertex_count = 0, triangle_count = 0;
};

struct viewer {
    options opt;
    vk_base base;
    GLFWwindow *window = nullptr;
    swapchain sc;
    bool imgui = false;
    VkDescriptorPool imgui_pool = VK_NULL_HANDLE;
    roma_context *ctx = nullptr;
    roma_scene *scene = nullptr;
    roma_scene_view view{};
    gpu_scene gs;
    roma_map *map = nullptr;
    roma_animator *animator = nullptr;
    roma_ao_effect *ao = nullptr;
    roma_light_effect *light = nullptr;
    roma_gi_effect *gi = nullptr;
    roma_temporal_effect *temporal = nullptr; // the picture averaged over frames
    gbuffer_pass gb;
    compose_pass cp;
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd[kSlots] = {};
    VkFence fence[kSlots] = {};
    VkSemaphore acquired[kSlots] = {};
    bool submitted[kSlots] = {};
    VkQueryPool queries = VK_NULL_HANDLE;
    double timestamp_ns = 1.0;
    uint32_t frame = 0, accumulated = 0, screenshots = 0;
    viewer_settings s;
    viewer_timings timings;
    viewer_info info;
    camera_control cam;
    // debug: a captured BOM and the Embree reference of the compared view
    vk_buffer bom, reference;
    float bom_origin[4] = {};
    uint32_t bom_res = 0;
    reference_job job;
    view_mode compared = VIEW_AO;
    roma_image coverage{};
    std::vector<std::string> passes; // what the last recorded frame ran
    std::vector<roma_light> lights;  // the scene's punctual lights, then the many lights
    uint32_t lights_made = UINT32_MAX; // the many-lights count `lights` was made for
    bool camera_moved = false;       // since the last recorded frame: reproject the history
    float prev_clip_rows[4][4] = {}; // the last recorded frame's world -> clip
    uint32_t scene_failures = 0;     // scenes that could not be opened (dropped files)
    float gi_pose_time = -1.0f;      // the animation time the GI effect's surfaces were posed at
    uint32_t gi_pose_clip = 0;
};

void log_to_stderr(roma_log_level level, roma_result, const char *message, void *)
{
    if (level >= ROMA_LOG_WARNING)
        std::fprintf(stderr, "roma-viewer: libroma %s: %s\n", roma_log_level_string(level), message);
}

// --- the scene on the GPU ---------------------------------------------------------------

bool upload_scene(viewer &v)
{
    const roma_scene_view &sv = v.view;
    gpu_scene &g = v.gs;
    g.vertex_count = sv.vertex_count;
    g.triangle_count = sv.triangle_count;
    VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    if (!vk_buffer_create(v.base, sizeof(float) * 3 * sv.vertex_count, storage, true, g.positions) ||
        !vk_buffer_create(v.base, sizeof(uint32_t) * 3 * sv.triangle_count, storage, true, g.indices) ||
        !vk_buffer_create(v.base, sizeof(float) * 4 * sv.triangle_count, storage, true, g.albedo)) {
        std::fprintf(stderr, "roma-viewer: out of memory for the scene's buffers\n");
        return false;
    }
    std::memcpy(g.positions.mapped, sv.positions, sizeof(float) * 3 * sv.vertex_count);
    std::memcpy(g.indices.mapped, sv.indices, sizeof(uint32_t) * 3 * sv.triangle_count);
    float *albedo = static_cast<float *>(g.albedo.mapped);
    for (uint32_t t = 0; t < sv.triangle_count; ++t) {
        const roma_material &m = sv.materials[sv.triangle_materials[t]];
        for (int c = 0; c < 3; ++c)
            albedo[4 * t + c] = m.base_color[c];
        albedo[4 * t + 3] = 1.0f;
    }
    return true;
}

void free_scene(viewer &v)
{
    vk_buffer_destroy(v.base, v.gs.positions);
    vk_buffer_destroy(v.base, v.gs.indices);
    vk_buffer_destroy(v.base, v.gs.albedo);
    roma_animator_destroy(v.animator);
    v.animator = nullptr;
    roma_map_destroy(v.map);
    v.map = nullptr;
    roma_scene_destroy(v.scene);
    v.scene = nullptr;
}

float effective_ao_radius(const viewer &v)
{
    return v.s.ao_radius > 0.0f ? v.s.ao_radius : v.s.auto_ao_radius;
}

// The cascade levels the settings ask for (0: chosen for the scene and the AO radius, as
// roma-render chooses), and the finest level's edge; at most 256 maps in all.
uint32_t wanted_levels(const viewer &v, float &finest)
{
    const float longest = std::max({v.view.bounds_max[0] - v.view.bounds_min[0],
                                    v.view.bounds_max[1] - v.view.bounds_min[1],
                                    v.view.bounds_max[2] - v.view.bounds_min[2]});
    uint32_t chosen = roma_app_auto_cascades(longest, v.s.res, effective_ao_radius(v), v.s.finest_extent, &finest);
    uint32_t levels = v.s.cascades ? v.s.cascades : chosen;
    return std::max(1u, std::min(levels, 256u / (v.s.angular * v.s.angular)));
}

bool create_map(viewer &v)
{
    roma_map_destroy(v.map);
    v.map = nullptr;
    roma_map_desc md{};
    md.resolution = v.s.res;
    md.angular = v.s.angular;
    md.frames_in_flight = kSlots;
    md.cascades = wanted_levels(v, v.info.finest_extent);
    if (roma_map_create(v.ctx, &md, v.scene, &v.map) != ROMA_SUCCESS) {
        std::fprintf(stderr, "roma-viewer: cannot create a RES %u, A %u map of %u cascade levels\n", v.s.res,
                     v.s.angular, md.cascades);
        return false;
    }
    roma_map_info mi;
    roma_map_get_info(v.map, &mi);
    v.info.levels = mi.levels;
    v.info.map_bytes = mi.bom_bytes + mi.maps_bytes + mi.params_bytes + mi.geometry_bytes;
    v.info.grid_cell = mi.grid_cell;
    return true;
}

// libroma's plan for every effect on this scene (roma/effects.h), and which of its passes
// the viewer runs through the public effect API.
void describe_plan(viewer &v)
{
    roma_effect_options eo{};
    eo.effects = ROMA_EFFECT_AO | ROMA_EFFECT_DIRECT | ROMA_EFFECT_GI | ROMA_EFFECT_LIGHTS;
    eo.resolution = v.s.res;
    eo.ao_angular = v.s.angular;
    roma_effect_plan plan;
    std::string text;
    if (roma_effect_plan_derive(v.scene, &eo, nullptr, &plan) != ROMA_SUCCESS) {
        v.info.plan = "no plan (roma_effect_plan_derive failed)";
        return;
    }
    text = "For every effect, libroma's plan runs:";
    for (uint32_t p = 0; p < ROMA_PASS_COUNT; ++p) {
        if (!roma_effect_plan_runs(&plan, roma_pass_kind(p)))
            continue;
        text += std::string("\n  ") + roma_pass_name(roma_pass_kind(p));
        if (plan.pass_map[p] >= 0) {
            const roma_map_config &m = plan.maps[plan.pass_map[p]];
            text += " (RES " + std::to_string(m.resolution) + ", A " + std::to_string(m.angular) + ")";
        }
    }
    text += "\n" + std::to_string(plan.map_count) + " ROMA arrays. The viewer runs the G-buffer, AO (roma_ao_effect)";
    text += v.view.light_count || v.view.emissive_triangle_count
                ? ", direct light from punctual and area lights (roma_light_effect) and one-bounce GI"
                  " (roma_gi_effect, its hits lit by shadow rays)"
                : " (no lights in the scene: no direct light, no GI)";
    text += " on one array. Many lights (when asked for) are added to the direct light: the light effect"
            " traces a few of them per pixel and frame (lights_per_frame) and the accumulation averages them;"
            " GI carries the scene's own lights only.";
    v.info.plan = text;
}

// The camera framing the scene's bounds at the picture's aspect (the options' size before
// the first picture is made).
void frame_scene(viewer &v)
{
    uint32_t w = v.gb.width ? v.gb.width : v.opt.width, h = v.gb.height ? v.gb.height : v.opt.height;
    camera_control_frame_bounds(v.cam, v.view.bounds_min, v.view.bounds_max, float(w) / float(std::max(1u, h)));
}

// Loads a scene (built-in or glTF) and everything made from it; the device must be idle.
// On failure the previous scene stays. A dropped file opens at its first camera
// (--gltf-camera names one of the command line's file).
bool open_scene(viewer &v, const std::string &name, bool dropped = false)
{
    roma_logger logger{log_to_stderr, nullptr};
    roma_scene *scene = nullptr;
    roma_result r;
    if (name.rfind("builtin:", 0) == 0 || name == "builtin") {
        const char *builtin = name.size() > 8 ? name.c_str() + 8 : nullptr;
        r = roma_scene_create_builtin(builtin, &logger, &scene);
    } else {
        roma_gltf_desc gd{};
        gd.logger = logger;
        gd.camera_index = dropped ? 0 : v.opt.gltf_camera;
        r = roma_scene_load_gltf(name.c_str(), &gd, &scene);
    }
    if (r != ROMA_SUCCESS) {
        std::fprintf(stderr, "roma-viewer: cannot open %s: %s\n", name.c_str(), roma_result_string(r));
        return false;
    }
    if (v.opt.up != "+y") {
        roma_scene_view sv;
        roma_scene_get_view(scene, &sv);
        roma_scene *turned = nullptr;
        if (sv.animation.animation_count > 0) {
            std::fprintf(stderr, "roma-viewer: --up is not applied to an animated scene\n");
        } else if (roma_app_reorient(scene, v.opt.up.c_str(), &turned) == ROMA_SUCCESS) {
            roma_scene_destroy(scene);
            scene = turned;
        }
    }
    free_scene(v);
    v.scene = scene;
    roma_scene_get_view(scene, &v.view);
    // The reference, its coverage and the captured BOM were the previous scene's.
    v.info.reference_ready = false;
    v.info.reference_status.clear();
    roma_image_free(&v.coverage);
    v.bom_res = 0;
    v.info.bom_captured = false;
    v.gi_pose_time = -1.0f;
    v.lights_made = UINT32_MAX; // the many lights follow the new scene's bounds
    v.info.scene_cameras.clear();
    for (uint32_t i = 0; i < v.view.camera_count; ++i)
        v.info.scene_cameras.push_back("camera " + std::to_string(i) + ": " + camera_to_string(v.view.cameras[i]));
    v.info.scene_name = name;
    v.info.vertices = v.view.vertex_count;
    v.info.triangles = v.view.triangle_count;
    v.info.lights = v.view.light_count;
    v.info.area_light_triangles = v.view.emissive_triangle_count;
    float dx = v.view.bounds_max[0] - v.view.bounds_min[0], dy = v.view.bounds_max[1] - v.view.bounds_min[1],
          dz = v.view.bounds_max[2] - v.view.bounds_min[2];
    v.s.auto_ao_radius = 0.1f * std::sqrt(dx * dx + dy * dy + dz * dz); // before the map: it sets the cascades
    if (!upload_scene(v) || !create_map(v))
        return false;
    if (roma_light_effect_set_area_lights(v.light, scene) != ROMA_SUCCESS ||
        roma_gi_effect_set_scene(v.gi, scene) != ROMA_SUCCESS)
        return false;
    v.s.animated = false;
    if (v.view.animation.animation_count > 0 && v.view.animation.vertex_node) {
        roma_animator_desc ad{};
        ad.frames_in_flight = kSlots;
        if (roma_animator_create(v.ctx, scene, &ad, &v.animator) == ROMA_SUCCESS) {
            roma_animator_info ai;
            roma_animator_get_info(v.animator, &ai);
            v.s.animated = true;
            v.s.clip_count = ai.clip_count;
            v.s.clip = std::min(v.s.clip, ai.clip_count ? ai.clip_count - 1 : 0u);
            roma_animator_clip_duration(v.animator, v.s.clip, &v.s.duration);
            v.s.playing = v.opt.play;
        }
    }
    // A scene without lights is lit by the sky alone: at the lit scenes' 0.2 it would open
    // nearly black.
    if (!v.opt.sky_given)
        v.s.ambient = v.view.light_count || v.view.emissive_triangle_count || v.s.many_lights ? 0.2f : 1.0f;
    describe_plan(v);
    frame_scene(v);
    if (v.view.has_camera)
        camera_control_set(v.cam, v.view.camera);
    v.accumulated = 0;
    return true;
}

// The animation's clip may have changed (UI): its duration, and the time within it.
void follow_clip(viewer &v)
{
    if (!v.s.animated || roma_animator_clip_duration(v.animator, v.s.clip, &v.s.duration) != ROMA_SUCCESS)
        return;
    if (v.s.time > v.s.duration)
        v.s.time = v.s.duration > 0.0f ? std::fmod(v.s.time, v.s.duration) : 0.0f;
}

// --- device, libroma objects, passes ------------------------------------------------------

bool create_frame_objects(viewer &v)
{
    VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pi.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pi.queueFamilyIndex = v.base.family;
    if (vkCreateCommandPool(v.base.device, &pi, nullptr, &v.pool) != VK_SUCCESS)
        return false;
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = v.pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = kSlots;
    if (vkAllocateCommandBuffers(v.base.device, &ai, v.cmd) != VK_SUCCESS)
        return false;
    for (uint32_t i = 0; i < kSlots; ++i) {
        VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        if (vkCreateFence(v.base.device, &fi, nullptr, &v.fence[i]) != VK_SUCCESS ||
            vkCreateSemaphore(v.base.device, &si, nullptr, &v.acquired[i]) != VK_SUCCESS)
            return false;
    }
    VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
    qi.queryCount = kSlots * kStamps;
    if (vkCreateQueryPool(v.base.device, &qi, nullptr, &v.queries) != VK_SUCCESS)
        return false;
    vkResetQueryPool(v.base.device, v.queries, 0, kSlots * kStamps);
    v.timestamp_ns = v.base.properties.limits.timestampPeriod;
    bool cpu = v.base.properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    v.timings.clock = cpu ? "GPU timestamps (a CPU device: they may not cover compute work)" : "GPU timestamps";
    return true;
}

bool create_libroma(viewer &v)
{
    roma_external_device ext{};
    ext.instance = v.base.instance;
    ext.physical_device = v.base.physical;
    ext.device = v.base.device;
    ext.queue_family_index = v.base.family;
    ext.queue = v.base.queue;
    ext.enabled_features = &v.base.requirements.features;
    roma_context_desc cd{};
    cd.external = &ext;
    cd.logger = {log_to_stderr, nullptr};
    if (roma_context_create(&cd, &v.ctx) != ROMA_SUCCESS)
        return false;
    roma_context_info ci{};
    roma_context_get_info(v.ctx, &ci);
    v.cp.corrected_division = ci.corrected_division; // the compose shader traces as libroma does
    roma_ao_effect_desc ad{};
    ad.frames_in_flight = kSlots;
    roma_light_effect_desc ld{};
    ld.frames_in_flight = kSlots;
    roma_gi_effect_desc gd{};
    gd.frames_in_flight = kSlots;
    roma_temporal_effect_desc td{};
    td.frames_in_flight = kSlots;
    return roma_ao_effect_create(v.ctx, &ad, &v.ao) == ROMA_SUCCESS &&
           roma_light_effect_create(v.ctx, &ld, &v.light) == ROMA_SUCCESS &&
           roma_gi_effect_create(v.ctx, &gd, &v.gi) == ROMA_SUCCESS &&
           roma_temporal_effect_create(v.ctx, &td, &v.temporal) == ROMA_SUCCESS;
}

bool resize_images(viewer &v, uint32_t width, uint32_t height)
{
    vkDeviceWaitIdle(v.base.device);
    v.info.width = width;
    v.info.height = height;
    v.accumulated = 0;
    vk_buffer_destroy(v.base, v.reference);
    v.info.reference_ready = false;
    if (!v.bom.buffer && !vk_buffer_create(v.base, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true, v.bom))
        return false;
    if (!gbuffer_pass_resize(v.base, v.gb, width, height) || !compose_pass_resize(v.base, v.cp, v.gb) ||
        !vk_buffer_create(v.base, VkDeviceSize(width) * height * 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true,
                          v.reference))
        return false;
    std::memset(v.reference.mapped, 0, size_t(width) * height * 16);
    compose_pass_set_buffers(v.base, v.cp, v.reference.buffer, v.bom.buffer);
    return true;
}

// The BOM of the last build, for the slice view (blocking: a debug action).
bool capture_bom(viewer &v)
{
    vkDeviceWaitIdle(v.base.device);
    roma_map_info mi;
    roma_map_get_info(v.map, &mi);
    uint64_t words = uint64_t(mi.resolution) * mi.resolution * mi.resolution / 32;
    vk_buffer_destroy(v.base, v.bom);
    v.bom_res = 0;
    v.info.bom_captured = false;
    if (!vk_buffer_create(v.base, words * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true, v.bom)) {
        // The slice view's set must not keep pointing at the freed buffer: a small one stands in.
        if (vk_buffer_create(v.base, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true, v.bom))
            compose_pass_set_buffers(v.base, v.cp, v.reference.buffer, v.bom.buffer);
        return false;
    }
    roma_result r = roma_map_download_bom(v.map, static_cast<uint32_t *>(v.bom.mapped), words);
    if (r != ROMA_SUCCESS) {
        std::fprintf(stderr, "roma-viewer: cannot download the occupancy map: %s\n", roma_result_string(r));
        std::memset(v.bom.mapped, 0, words * 4);
    }
    for (int i = 0; i < 3; ++i)
        v.bom_origin[i] = mi.grid_origin[i];
    v.bom_origin[3] = mi.grid_cell;
    v.bom_res = r == ROMA_SUCCESS ? mi.resolution : 0;
    v.info.bom_captured = v.bom_res != 0;
    v.accumulated = 0; // the view changes
    compose_pass_set_buffers(v.base, v.cp, v.reference.buffer, v.bom.buffer);
    return r == ROMA_SUCCESS;
}

// Starts the Embree reference of the current view (AO, or direct in the direct view).
void start_reference(viewer &v)
{
    v.compared = v.s.view == VIEW_DIRECT ? VIEW_DIRECT : VIEW_AO;
    if (v.compared == VIEW_DIRECT && v.s.many_lights > 0) {
        // roma-render's reference knows the scene's lights only.
        v.info.reference_status = "the reference has the scene's own lights: turn the many lights off to compare";
        v.info.reference_ready = false;
        return;
    }
    std::string camera = camera_to_string(camera_control_get(v.cam));
    // The scene as the viewer shows it: turned (not for animated scenes, as open_scene), posed.
    std::string scene_options;
    if (v.opt.up != "+y" && !v.s.animated)
        scene_options += " --up '" + v.opt.up + "'";
    if (v.s.animated) {
        char pose[96];
        std::snprintf(pose, sizeof pose, " --time %.9g --clip %u", double(v.s.time), v.s.clip);
        scene_options += pose;
    }
    bool was_running = v.job.running;
    if (!reference_job_start(v.job, reference_tool_path(), camera, v.gb.width, v.gb.height, v.s.reference_spp,
                             effective_ao_radius(v), v.info.scene_name, scene_options))
        v.info.reference_status = was_running ? "a reference render is still running" : v.job.message;
    else
        v.info.reference_status = "rendering the reference: " + v.job.command;
    v.info.reference_ready = false;
}

// When the job has finished: its image into the reference buffer, the coverage kept.
void finish_reference(viewer &v)
{
    if (!v.job.finished || v.job.running)
        return;
    v.job.finished = false;
    reference_job_join(v.job);
    if (!v.job.ok) {
        v.info.reference_status = v.job.message;
        return;
    }
    roma_image img{};
    roma_image_free(&v.coverage);
    const char *name = v.compared == VIEW_DIRECT ? "direct" : "ao";
    if (!reference_job_image(v.job, name, &img) || !reference_job_image(v.job, "coverage", &v.coverage) ||
        img.width != v.gb.width || img.height != v.gb.height) {
        v.info.reference_status = "the reference's images are missing or of another size (the window changed?)";
        roma_image_free(&img);
        return;
    }
    vkDeviceWaitIdle(v.base.device);
    float *dst = static_cast<float *>(v.reference.mapped);
    for (size_t i = 0; i < size_t(img.width) * img.height; ++i)
        for (uint32_t c = 0; c < 3; ++c)
            dst[4 * i + c] = img.pixels[i * img.channels + (img.channels == 1 ? 0 : c)];
    roma_image_free(&img);
    v.info.reference_ready = true;
    v.info.reference_status = std::string("reference of ") + name + " ready (" +
                              std::to_string(v.s.reference_spp) + " samples per pixel)";
}

// World -> clip rows for the G-buffer, from the same frame libroma's camera rays use
// (row 0 of the image at the top, depth 0 at the near plane).
void clip_rows(const roma_camera &cam, uint32_t width, uint32_t height, float scene_size, float rows[4][4])
{
    roma_camera_frame f;
    roma_camera_make_frame(&cam, width, height, &f);
    float near_plane = 1e-4f * scene_size, far_plane = 100.0f * scene_size;
    float a = far_plane / (far_plane - near_plane), b = -far_plane * near_plane / (far_plane - near_plane);
    const float *axes[3] = {f.right, f.up, f.forward};
    float scale[3] = {1.0f / (f.tan_half_fovy * f.aspect), -1.0f / f.tan_half_fovy, 1.0f};
    for (int r = 0; r < 3; ++r) {
        float d = 0.0f;
        for (int i = 0; i < 3; ++i) {
            rows[r][i] = axes[r][i] * scale[r];
            d += axes[r][i] * f.origin[i];
        }
        rows[r][3] = -d * scale[r];
    }
    // depth = a * z + b, w = z (z: distance along forward)
    for (int i = 0; i < 4; ++i) {
        float z = i < 3 ? f.forward[i] : -(f.forward[0] * f.origin[0] + f.forward[1] * f.origin[1] +
                                           f.forward[2] * f.origin[2]);
        rows[3][i] = z;
        rows[2][i] = a * z + (i == 3 ? b : 0.0f);
    }
}

// --- one frame ------------------------------------------------------------------------------

void stamp(viewer &v, VkCommandBuffer cmd, uint32_t slot, uint32_t k)
{
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, v.queries, slot * kStamps + k);
}

// An effect's inputs: the viewer's G-buffer images (the images struct of roma_ao_effect or
// of roma_light_effect / roma_gi_effect), and its output.
template <typename Images> Images gbuffer_images(const viewer &v, VkImageView output)
{
    Images images{};
    images.width = v.gb.width;
    images.height = v.gb.height;
    images.position = v.gb.position.view;
    images.normal = v.gb.normal.view;
    images.output = output;
    return images;
}

bool record_frame(viewer &v, uint32_t slot, VkCommandBuffer cmd)
{
    const viewer_settings &s = v.s;
    v.passes.clear();
    vkCmdResetQueryPool(cmd, v.queries, slot * kStamps, kStamps);
    stamp(v, cmd, slot, 0);
    VkDeviceAddress positions = v.gs.positions.address;
    roma_map_frame_desc fd{};
    fd.frame = v.frame;
    fd.seed = 1;
    fd.jitter_grid = 1;
    fd.jitter_directions = 1;
    fd.slot = slot;
    // Cascade levels centre on the camera.
    const roma_camera cam = camera_control_get(v.cam);
    if (v.info.levels > 1) {
        fd.focus = cam.eye;
        fd.finest_extent = v.info.finest_extent;
    }
    roma_animator_output out{};
    if (v.animator) {
        roma_animator_pose pose{s.clip, s.time};
        if (roma_animator_record(v.animator, cmd, slot, &pose, &out) != ROMA_SUCCESS)
            return false;
        v.passes.push_back("animate");
        positions = out.positions;
        fd.gpu_positions = out.positions;
        fd.vertex_count = v.gs.vertex_count;
        fd.volume = &out.bounds;
    }
    stamp(v, cmd, slot, 1);
    if (roma_map_record_build(v.map, cmd, &fd, nullptr) != ROMA_SUCCESS)
        return false;
    v.passes.push_back("map_build");
    stamp(v, cmd, slot, 2);
    // The skinned positions, read by the G-buffer's vertex shader.
    VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    mb.srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    mb.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    mb.dstStageMask = VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT;
    mb.dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_READ_BIT;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &mb;
    vkCmdPipelineBarrier2(cmd, &dep);
    gbuffer_draw draw{};
    clip_rows(cam, v.gb.width, v.gb.height, v.cam.scene_size, draw.clip_rows);
    for (int i = 0; i < 3; ++i)
        draw.eye[i] = cam.eye[i];
    draw.positions = positions;
    draw.albedo = v.gs.albedo.address;
    draw.indices = v.gs.indices.address;
    draw.triangle_count = v.gs.triangle_count;
    gbuffer_pass_record(v.gb, cmd, draw);
    v.passes.push_back("gbuffer");
    stamp(v, cmd, slot, 3);
    compose_pass_prepare(v.cp, cmd);
    view_mode shown = (s.view == VIEW_REFERENCE || s.view == VIEW_DIFFERENCE) ? v.compared : s.view;
    bool want_ao = s.ao_on && (shown == VIEW_COMPOSED || shown == VIEW_AO);
    bool lit = v.view.light_count > 0 || v.view.emissive_triangle_count > 0;
    bool want_direct = s.direct_on && (lit || s.many_lights > 0) && (shown == VIEW_COMPOSED || shown == VIEW_DIRECT);
    bool want_gi = s.gi_on && lit && (shown == VIEW_COMPOSED || shown == VIEW_GI);
    // The GI effect follows the map's triangles by itself; the area lights (of the direct
    // light and of GI's bounce hits) are CPU copies of the scene's emissive triangles
    // (light_effect.h, gi_effect.h): posed anew when the animation moves, between frames,
    // before this frame records an effect that reads them.
    bool posed_copies = (want_gi || want_direct) && v.view.emissive_triangle_count > 0;
    if (posed_copies && v.animator && (s.time != v.gi_pose_time || s.clip != v.gi_pose_clip)) {
        vkDeviceWaitIdle(v.base.device);
        roma_logger logger{log_to_stderr, nullptr};
        roma_animator_pose pose{s.clip, s.time};
        roma_scene *posed = nullptr;
        roma_result r = roma_scene_pose(v.scene, &pose, &logger, &posed);
        if (r == ROMA_SUCCESS)
            r = roma_gi_effect_set_scene(v.gi, posed);
        if (r == ROMA_SUCCESS)
            r = roma_light_effect_set_area_lights(v.light, posed);
        roma_scene_destroy(posed);
        if (r != ROMA_SUCCESS) {
            std::fprintf(stderr, "roma-viewer: cannot pose the GI surfaces: %s\n", roma_result_string(r));
            return false;
        }
        v.gi_pose_time = s.time;
        v.gi_pose_clip = s.clip;
    }
    if (want_ao) {
        roma_ao_images images = gbuffer_images<roma_ao_images>(v, v.cp.ao.view);
        roma_ao_settings as{};
        as.samples = s.ao_samples;
        as.radius = effective_ao_radius(v);
        as.offset_cells = s.offset;
        as.skip_cells = s.ao_skip;
        as.seed = 1;
        as.frame = v.frame;
        if (roma_ao_effect_record(v.ao, cmd, slot, v.map, &images, &as) != ROMA_SUCCESS)
            return false;
        v.passes.push_back("ao");
    }
    if (want_direct) {
        roma_light_images images = gbuffer_images<roma_light_images>(v, v.cp.light.view);
        roma_light_settings ls{};
        ls.max_steps = s.max_steps;
        ls.offset_cells = s.offset;
        ls.skip_cells = s.shadow_skip;
        ls.area_samples = s.area_samples;
        ls.seed = 1;
        ls.frame = v.frame;
        if (v.lights_made != s.many_lights) { // the scene's lights, then the many lights
            v.lights.assign(v.view.lights, v.view.lights + v.view.light_count);
            // The light effect takes 65,536 lights in all: the scene's count against that.
            uint32_t room = 65536u - std::min(65536u, v.view.light_count);
            if (s.many_lights > room)
                std::fprintf(stderr, "roma-viewer: %u many lights, %u with the scene's %u lights\n", s.many_lights,
                             room, v.view.light_count);
            std::vector<roma_light> many =
                make_many_lights(v.view.bounds_min, v.view.bounds_max, std::min(s.many_lights, room));
            v.lights.insert(v.lights.end(), many.begin(), many.end());
            v.lights_made = s.many_lights;
        }
        if (s.many_lights > 0) { // the scene's lights every frame, a few of the many sampled
            ls.lights_per_frame = s.lights_per_frame;
            ls.exact_light_count = v.view.light_count;
        }
        if (roma_light_effect_record(v.light, cmd, slot, v.map, &images, v.lights.data(),
                                     static_cast<uint32_t>(v.lights.size()), &ls) != ROMA_SUCCESS)
            return false;
        v.passes.push_back("direct_light");
        if (s.many_lights > 0)
            v.passes.push_back("many_lights");
    }
    if (want_gi) {
        roma_light_images images = gbuffer_images<roma_light_images>(v, v.cp.gi.view);
        roma_gi_settings gs{};
        gs.samples = s.gi_samples;
        gs.max_steps = s.max_steps;
        gs.offset_cells = s.offset;
        gs.skip_cells = s.ao_skip;
        gs.shadow_skip_cells = s.shadow_skip;
        gs.seed = 1;
        gs.frame = v.frame;
        if (roma_gi_effect_record(v.gi, cmd, slot, v.map, &images, v.view.lights, v.view.light_count, &gs) !=
            ROMA_SUCCESS)
            return false;
        v.passes.push_back("gi");
    }
    stamp(v, cmd, slot, 4);
    roma_map_info mi;
    roma_map_get_info(v.map, &mi);
    compose_settings cs{};
    for (int i = 0; i < 3; ++i) {
        cs.ambient[i] = s.ambient;
        cs.background[i] = s.background[i];
    }
    cs.view = s.view;
    cs.accumulated = v.accumulated;
    cs.exposure = s.exposure;
    cs.debug_length = effective_ao_radius(v);
    cs.offset = (s.offset > 0.0f ? s.offset : ROMA_DEFAULT_OFFSET_CELLS) * mi.trace_cell;
    cs.ao_on = want_ao;
    cs.direct_on = want_direct;
    cs.gi_on = want_gi;
    for (int i = 0; i < 4; ++i)
        cs.bom_origin[i] = v.bom_origin[i];
    cs.slice_axis = s.slice_axis;
    cs.slice_depth = std::min(s.slice_depth, v.bom_res ? v.bom_res - 1 : 0u);
    cs.bom_res = v.bom_res;
    cs.compared = v.compared;
    // History (libroma's temporal effect): start over after a change of scene, settings or
    // size; reproject after the camera moved (at most 16 frames kept, so old light does not
    // trail); else keep adding.
    cs.parity = slot;
    cs.frame = v.frame;
    cs.history_mode = v.accumulated == 0 ? 0u : v.camera_moved ? 2u : 1u;
    cs.history_cap = v.camera_moved ? 16u : 1u << 30;
    std::memcpy(cs.prev_clip_rows, v.prev_clip_rows, sizeof cs.prev_clip_rows);
    // The steps view: the scene's first punctual light, the light effect's skip and steps.
    for (uint32_t i = 0; i < v.view.light_count && cs.steps_light[3] == 0.0f; ++i) {
        const roma_light &l = v.view.lights[i];
        bool sun = l.type == ROMA_LIGHT_DIRECTIONAL;
        for (int k = 0; k < 3; ++k)
            cs.steps_light[k] = sun ? l.direction[k] : l.position[k];
        cs.steps_light[3] = sun ? 2.0f : 1.0f;
    }
    cs.steps_tmin = (s.shadow_skip > 0.0f ? s.shadow_skip : ROMA_DEFAULT_SHADOW_SKIP_CELLS) * mi.trace_cell;
    cs.steps_max = s.max_steps;
    cs.map_index = std::min(s.map_index, s.angular * s.angular - 1);
    // Capped at the AO radius, as the AO effect caps it: a ray never skips past its end.
    cs.ao_skip = std::min((s.ao_skip > 0.0f ? s.ao_skip : ROMA_DEFAULT_AO_SKIP_CELLS) * mi.trace_cell,
                          effective_ao_radius(v));
    cs.bom_address = mi.bom_address;
    // The temporal effect's spatial filter (it runs where the history is short: a moving
    // camera's disocclusions, the first frames after a change); not asked for while a still
    // camera has 4 frames everywhere (nothing to filter; its passes would still cost); only for
    // the views of light, not the debug views, whose values are labels.
    cs.filter = v.s.filter && (cs.history_mode == 2u || v.accumulated + 1 < ROMA_DEFAULT_FILTER_BELOW) &&
                (shown == VIEW_COMPOSED || shown == VIEW_DIRECT || shown == VIEW_AO || shown == VIEW_GI) &&
                s.view != VIEW_REFERENCE && s.view != VIEW_DIFFERENCE;
    if (!compose_pass_record(v.base, v.cp, cmd, cs, mi.trace_set, v.temporal, v.gb))
        return false;
    v.passes.push_back("compose");
    roma_context_info ci;
    if (roma_context_get_info(v.ctx, &ci) == ROMA_SUCCESS)
        v.info.device_memory = ci.device_memory_in_use;
    std::memcpy(v.prev_clip_rows, draw.clip_rows, sizeof v.prev_clip_rows);
    v.camera_moved = false;
    v.info.grid_cell = mi.grid_cell;
    stamp(v, cmd, slot, 5);
    return true;
}

void read_timings(viewer &v, uint32_t slot)
{
    uint64_t t[kStamps];
    VkResult r = vkGetQueryPoolResults(v.base.device, v.queries, slot * kStamps, kStamps, sizeof t, t, sizeof t[0],
                                       VK_QUERY_RESULT_64_BIT);
    v.timings.gpu = r == VK_SUCCESS;
    if (!v.timings.gpu)
        return;
    auto ms = [&](int a, int b) { return double(t[b] - t[a]) * v.timestamp_ns * 1e-6; };
    v.timings.animate_ms = ms(0, 1);
    v.timings.build_ms = ms(1, 2);
    v.timings.gbuffer_ms = ms(2, 3);
    v.timings.effects_ms = ms(3, 4);
    v.timings.compose_ms = ms(4, 5);
}

// --- pictures ---------------------------------------------------------------------------------

struct readback {
    const viewer *v;
    VkBuffer display, accum;
};

void record_readback(VkCommandBuffer cmd, void *user)
{
    const readback *r = static_cast<const readback *>(user);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {r->v->cp.width, r->v->cp.height, 1};
    vkCmdCopyImageToBuffer(cmd, r->v->cp.display.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, r->display, 1, &region);
    // What the picture shows: the filtered values when the filter ran, else the accumulation.
    const vk_image &shown = compose_pass_picture(r->v->cp);
    vkCmdCopyImageToBuffer(cmd, shown.image, VK_IMAGE_LAYOUT_GENERAL, r->accum, 1, &region);
    VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    mb.srcStageMask = VK_PIPELINE_STAGE_2_TRANSFER_BIT;
    mb.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    mb.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
    mb.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &mb;
    vkCmdPipelineBarrier2(cmd, &dep);
}

// The last frame's pictures in host memory: the displayed RGBA8 and the accumulated RGBA32F
// (blocking: waits for the device). Empty buffers on failure.
struct pictures {
    const viewer &v;
    vk_buffer display, accum;
    bool ok = false;
    explicit pictures(viewer &viewer_) : v(viewer_)
    {
        vkDeviceWaitIdle(v.base.device);
        VkDeviceSize n = VkDeviceSize(v.cp.width) * v.cp.height;
        ok = vk_buffer_create(v.base, n * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, display) &&
             vk_buffer_create(v.base, n * 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, accum);
        readback r{&v, display.buffer, accum.buffer};
        ok = ok && vk_submit_now(v.base, v.pool, record_readback, &r);
    }
    ~pictures()
    {
        vk_buffer_destroy(v.base, display);
        vk_buffer_destroy(v.base, accum);
    }
    const float *linear() const { return static_cast<const float *>(accum.mapped); }
    const unsigned char *shown() const { return static_cast<const unsigned char *>(display.mapped); }
};

// MAE of the accumulated compared view against the reference, over the pixels the
// reference saw geometry in (its coverage), as roma-compare --mask computes it.
bool measure_mae(viewer &v, double &mae, uint64_t &pixels, std::string &why_not)
{
    if (!v.info.reference_ready || v.coverage.width != v.cp.width || v.coverage.height != v.cp.height) {
        why_not = "the reference does not match this view's size";
        return false;
    }
    // The accumulation holds what is shown: it must be the quantity the reference has.
    view_mode shown = (v.s.view == VIEW_REFERENCE || v.s.view == VIEW_DIFFERENCE) ? v.compared : v.s.view;
    if (shown != v.compared) {
        why_not = std::string("the picture shows another quantity than the reference (") +
                  (v.compared == VIEW_AO ? "AO" : "direct light") + "): switch to its view first";
        return false;
    }
    uint32_t w = v.cp.width, h = v.cp.height;
    pictures pics(v);
    bool ok = pics.ok;
    double sum = 0.0;
    pixels = 0;
    uint32_t channels = v.compared == VIEW_AO ? 1 : 3;
    if (ok) {
        const float *a = pics.linear();
        const float *ref = static_cast<const float *>(v.reference.mapped);
        for (size_t i = 0; i < size_t(w) * h; ++i) {
            if (!(v.coverage.pixels[i * v.coverage.channels] > 0.0f))
                continue;
            for (uint32_t c = 0; c < channels; ++c)
                sum += std::fabs(double(a[4 * i + c]) - double(ref[4 * i + c]));
            ++pixels;
        }
    }
    mae = pixels ? sum / double(pixels * channels) : 0.0;
    return ok && pixels > 0;
}

// Headless bom-slice view: how many pixels of the layer show occupied (red) and empty
// (blue) cells. Every surface point lies in a cell the voxelization marked, so blue
// pixels are cells the voxelization missed, or points on a cell boundary.
void report_slice(viewer &v)
{
    uint32_t w = v.cp.width, h = v.cp.height;
    pictures pics(v);
    uint64_t occupied = 0, empty = 0;
    if (pics.ok) {
        const float *a = pics.linear();
        for (size_t i = 0; i < size_t(w) * h; ++i) {
            occupied += a[4 * i] > 0.85f && a[4 * i + 1] < 0.2f;
            empty += a[4 * i + 2] > 0.85f && a[4 * i] < 0.2f;
        }
    }
    std::printf("roma-viewer: occupancy slice %c = %u (RES %u): %llu pixels on occupied cells, %llu on empty cells\n",
                char('x' + v.s.slice_axis), v.s.slice_depth, v.bom_res, (unsigned long long)occupied,
                (unsigned long long)empty);
}

// The last frame's picture (8-bit PNG) and its accumulated linear values (PFM or EXR by
// the name's ending; AO and debug views: the value itself; composed and direct: radiance).
bool save_pictures(viewer &v, const std::string &png, const std::string &linear)
{
    uint32_t w = v.cp.width, h = v.cp.height;
    pictures pics(v);
    bool ok = pics.ok;
    if (ok && !png.empty()) {
        std::vector<unsigned char> rgb(size_t(w) * h * 3);
        const unsigned char *src = pics.shown();
        for (size_t i = 0; i < size_t(w) * h; ++i)
            for (int c = 0; c < 3; ++c)
                rgb[3 * i + c] = src[4 * i + c];
        ok = stbi_write_png(png.c_str(), int(w), int(h), 3, rgb.data(), int(w) * 3) != 0;
        if (!ok)
            std::fprintf(stderr, "roma-viewer: cannot write %s\n", png.c_str());
        else
            std::printf("wrote %s\n", png.c_str());
    }
    if (ok && !linear.empty()) {
        bool one_channel = v.s.view == VIEW_AO;
        roma_image img{};
        ok = roma_image_alloc(&img, w, h, one_channel ? 1 : 3) == ROMA_SUCCESS;
        const float *src = pics.linear();
        for (size_t i = 0; ok && i < size_t(w) * h; ++i)
            for (uint32_t c = 0; c < img.channels; ++c)
                img.pixels[i * img.channels + c] = src[4 * i + c];
        bool exr = linear.size() > 4 && linear.compare(linear.size() - 4, 4, ".exr") == 0;
        roma_result rr = !ok ? ROMA_ERROR_OUT_OF_HOST_MEMORY
                         : exr ? roma_app_write_exr(&img, linear.c_str())
                               : roma_image_write_pfm(&img, linear.c_str());
        roma_image_free(&img);
        ok = rr == ROMA_SUCCESS;
        if (!ok)
            std::fprintf(stderr, "roma-viewer: cannot write %s: %s\n", linear.c_str(), roma_result_string(rr));
        else
            std::printf("wrote %s (%u frames accumulated)\n", linear.c_str(), v.accumulated);
    }
    return ok;
}

// --- the window -----------------------------------------------------------------------------

void check_vk(VkResult r)
{
    if (r < 0)
        std::fprintf(stderr, "roma-viewer: the interface's Vulkan call failed (%d)\n", int(r));
}

struct font_upload {
    static void record(VkCommandBuffer cmd, void *) { ImGui_ImplVulkan_CreateFontsTexture(cmd); }
};

bool init_imgui(viewer &v)
{
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16};
    VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pi.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    pi.maxSets = 16;
    pi.poolSizeCount = 1;
    pi.pPoolSizes = &size;
    if (vkCreateDescriptorPool(v.base.device, &pi, nullptr, &v.imgui_pool) != VK_SUCCESS)
        return false;
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr; // no imgui.ini beside the user's files
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForVulkan(v.window, true);
    ImGui_ImplVulkan_InitInfo ii{};
    ii.Instance = v.base.instance;
    ii.PhysicalDevice = v.base.physical;
    ii.Device = v.base.device;
    ii.QueueFamily = v.base.family;
    ii.Queue = v.base.queue;
    ii.DescriptorPool = v.imgui_pool;
    ii.MinImageCount = v.sc.min_image_count;
    ii.ImageCount = static_cast<uint32_t>(v.sc.images.size());
    ii.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    ii.CheckVkResultFn = check_vk;
    if (!ImGui_ImplVulkan_Init(&ii, v.sc.ui_pass))
        return false;
    v.imgui = true;
    bool ok = vk_submit_now(v.base, v.pool, font_upload::record, nullptr);
    ImGui_ImplVulkan_DestroyFontUploadObjects();
    return ok;
}

struct input_state {
    double x = 0, y = 0;
    bool have = false;
    float wheel = 0;
    std::vector<std::string> dropped;
    bool down[3] = {}; // Tab, F, F12 last frame
};

// True on the frame a key goes down (Tab, F, F12).
bool pressed(GLFWwindow *w, input_state &in, int which)
{
    static const int keys[3] = {GLFW_KEY_TAB, GLFW_KEY_F, GLFW_KEY_F12};
    bool now = glfwGetKey(w, keys[which]) == GLFW_PRESS;
    bool edge = now && !in.down[which];
    in.down[which] = now;
    return edge;
}

void on_scroll(GLFWwindow *w, double dx, double dy)
{
    ImGui_ImplGlfw_ScrollCallback(w, dx, dy);
    if (!ImGui::GetIO().WantCaptureMouse)
        static_cast<input_state *>(glfwGetWindowUserPointer(w))->wheel += float(dy);
}

void on_drop(GLFWwindow *w, int count, const char **paths)
{
    auto *in = static_cast<input_state *>(glfwGetWindowUserPointer(w));
    for (int i = 0; i < count; ++i)
        in->dropped.push_back(paths[i]);
}

// Mouse and keys to the camera; true when it moved.
bool handle_input(viewer &v, input_state &in, float dt)
{
    bool moved = false;
    double x, y;
    glfwGetCursorPos(v.window, &x, &y);
    ImGuiIO &io = ImGui::GetIO();
    if (in.have && !io.WantCaptureMouse) {
        float dx = float(x - in.x), dy = float(y - in.y);
        if (glfwGetMouseButton(v.window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS)
            moved |= camera_control_rotate(v.cam, dx, dy);
        else if (glfwGetMouseButton(v.window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
                 glfwGetMouseButton(v.window, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS)
            moved |= camera_control_pan(v.cam, dx, dy, float(v.gb.height));
    }
    in.x = x, in.y = y, in.have = true;
    moved |= camera_control_zoom(v.cam, in.wheel);
    in.wheel = 0;
    if (!io.WantCaptureKeyboard) {
        if (pressed(v.window, in, 0))
            v.cam.fly = !v.cam.fly;
        if (pressed(v.window, in, 1)) {
            frame_scene(v);
            moved = true;
        }
        if (v.cam.fly) {
            float move[3] = {0, 0, 0};
            auto key = [&](int k) { return glfwGetKey(v.window, k) == GLFW_PRESS ? 1.0f : 0.0f; };
            move[0] = key(GLFW_KEY_D) - key(GLFW_KEY_A);
            move[1] = key(GLFW_KEY_E) - key(GLFW_KEY_Q);
            move[2] = key(GLFW_KEY_W) - key(GLFW_KEY_S);
            moved |= camera_control_move(v.cam, move, dt);
        }
    }
    return moved;
}

std::string next_screenshot_name(viewer &v)
{
    char name[64];
    std::snprintf(name, sizeof name, "roma-viewer-%u.png", v.screenshots++);
    return name;
}

// One frame's share of the script: the drag in progress, or the steps up to the next wait.
// Sets moved when the camera moved; act gets the interface's actions (toggles, screenshot).
void run_script(viewer &v, script &sc, input_state &in, ui_actions &act, bool &moved)
{
    if (sc.drag_frames > 0) {
        float dx = sc.drag_dx / float(sc.drag_frames), dy = sc.drag_dy / float(sc.drag_frames);
        moved |= sc.drag_button == 0 ? camera_control_rotate(v.cam, dx, dy)
                                     : camera_control_pan(v.cam, dx, dy, float(v.gb.height));
        sc.drag_dx -= dx, sc.drag_dy -= dy, --sc.drag_frames;
        return;
    }
    if (sc.wait > 0) {
        --sc.wait;
        return;
    }
    while (sc.next < sc.steps.size()) {
        const script_step &st = sc.steps[sc.next++];
        auto arg = [&](size_t i) { return i < st.args.size() ? st.args[i] : std::string(); };
        auto number = [&](size_t i) { return std::atof(arg(i).c_str()); };
        std::printf("roma-viewer: script line %d: %s\n", st.line, st.verb.c_str());
        if (st.verb == "wait") {
            sc.wait = uint32_t(std::max(0.0, number(0)));
            return;
        } else if (st.verb == "key") {
            if (arg(0) == "F") {
                frame_scene(v);
                moved = true;
            } else if (arg(0) == "TAB") {
                v.cam.fly = !v.cam.fly;
            } else if (arg(0) == "F12") {
                act.screenshot = true;
            }
        } else if (st.verb == "drag") {
            sc.drag_button = arg(0) == "right" ? 1 : 0;
            sc.drag_dx = float(number(1)), sc.drag_dy = float(number(2));
            sc.drag_frames = uint32_t(std::max(1.0, number(3)));
            return;
        } else if (st.verb == "wheel") {
            moved |= camera_control_zoom(v.cam, float(number(0)));
        } else if (st.verb == "set") {
            bool on = arg(1) == "on";
            bool *flag = arg(0) == "ao" ? &v.s.ao_on : arg(0) == "direct" ? &v.s.direct_on : arg(0) == "gi" ? &v.s.gi_on
                         : arg(0) == "accumulate" ? &v.s.accumulate : arg(0) == "filter" ? &v.s.filter : nullptr;
            if (flag)
                *flag = on, act.reset_accumulation = true;
        } else if (st.verb == "view") {
            for (uint32_t k = 0; k < VIEW_COUNT; ++k)
                if (arg(0) == kViewNames[k])
                    v.s.view = view_mode(k), act.reset_accumulation = true;
        } else if (st.verb == "res" || st.verb == "angular") {
            // The command line's ranges: RES a power of two in [32, 256], A in [1, 16].
            uint32_t n = 0;
            bool res = st.verb == "res";
            bool valid = res ? parse_u32(arg(0).c_str(), 32, 256, n) && (n & (n - 1)) == 0
                             : parse_u32(arg(0).c_str(), 1, 16, n);
            if (valid) {
                (res ? v.s.res : v.s.angular) = n;
                act.rebuild_map = act.reset_accumulation = true;
            } else {
                std::fprintf(stderr, "roma-viewer: script line %d: %s %s is out of range (ignored)\n", st.line,
                             st.verb.c_str(), arg(0).c_str());
            }
        } else if (st.verb == "camera") {
            act.scene_camera = int(number(0));
        } else if (st.verb == "resize") {
            glfwSetWindowSize(v.window, std::max(1, int(number(0))), std::max(1, int(number(1))));
        } else if (st.verb == "minimize") {
            glfwIconifyWindow(v.window);
        } else if (st.verb == "restore") {
            glfwRestoreWindow(v.window);
        } else if (st.verb == "drop") {
            in.dropped.push_back(arg(0));
        } else if (st.verb == "reference") {
            act.start_reference = true; // as the interface's button: the current view's reference
        } else if (st.verb == "screenshot") {
            // After this frame is recorded and submitted, as F12: the steps before it have taken effect.
            act.screenshot = true;
            act.screenshot_path = arg(0);
        } else if (st.verb == "quit") {
            glfwSetWindowShouldClose(v.window, GLFW_TRUE);
            return;
        }
    }
}

// The slot's previous frame is done (its timings read) before its objects are reused.
void wait_for_slot(viewer &v, uint32_t slot)
{
    if (v.submitted[slot]) {
        vkWaitForFences(v.base.device, 1, &v.fence[slot], VK_TRUE, UINT64_MAX);
        read_timings(v, slot);
    }
}

// The slot's command buffer, begun, its fence reset (after the slot was waited for).
VkCommandBuffer begin_slot_commands(viewer &v, uint32_t slot)
{
    vkResetFences(v.base.device, 1, &v.fence[slot]);
    VkCommandBuffer cmd = v.cmd[slot];
    vkResetCommandBuffer(cmd, 0);
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkBeginCommandBuffer(cmd, &bi);
    return cmd;
}

// What a script asked for while no frame was drawn (a minimised window), into this frame's actions.
void merge_actions(ui_actions &into, const ui_actions &from)
{
    into.reset_accumulation |= from.reset_accumulation;
    into.rebuild_map |= from.rebuild_map;
    into.frame_scene |= from.frame_scene;
    into.capture_bom |= from.capture_bom;
    into.start_reference |= from.start_reference;
    into.measure |= from.measure;
    if (from.screenshot) {
        into.screenshot = true;
        into.screenshot_path = from.screenshot_path;
    }
    if (from.camera_pasted) {
        into.camera_pasted = true;
        std::memcpy(into.camera_text, from.camera_text, sizeof into.camera_text);
    }
    if (from.scene_camera >= 0)
        into.scene_camera = from.scene_camera;
}

int run_window(viewer &v)
{
    script sc;
    if (!v.opt.script.empty() && !script_load(v.opt.script.c_str(), sc))
        return 2;
    bool scripted = !sc.steps.empty();
    input_state in;
    glfwSetWindowUserPointer(v.window, &in);
    glfwSetScrollCallback(v.window, on_scroll);
    glfwSetDropCallback(v.window, on_drop);
    bool resize = false;
    auto previous = std::chrono::steady_clock::now();
    uint32_t frames_left = v.opt.frames;
    uint32_t swapchain_failures = 0;
    int status = 0;
    ui_actions pending; // a script's actions while minimised, for the next frame drawn
    bool pending_moved = false;
    while (!glfwWindowShouldClose(v.window)) {
        glfwPollEvents();
        int fw = 0, fh = 0;
        glfwGetFramebufferSize(v.window, &fw, &fh);
        if (fw == 0 || fh == 0) { // minimised: wait, render nothing (a script goes on)
            if (scripted) {
                run_script(v, sc, in, pending, pending_moved);
                glfwWaitEventsTimeout(0.02);
            } else {
                glfwWaitEvents();
            }
            continue;
        }
        if (resize || uint32_t(fw) != v.sc.extent.width || uint32_t(fh) != v.sc.extent.height) {
            vkDeviceWaitIdle(v.base.device);
            if (!swapchain_create(v.base, v.sc, uint32_t(fw), uint32_t(fh))) {
                if (++swapchain_failures > 200) { // not a minimised window: give up with a message
                    std::fprintf(stderr, "roma-viewer: cannot make a %dx%d swapchain\n", fw, fh);
                    return 1;
                }
                glfwWaitEventsTimeout(0.02);
                continue;
            }
            swapchain_failures = 0;
            ImGui_ImplVulkan_SetMinImageCount(v.sc.min_image_count);
            // A swapchain made anew at the same size (suboptimal, say) keeps the pictures and history.
            if ((v.sc.extent.width != v.gb.width || v.sc.extent.height != v.gb.height) &&
                !resize_images(v, v.sc.extent.width, v.sc.extent.height))
                return 1;
            resize = false;
        }
        for (const std::string &path : in.dropped) {
            vkDeviceWaitIdle(v.base.device);
            if (open_scene(v, path, true))
                v.accumulated = 0;
            else
                ++v.scene_failures; // the message is out; the previous scene stays
        }
        in.dropped.clear();
        if (!v.map) { // a dropped file loaded but its GPU objects could not be made
            status = 1;
            break;
        }
        auto now = std::chrono::steady_clock::now();
        float dt = std::chrono::duration<float>(now - previous).count();
        previous = now;
        v.timings.frame_ms = dt * 1000.0;
        v.timings.history.push_back(float(v.timings.frame_ms));
        if (v.timings.history.size() > kHistory)
            v.timings.history.erase(v.timings.history.begin());

        ImGui_ImplVulkan_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        ui_actions act;
        v.info.camera_string = camera_to_string(camera_control_get(v.cam));
        v.info.accumulated = v.accumulated;
        v.info.validation_messages = v.base.validation_messages;
        ui_draw(v.s, v.timings, v.info, act);
        bool moved = handle_input(v, in, dt) || pending_moved;
        merge_actions(act, pending);
        pending = ui_actions{};
        pending_moved = false;
        if (scripted)
            run_script(v, sc, in, act, moved);
        if (act.camera_pasted) {
            roma_camera c;
            if (camera_from_string(act.camera_text, c)) {
                camera_control_set(v.cam, c);
                moved = true;
            }
        }
        if (act.scene_camera >= 0) {
            if (uint32_t(act.scene_camera) < v.view.camera_count) {
                camera_control_set(v.cam, v.view.cameras[act.scene_camera]);
                moved = true;
            } else {
                std::fprintf(stderr, "roma-viewer: the scene has no camera %d (it has %u)\n", act.scene_camera,
                             v.view.camera_count);
            }
        }
        if (act.frame_scene) {
            frame_scene(v);
            moved = true;
        }
        if (act.capture_bom)
            capture_bom(v);
        if (act.start_reference)
            start_reference(v);
        finish_reference(v);
        v.info.reference_running = v.job.running;
        v.info.reference_percent = v.job.percent;
        if (act.measure) {
            double mae;
            uint64_t pixels;
            std::string why_not;
            if (measure_mae(v, mae, pixels, why_not)) {
                char line[256];
                std::snprintf(line, sizeof line, "%s MAE %.4f over %llu covered pixels, %u frames accumulated",
                              v.compared == VIEW_AO ? "AO" : "direct light", mae, (unsigned long long)pixels,
                              v.accumulated);
                v.info.reference_status = line;
            } else {
                v.info.reference_status = "no measurement: " + why_not;
            }
        }
        // The cascade levels the settings now call for (chosen for the AO radius, which may have
        // changed): a new map for another count, the finest edge for the next build.
        float finest = 0.0f;
        if (wanted_levels(v, finest) != v.info.levels)
            act.rebuild_map = act.reset_accumulation = true;
        else if (finest != v.info.finest_extent)
            v.info.finest_extent = finest, act.reset_accumulation = true;
        if (act.rebuild_map) {
            vkDeviceWaitIdle(v.base.device);
            if (!create_map(v))
                return 1;
        }
        bool scene_changed = false;
        follow_clip(v);
        if (v.s.animated && v.s.playing && v.s.duration > 0.0f) {
            v.s.time = std::fmod(v.s.time + dt * v.s.speed, v.s.duration);
            scene_changed = true;
        }
        if (scene_changed || act.reset_accumulation || !v.s.accumulate)
            v.accumulated = 0;
        else if (moved)
            v.camera_moved = true; // the history follows the surfaces
        ImGui::Render();

        uint32_t slot = v.frame % kSlots;
        wait_for_slot(v, slot);
        uint32_t image = 0;
        VkResult ar = vkAcquireNextImageKHR(v.base.device, v.sc.handle, UINT64_MAX, v.acquired[slot], VK_NULL_HANDLE,
                                            &image);
        if (ar == VK_ERROR_OUT_OF_DATE_KHR) {
            resize = true;
            continue;
        }
        if (ar < 0) {
            std::fprintf(stderr, "roma-viewer: vkAcquireNextImageKHR failed (%d)\n", int(ar));
            status = 1;
            break;
        }
        VkCommandBuffer cmd = begin_slot_commands(v, slot);
        if (!record_frame(v, slot, cmd)) {
            std::fprintf(stderr, "roma-viewer: recording frame %u failed\n", v.frame);
            vkEndCommandBuffer(cmd);
            status = 1;
            break;
        }
        // The picture into the swapchain image, the interface over it.
        VkImage target = v.sc.images[image];
        vk_image_barrier(cmd, target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                         VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, 0, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                         VK_ACCESS_2_TRANSFER_WRITE_BIT);
        VkImageBlit blit{};
        blit.srcSubresource = blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        blit.srcOffsets[1] = {int32_t(v.cp.width), int32_t(v.cp.height), 1};
        blit.dstOffsets[1] = {int32_t(v.sc.extent.width), int32_t(v.sc.extent.height), 1};
        vkCmdBlitImage(cmd, v.cp.display.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
        VkRenderPassBeginInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
        rp.renderPass = v.sc.ui_pass;
        rp.framebuffer = v.sc.framebuffers[image];
        rp.renderArea = {{0, 0}, v.sc.extent};
        vkCmdBeginRenderPass(cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
        ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
        vkCmdEndRenderPass(cmd);
        vkEndCommandBuffer(cmd);
        // Only the swapchain image's first use waits for it (its barrier's source stage): the
        // frame's other work, transfers of the map build among them, runs before it is acquired.
        VkPipelineStageFlags wait_stage = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
        VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        si.waitSemaphoreCount = 1;
        si.pWaitSemaphores = &v.acquired[slot];
        si.pWaitDstStageMask = &wait_stage;
        si.commandBufferCount = 1;
        si.pCommandBuffers = &cmd;
        si.signalSemaphoreCount = 1;
        si.pSignalSemaphores = &v.sc.rendered[image];
        if (vkQueueSubmit(v.base.queue, 1, &si, v.fence[slot]) != VK_SUCCESS) {
            std::fprintf(stderr, "roma-viewer: vkQueueSubmit failed\n");
            status = 1;
            break;
        }
        v.submitted[slot] = true;
        VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
        pi.waitSemaphoreCount = 1;
        pi.pWaitSemaphores = &v.sc.rendered[image];
        pi.swapchainCount = 1;
        pi.pSwapchains = &v.sc.handle;
        pi.pImageIndices = &image;
        VkResult pr = vkQueuePresentKHR(v.base.queue, &pi);
        if (pr == VK_ERROR_OUT_OF_DATE_KHR || pr == VK_SUBOPTIMAL_KHR)
            resize = true;
        ++v.frame;
        ++v.accumulated;
        if (act.screenshot || (!ImGui::GetIO().WantCaptureKeyboard && pressed(v.window, in, 2)))
            save_pictures(v, act.screenshot_path.empty() ? next_screenshot_name(v) : act.screenshot_path, "");
        if (glfwGetKey(v.window, GLFW_KEY_ESCAPE) == GLFW_PRESS)
            glfwSetWindowShouldClose(v.window, GLFW_TRUE);
        if (frames_left && --frames_left == 0)
            break;
    }
    vkDeviceWaitIdle(v.base.device);
    if (status == 0 && (!v.opt.screenshot.empty() || !v.opt.linear.empty()) &&
        !save_pictures(v, v.opt.screenshot, v.opt.linear))
        status = 1;
    return status;
}

// --- headless -------------------------------------------------------------------------------

int run_headless(viewer &v)
{
    if (!resize_images(v, v.opt.width, v.opt.height))
        return 1;
    // Frames per second over all frames but the first (which compiles nothing, but fills caches).
    auto first_done = std::chrono::steady_clock::now();
    for (uint32_t f = 0; f < v.opt.frames; ++f) {
        if (f == 1) {
            vkDeviceWaitIdle(v.base.device);
            first_done = std::chrono::steady_clock::now();
        }
        uint32_t slot = v.frame % kSlots;
        wait_for_slot(v, slot);
        VkCommandBuffer cmd = begin_slot_commands(v, slot);
        bool ok = record_frame(v, slot, cmd);
        vkEndCommandBuffer(cmd);
        VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        si.commandBufferCount = 1;
        si.pCommandBuffers = &cmd;
        if (!ok || vkQueueSubmit(v.base.queue, 1, &si, v.fence[slot]) != VK_SUCCESS) {
            std::fprintf(stderr, "roma-viewer: frame %u failed\n", v.frame);
            vkDeviceWaitIdle(v.base.device);
            return 1;
        }
        v.submitted[slot] = true;
        ++v.frame;
        ++v.accumulated;
        if (v.s.animated && v.s.playing && v.s.duration > 0.0f) {
            v.s.time = std::fmod(v.s.time + 1.0f / 30.0f * v.s.speed, v.s.duration);
            v.accumulated = 0;
        }
        if (f == 0 && v.s.view == VIEW_BOM_SLICE && !capture_bom(v))
            return 1;
    }
    vkDeviceWaitIdle(v.base.device);
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - first_done).count();
    read_timings(v, (v.frame + kSlots - 1) % kSlots);
    std::printf("roma-viewer: %u frames of %s at %ux%u on %s; last frame: build %.2f, G-buffer %.2f, effects "
                "%.2f, compose %.2f ms (%s)\n",
                v.frame, v.info.scene_name.c_str(), v.gb.width, v.gb.height, v.info.device.c_str(),
                v.timings.build_ms, v.timings.gbuffer_ms, v.timings.effects_ms, v.timings.compose_ms,
                v.timings.clock.c_str());
    if (v.frame > 1)
        std::printf("roma-viewer: %.1f frames per second (host-observed, frames 2 to %u, two in flight)\n",
                    double(v.frame - 1) / seconds, v.frame);
    if ((!v.opt.screenshot.empty() || !v.opt.linear.empty()) && !save_pictures(v, v.opt.screenshot, v.opt.linear))
        return 1;
    if (v.s.view == VIEW_BOM_SLICE)
        report_slice(v);
    if (v.opt.compare_reference) {
        start_reference(v);
        reference_job_join(v.job);
        finish_reference(v);
        double mae;
        uint64_t pixels;
        std::string why_not;
        if (!measure_mae(v, mae, pixels, why_not)) {
            std::fprintf(stderr, "roma-viewer: no comparison with the reference: %s\n",
                         v.info.reference_ready ? why_not.c_str() : v.info.reference_status.c_str());
            return 1;
        }
        std::printf("roma-viewer: %s against the Embree reference (%u samples per pixel): MAE %.4f over %llu "
                    "covered pixels, %u frames accumulated\n",
                    v.compared == VIEW_AO ? "AO" : "direct light", v.s.reference_spp, mae,
                    (unsigned long long)pixels, v.accumulated);
    }
    return 0;
}

// --stats: what a script or a person needs to check a run.
bool write_stats(const viewer &v, int status)
{
    FILE *f = std::fopen(v.opt.stats.c_str(), "w");
    if (!f) {
        std::fprintf(stderr, "roma-viewer: cannot write %s: %s\n", v.opt.stats.c_str(), std::strerror(errno));
        return false;
    }
    roma_json j{};
    j.f = f;
    roma_json_begin_object(&j, nullptr);
    roma_json_string(&j, "tool", "roma-viewer");
    roma_json_string(&j, "device", v.info.device.c_str());
    roma_json_string(&j, "scene", v.info.scene_name.c_str());
    roma_json_int(&j, "frames", v.frame);
    roma_json_int(&j, "width", v.gb.width);
    roma_json_int(&j, "height", v.gb.height);
    roma_json_string(&j, "view", kViewNames[v.s.view]);
    roma_json_string(&j, "camera", camera_to_string(camera_control_get(v.cam)).c_str());
    roma_json_int(&j, "accumulated", v.accumulated);
    roma_map_info mi{}; // the map's own RES and A: what the last build used
    if (v.map)
        roma_map_get_info(v.map, &mi);
    roma_json_int(&j, "resolution", mi.resolution);
    roma_json_int(&j, "angular", mi.angular);
    roma_json_int(&j, "levels", mi.levels);
    roma_json_number(&j, "sky", v.s.ambient);
    roma_json_begin_array(&j, "passes"); // of the last recorded frame
    for (const std::string &p : v.passes)
        roma_json_string(&j, nullptr, p.c_str());
    roma_json_end_array(&j);
    roma_json_begin_object(&j, "last_frame_ms");
    roma_json_string(&j, "clock", v.timings.clock.c_str());
    roma_json_number(&j, "animate", v.timings.animate_ms);
    roma_json_number(&j, "build", v.timings.build_ms);
    roma_json_number(&j, "gbuffer", v.timings.gbuffer_ms);
    roma_json_number(&j, "effects", v.timings.effects_ms);
    roma_json_number(&j, "compose", v.timings.compose_ms);
    roma_json_end_object(&j);
    roma_json_int(&j, "scene_failures", v.scene_failures);
    roma_json_int(&j, "validation_messages", v.base.validation_messages);
    roma_json_int(&j, "libroma_device_memory_bytes", (long long)v.info.device_memory);
    roma_json_int(&j, "exit_status", status);
    roma_json_end_object(&j);
    std::fputc('\n', f);
    bool ok = !std::ferror(f);
    ok = std::fclose(f) == 0 && ok;
    return ok;
}

void destroy(viewer &v)
{
    if (v.base.device)
        vkDeviceWaitIdle(v.base.device);
    if (v.imgui) {
        ImGui_ImplVulkan_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
    if (v.imgui_pool)
        vkDestroyDescriptorPool(v.base.device, v.imgui_pool, nullptr);
    if (v.job.running) { // quitting does not wait for a reference still rendering
        reference_job_cancel(v.job);
        std::printf("roma-viewer: quitting stopped the reference render\n");
    }
    reference_job_cleanup(v.job);
    roma_image_free(&v.coverage);
    vk_buffer_destroy(v.base, v.bom);
    vk_buffer_destroy(v.base, v.reference);
    free_scene(v);
    roma_ao_effect_destroy(v.ao);
    roma_light_effect_destroy(v.light);
    roma_gi_effect_destroy(v.gi);
    roma_temporal_effect_destroy(v.temporal);
    roma_context_destroy(v.ctx);
    gbuffer_pass_destroy(v.base, v.gb);
    compose_pass_destroy(v.base, v.cp);
    if (v.base.device) {
        for (uint32_t i = 0; i < kSlots; ++i) {
            if (v.fence[i])
                vkDestroyFence(v.base.device, v.fence[i], nullptr);
            if (v.acquired[i])
                vkDestroySemaphore(v.base.device, v.acquired[i], nullptr);
        }
        if (v.queries)
            vkDestroyQueryPool(v.base.device, v.queries, nullptr);
        if (v.pool)
            vkDestroyCommandPool(v.base.device, v.pool, nullptr);
        swapchain_destroy(v.base, v.sc);
    }
    vk_base_destroy(v.base);
    if (v.window)
        glfwDestroyWindow(v.window);
}

} // namespace

int main(int argc, char **argv)
{
    viewer v;
    int parsed = parse_args(argc, argv, v.opt);
    if (parsed >= 0)
        return parsed;
    v.s = v.opt.settings;
    if (!v.opt.headless) {
        if (!glfwInit()) {
            std::fprintf(stderr, "roma-viewer: cannot open a window (no display?); --headless renders without one\n");
            return 1;
        }
        glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
        v.window = glfwCreateWindow(int(v.opt.width), int(v.opt.height), "roma-viewer", nullptr, nullptr);
        if (!v.window || !glfwVulkanSupported()) {
            std::fprintf(stderr, "roma-viewer: cannot open a Vulkan window; --headless renders without one\n");
            glfwTerminate();
            return 1;
        }
    }
    int status = 1;
    if (vk_base_create(v.base, v.window, v.opt.validation, v.opt.device.empty() ? nullptr : v.opt.device.c_str()) &&
        create_frame_objects(v) && create_libroma(v) && gbuffer_pass_create(v.base, v.gb) &&
        compose_pass_create(v.base, v.cp) && open_scene(v, v.opt.scene)) {
        v.info.device = v.base.properties.deviceName;
        if (v.opt.has_camera)
            camera_control_set(v.cam, v.opt.camera);
        if (v.opt.headless) {
            status = run_headless(v);
        } else {
            int fw = 0, fh = 0;
            glfwGetFramebufferSize(v.window, &fw, &fh);
            if (swapchain_create(v.base, v.sc, uint32_t(fw), uint32_t(fh)) && init_imgui(v) &&
                resize_images(v, v.sc.extent.width, v.sc.extent.height))
                status = run_window(v);
        }
    }
    if (!v.opt.stats.empty() && !write_stats(v, status))
        status = 1;
    uint32_t messages = v.base.validation_messages;
    destroy(v);
    messages = std::max(messages, v.base.validation_messages);
    if (!v.opt.headless)
        glfwTerminate();
    if (v.opt.validation && messages) {
        std::fprintf(stderr, "roma-viewer: %u validation messages\n", messages);
        return 1;
    }
    return status;
}
