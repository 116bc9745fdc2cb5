// roma-viewer: what the user chooses (command line and interface) and what the
// interface shows (timings, device, scene), shared by the frame loop and the interface.
#pragma once

#include "camera_control.h"
#include "compose_pass.h"

#include <cstdint>
#include <string>
#include <vector>

struct viewer_settings {
    // ROMA array (a change makes a new map: pipelines are shared, so it is quick)
    uint32_t res = 128, angular = 4;
    // Cascade levels around the camera (0: as roma-render chooses: several for a scene much
    // wider than the AO radius, roma_app_auto_cascades) and the finest one's edge (0: 30 cells
    // to the AO radius, roma_app_finest_extent)
    uint32_t cascades = 0;
    float finest_extent = 0.0f;
    // effects
    bool ao_on = true, direct_on = true, gi_on = true;
    uint32_t gi_samples = 1;         // bounce rays per pixel and frame
    uint32_t ao_samples = 4;
    // The effects trace one pixel of each 2x2 or 4x4 block a frame (1: every pixel) and
    // upsample the rest (roma_*_settings.resolution_divisor)
    uint32_t resolution_divisor = 1;
    float ao_radius = 0.0f;          // 0: from the scene size (auto_ao_radius)
    float auto_ao_radius = 1.0f;
    uint32_t max_steps = 8;
    uint32_t area_samples = 4;       // area-light samples per pixel and frame
    uint32_t many_lights = 0;        // synthetic point lights added to the direct light (0: none)
    uint32_t lights_per_frame = 8;   // of them, traced per pixel and frame (the scene's own: all)
    float ao_skip = 0.0f, shadow_skip = 0.0f, offset = 0.0f; // 0 = the library's defaults
    bool ao_surfaces = false;        // AO rays' start checked through the surface grid too
    bool ao_surface_rays = false;    // AO rays walked through the surface grid (ROMA_AO_TRACE_SURFACES)
    // picture
    view_mode view = VIEW_COMPOSED;
    float exposure = 1.2f;           // the built-in room's lights read well at 1.2
    float ambient = 0.2f;            // sky radiance in the composed view (scaled by AO); set per scene
                                     // (1 without lights) unless --sky gives it
    float background[3] = {0.11f, 0.12f, 0.15f};
    bool accumulate = true;          // still camera: average frames
    bool filter = true;              // a-trous filter while there is little history
    // debug
    uint32_t slice_axis = 1, slice_depth = 8; // y = 8: near the floor at RES 128
    uint32_t map_index = 0;          // the rotated-map view's map (of A x A)
    uint32_t reference_spp = 64;
    // animation
    bool animated = false, playing = false;
    uint32_t clip = 0, clip_count = 0;
    float time = 0.0f, duration = 0.0f, speed = 1.0f;
};

// Measured per frame (GPU timestamps where the device writes them; host otherwise).
struct viewer_timings {
    bool gpu = false;                 // timestamps valid
    std::string clock;                // what the stage times are, in words
    double animate_ms = 0, build_ms = 0, gbuffer_ms = 0, effects_ms = 0, compose_ms = 0;
    double frame_ms = 0;              // host: from one frame's start to the next
    std::vector<float> history;       // frame_ms, newest last
};

struct viewer_info {
    std::string device, scene_name, camera_string;
    std::vector<std::string> scene_cameras; // the scene's cameras (a glTF file's), as buttons
    uint32_t vertices = 0, triangles = 0, lights = 0, area_light_triangles = 0;
    uint32_t width = 0, height = 0, accumulated = 0;
    uint64_t map_bytes = 0;
    uint64_t device_memory = 0;       // what libroma's objects hold (roma_context_info)
    float grid_cell = 0;              // the finest level's cell
    uint32_t levels = 1;              // the map's cascade levels
    float finest_extent = 0;          // with several, the finest one's edge (roma_map_frame_desc)
    uint32_t validation_messages = 0;
    std::string plan; // libroma's effect plan for this scene, and what the viewer runs of it
    bool bom_captured = false;
    bool reference_running = false, reference_ready = false;
    int reference_percent = 0;
    std::string reference_status; // what was compared and the last MAE, or the error
};
