// roma-viewer: the effect outputs (AO, direct and indirect irradiance), the picture of the
// chosen view (current), its average over frames (libroma's temporal effect, into history
// images the viewer owns) and the display image; the compute passes that make them.
#pragma once

#include "gbuffer_pass.h"

#include <roma/temporal_effect.h>

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
    VIEW_LEVELS,       // the cascade level that holds each surface point, its cube's faces
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
    // The steps view: the light its shadow rays go to (xyz: position, or direction of travel
    // of a sun's light; w: 0 none, 1 a position, 2 a direction), their skip and most steps.
    float steps_light[4];
    float steps_tmin;
    uint32_t steps_max;
    uint32_t map_index;         // the rotated-map view's map
    float ao_skip;              // the ray-start view: the AO rays' skip (world units)
    uint64_t bom_address;       // and the map's BOM
    uint32_t parity;            // frame % 2: the frame slot, and which history images this frame writes
    uint32_t frame;             // the viewer's frame counter (the temporal effect's slot rules)
    bool filter;                // give the temporal effect its filter (it runs where the history is short)
};

struct compose_pass {
    vk_image ao, light, gi, display;
    vk_image current;                // this frame's view, linear (the temporal effect's input)
    vk_image accum[2], positions[2]; // history, alternating: frame parity k writes [k], reads [1 - k]
    vk_image t[2];                   // the temporal effect's filter: t[0] the filtered picture, t[1] scratch
    vk_buffer frame_data[2];         // the Frame uniform block per parity (host-written)
    bool history_ready[2] = {};      // [k] was written since the images were made
    uint32_t current_accum = 0;      // the accum image the last recorded frame wrote
    bool filtered = false;           // the last recorded frame shows t[0], the filtered picture
    uint32_t width = 0, height = 0;
    VkBool32 corrected_division = VK_TRUE; // roma_context_info.corrected_division (set by the viewer)
    VkSampler sampler = VK_NULL_HANDLE;
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE, trace_layout = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet sets[2][2] = {}; // per parity, and whether the final picture is t[0] (filtered)
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkShaderModule module = VK_NULL_HANDLE, display_module = VK_NULL_HANDLE; // compose.comp, display.comp
    // One per pass (compose, display) and view (a specialization constant), made on first use.
    VkPipeline pipelines[2][VIEW_COUNT] = {};
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
// The picture of one frame: compose, libroma's temporal effect, display. trace_set:
// roma_map_info.trace_set of this frame's map. Leaves the display image in TRANSFER_SRC_OPTIMAL.
bool compose_pass_record(const vk_base &b, compose_pass &c, VkCommandBuffer cmd, const compose_settings &s,
                         VkDescriptorSet trace_set, roma_temporal_effect *temporal, const gbuffer_pass &g);
// The image that holds the last recorded frame's linear picture (filtered or accumulated).
const vk_image &compose_pass_picture(const compose_pass &c);
