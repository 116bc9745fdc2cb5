// roma-viewer: the interface (Dear ImGui): settings, timings, camera string, screenshot.
#pragma once

#include <string>

#include "settings.h"

struct ui_actions {
    bool reset_accumulation = false; // a setting that changes the picture changed
    bool rebuild_map = false;        // RES or A changed
    bool frame_scene = false;
    bool screenshot = false;
    std::string screenshot_path;     // a script's: saved after this frame's submission; empty: numbered
    bool camera_pasted = false;      // camera_text holds a new camera string
    bool capture_bom = false;
    bool start_reference = false;
    bool measure = false;            // MAE of the accumulated view against the reference
    int scene_camera = -1;           // one of the scene's cameras picked (viewer_info.scene_cameras)
    char camera_text[256] = {};
};

void ui_draw(viewer_settings &s, const viewer_timings &t, const viewer_info &info, ui_actions &out);
