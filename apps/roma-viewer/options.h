// roma-viewer: the command line (what --help lists) into options; the number parsers and the
// view names are shared with --script, which takes the same ranges and names.
#pragma once

#include "settings.h"

#include <roma/camera.h>

#include <cstdint>
#include <string>

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

bool parse_u32(const char *s, uint32_t lo, uint32_t hi, uint32_t &out);
bool parse_float(const char *s, float lo, float hi, float &out);

// --view's names, by view_mode.
extern const char *kViewNames[VIEW_COUNT];

// -1: go on; otherwise the exit status (0 after --help, 2 for a bad command line).
int parse_args(int argc, char **argv, options &o);
