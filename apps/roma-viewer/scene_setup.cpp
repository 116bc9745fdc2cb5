// roma-viewer: what outlives a frame: the scene on the GPU, its map, libroma's context and
// effects, the frame objects; made once or when the scene changes, all destroyed at exit.
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

#include <roma/builtin_scenes.h>
#include <roma/gltf.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "app_common.h"
#include "viewer.h"

void log_to_stderr(roma_log_level level, roma_result, const char *message, void *)
{
    if (level >= ROMA_LOG_WARNING)
        std::fprintf(stderr, "roma-viewer: libroma %s: %s\n", roma_log_level_string(level), message);
}

// --- the scene on the GPU ---------------------------------------------------------------

namespace {

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

} // namespace

float effective_ao_radius(const viewer &v)
{
    return v.s.ao_radius > 0.0f ? v.s.ao_radius : v.s.auto_ao_radius;
}

// The cascade levels the settings ask for (0: chosen for the scene and the AO radius, as
// roma-render chooses, from the camera the scene opens at: the one given or the scene's own,
// else one framing it from outside; not the moving camera, so that flying does not rebuild
// the map), and the finest level's edge; at most 256 maps in all, and at most what one storage
// buffer of the device holds.
uint32_t wanted_levels(const viewer &v, float &finest)
{
    const float *eye = v.opt.has_camera ? v.opt.camera.eye : v.view.has_camera ? v.view.camera.eye : nullptr;
    uint32_t chosen = roma_app_auto_cascades(v.view.bounds_min, v.view.bounds_max, eye, v.s.res, effective_ao_radius(v),
                                             v.s.finest_extent, &finest);
    const uint32_t levels = v.s.cascades ? v.s.cascades : chosen;
    const uint32_t fit = roma_app_levels_that_fit(v.s.res, v.s.angular, v.base.properties.limits.maxStorageBufferRange);
    return std::max(1u, std::min(levels, fit));
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

namespace {

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

} // namespace

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
bool open_scene(viewer &v, const std::string &name, bool dropped)
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
    roma_pixel_list_desc pd{};
    pd.frames_in_flight = kSlots;
    if (ci.device_type == VK_PHYSICAL_DEVICE_TYPE_CPU && roma_pixel_list_create(v.ctx, &pd, &v.pixels) != ROMA_SUCCESS)
        return false;
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
    roma_pixel_list_destroy(v.pixels);
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
