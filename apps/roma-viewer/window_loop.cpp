// roma-viewer: the window: Dear ImGui, mouse and keys, --script's events and the loop that
// draws and presents frames until the window closes.
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "script.h"
#include "ui.h"
#include "viewer.h"

namespace {

constexpr uint32_t kHistory = 240;  // frame-time graph

void check_vk(VkResult r)
{
    if (r < 0)
        std::fprintf(stderr, "roma-viewer: the interface's Vulkan call failed (%d)\n", int(r));
}

struct font_upload {
    static void record(VkCommandBuffer cmd, void *) { ImGui_ImplVulkan_CreateFontsTexture(cmd); }
};

} // namespace

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

namespace {

// The animation's clip may have changed (UI): its duration, and the time within it.
void follow_clip(viewer &v)
{
    if (!v.s.animated || roma_animator_clip_duration(v.animator, v.s.clip, &v.s.duration) != ROMA_SUCCESS)
        return;
    if (v.s.time > v.s.duration)
        v.s.time = v.s.duration > 0.0f ? std::fmod(v.s.time, v.s.duration) : 0.0f;
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

} // namespace

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
