// roma-viewer: the command line, kept apart from the viewer's work so that its usage text and its
// checks read as one list.
#include "options.h"

#include <roma/roma.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "app_common.h"

namespace {

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
    "  --resolution-divisor 1|2|4  the effects trace one pixel of each 2x2 or 4x4 block a frame\n"
    "                       and upsample the rest (default 1: every pixel)\n"
    "  --ao-radius R        AO ray length (default: 10% of the scene's diagonal)\n"
    "  --area-samples N     area-light samples per pixel and frame (default 4)\n"
    "  --many-lights N      N synthetic point lights added to the direct light (default 0)\n"
    "  --lights-per-frame K of them, traced per pixel and frame (default 8; the scene's\n"
    "                       own lights are traced every frame)\n"
    "  --max-steps N        texels an un-snapped shadow ray walks (default 8, the paper's)\n"
    "  --ao-skip C --offset C   AO rays' skip and every ray's origin offset, in trace cells\n"
    "                       (default: the library's, 1.6 and 1.5)\n"
    "  --ao-start walk|surfaces  AO rays' skipped start walked through the voxel grid (default),\n"
    "                       and where it meets an occupied cell, through the surface grid's\n"
    "                       triangles (finer geometry, slower)\n"
    "  --ao-trace maps|surfaces  AO rays past their start: one snapped query (default), or\n"
    "                       walked through the surface grid's triangles (close to the\n"
    "                       reference, slower)\n"
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

} // namespace

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
        } else if (a == "--resolution-divisor") {
            ok = parse_u32(v, 1, 4, o.settings.resolution_divisor) && o.settings.resolution_divisor != 3;
        } else if (a == "--ao-start") {
            ok = !std::strcmp(v, "walk") || !std::strcmp(v, "surfaces");
            o.settings.ao_surfaces = !std::strcmp(v, "surfaces");
        } else if (a == "--ao-trace") {
            ok = !std::strcmp(v, "maps") || !std::strcmp(v, "surfaces");
            o.settings.ao_surface_rays = !std::strcmp(v, "surfaces");
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
