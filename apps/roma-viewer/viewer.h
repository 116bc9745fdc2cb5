// roma-viewer: the viewer's state (one struct every part of it works on) and what its parts,
// one file each, offer the others.
#pragma once

#include <roma/image.h>
#include <roma/roma.h>

#include <cstdint>
#include <string>
#include <vector>

#include "compose_pass.h"
#include "gbuffer_pass.h"
#include "options.h"
#include "reference_job.h"
#include "settings.h"
#include "swapchain.h"

constexpr uint32_t kSlots = 2;      // frames in flight
constexpr uint32_t kStamps = 6;     // timestamps per frame

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
    // On CPU devices the covered pixels listed once a frame for the three effects (what
    // roma_pixel_dispatch's AUTO would make each effect list again); on GPUs none: every pixel.
    roma_pixel_list *pixels = nullptr;
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

// --- scene_setup.cpp: the scene, its map and the objects made once ------------------------

void log_to_stderr(roma_log_level level, roma_result, const char *message, void *);
float effective_ao_radius(const viewer &v);
uint32_t wanted_levels(const viewer &v, float &finest);
bool create_map(viewer &v);
void frame_scene(viewer &v);
bool open_scene(viewer &v, const std::string &name, bool dropped = false);
bool create_frame_objects(viewer &v);
bool create_libroma(viewer &v);
bool resize_images(viewer &v, uint32_t width, uint32_t height);
void destroy(viewer &v);

// --- frame.cpp: one frame's commands ----------------------------------------------------------

bool record_frame(viewer &v, uint32_t slot, VkCommandBuffer cmd);
void read_timings(viewer &v, uint32_t slot);
void wait_for_slot(viewer &v, uint32_t slot);
VkCommandBuffer begin_slot_commands(viewer &v, uint32_t slot);

// --- pictures.cpp: pictures read back, the occupancy map captured, the reference compared -----

bool capture_bom(viewer &v);
void start_reference(viewer &v);
void finish_reference(viewer &v);
bool measure_mae(viewer &v, double &mae, uint64_t &pixels, std::string &why_not);
void report_slice(viewer &v);
bool save_pictures(viewer &v, const std::string &png, const std::string &linear);

// --- window_loop.cpp, headless.cpp, stats.cpp ---------------------------------------------------

bool init_imgui(viewer &v);
int run_window(viewer &v);
int run_headless(viewer &v);
bool write_stats(const viewer &v, int status);
