// roma-viewer: one frame's commands, the same in the window and headless: libroma's passes and
// the viewer's own, between GPU timestamps, in the command buffer of one of the two slots.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <vector>

#include "many_lights.h"
#include "viewer.h"

namespace {

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
    images.pixels = v.pixels; // listed by record_frame before the effects (CPU devices)
    return images;
}

} // namespace

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
    if (v.pixels && (want_ao || want_direct || want_gi)) { // once for the frame's effects
        roma_pixel_list_images list{};
        list.width = v.gb.width;
        list.height = v.gb.height;
        list.position = v.gb.position.view;
        list.frame = v.frame;
        if (roma_pixel_list_record(v.pixels, cmd, slot, &list) != ROMA_SUCCESS)
            return false;
        v.passes.push_back("pixel_list");
    }
    if (want_ao) {
        roma_ao_images images = gbuffer_images<roma_ao_images>(v, v.cp.ao.view);
        roma_ao_settings as{};
        as.samples = s.ao_samples;
        as.resolution_divisor = s.resolution_divisor;
        as.radius = effective_ao_radius(v);
        as.offset_cells = s.offset;
        as.skip_cells = s.ao_skip;
        as.start = s.ao_surfaces ? ROMA_AO_START_SURFACES : ROMA_AO_START_VOXELS;
        as.trace = s.ao_surface_rays ? ROMA_AO_TRACE_SURFACES : ROMA_AO_TRACE_MAPS;
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
        ls.resolution_divisor = s.resolution_divisor;
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
        gs.resolution_divisor = s.resolution_divisor;
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
