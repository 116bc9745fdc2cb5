// roma-viewer: the effect outputs (AO, direct and indirect irradiance), the accumulation image and
// the display image, and the compute pass that turns them into the picture.
#pragma once

#include "gbuffer_pass.h"

enum view_mode : uint32_t {
    VIEW_COMPOSED = 0,
    VIEW_AO,
    VIEW_DIRECT,
    VIEW_ALBEDO,
    VIEW_NORMAL,
    VIEW_MAP,          // which ROMA map a ray along the normal uses
    VIEW_HIT_DISTANCE, // how far that ray goes before a hit
    VIEW_BOM_SLICE,    // a layer of a captured base occupancy map over the scene
    VIEW_REFERENCE,    // the Embree reference of the compared view
    VIEW_DIFFERENCE,   // |ROMA - reference| as a heat map
    VIEW_GI,           // one-bounce indirect light
    VIEW_STEPS,        // texels an un-snapped shadow ray to the first light walks (heat map)
    VIEW_ROTATED_MAP,  // one ray-aligned map seen along its direction
    VIEW_RAY_START,    // the share of AO rays whose start (offset + skip) meets another surface
    VIEW_COUNT
};

struct compose_settings {
    float ambient[3];
    float background[3];
    view_mode view;
    uint32_t accumulated;
    float exposure;
    float debug_length;
    float offset;
    bool ao_on, direct_on, gi_on;
    float bom_origin[4];    // xyz corner of cell (0,0,0), w cell size
    uint32_t slice_axis, slice_depth, bom_res; // bom_res 0: nothing captured
    view_mode compared;     // VIEW_AO or VIEW_DIRECT: what the reference holds
    // History: 0 start over, 1 still camera (each pixel's own), 2 reprojected (a moved camera)
    uint32_t history_mode, history_cap;
    float prev_clip_rows[4][4]; // last frame's world -> clip (mode 2)
    float eye[3];
    float pixel_angle;          // radians a pixel subtends
    // The steps view: the light its shadow rays go to (xyz: position, or direction of travel
    // of a sun's light; w: 0 none, 1 a position, 2 a direction), their skip and most steps.
    float steps_light[4];
    float steps_tmin;
    uint32_t steps_max;
    uint32_t map_index;         // the rotated-map view's map
    float ao_skip;              // the ray-start view: the AO rays' skip (world units)
    uint64_t bom_address;       // and the map's BOM
    uint32_t parity;            // frame % 2: which history images this frame writes
    bool filter;                // run the a-trous filter (a moving camera: little history)
    bool tone;                  // the view's values are radiance (exposure applies)
};

struct compose_pass {
    vk_image ao, light, gi, display;
    vk_image accum[2], positions[2]; // history, alternating: frame parity k writes [k], reads [1 - k]
    vk_buffer frame_data[2];         // the Frame uniform block per parity (host-written)
    bool history_ready[2] = {};      // [k] was written since the images were made
    uint32_t current = 0;            // the accum image the last recorded frame wrote
    bool filtered = false;           // the last recorded frame shows t[0], the filtered picture
    uint32_t width = 0, height = 0;
    VkSampler sampler = VK_NULL_HANDLE;
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE, trace_layout = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet sets[2] = {};    // per parity
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkShaderModule module = VK_NULL_HANDLE;
    VkPipeline pipelines[VIEW_COUNT] = {}; // one per view (specialization constant), made on first use
    // The a-trous filter (atrous.comp): 3 iterations per parity, ping-ponging through t.
    vk_image t[2];                    // t[0] ends with the filtered picture (linear)
    VkDescriptorSetLayout atrous_set_layout = VK_NULL_HANDLE;
    VkDescriptorPool atrous_pool = VK_NULL_HANDLE;
    VkDescriptorSet atrous_sets[2][3] = {};
    VkPipelineLayout atrous_layout = VK_NULL_HANDLE;
    VkPipeline atrous = VK_NULL_HANDLE;
};

bool compose_pass_create(const vk_base &b, compose_pass &c);
// New images at the G-buffer's size (the old ones must be idle); the set is rewritten.
bool compose_pass_resize(const vk_base &b, compose_pass &c, const gbuffer_pass &g);
void compose_pass_destroy(const vk_base &b, compose_pass &c);
// Binds the reference (vec4 per pixel, at least width * height) and the captured BOM
// (RES^3 / 32 words); both must be idle.
void compose_pass_set_buffers(const vk_base &b, compose_pass &c, VkBuffer reference, VkBuffer bom);
// Puts the effect outputs into GENERAL after last frame's readers, ready for the effects.
void compose_pass_prepare(const compose_pass &c, VkCommandBuffer cmd);
// trace_set: roma_map_info.trace_set of this frame's map. Leaves the display image in
// TRANSFER_SRC_OPTIMAL.
bool compose_pass_record(const vk_base &b, compose_pass &c, VkCommandBuffer cmd, const compose_settings &s,
                         VkDescriptorSet trace_set);
