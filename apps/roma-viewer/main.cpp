// roma-viewer: the interactive viewer of libroma, built on the public API only (the
// installed libraries roma::roma, roma::gltf and roma::tools, the public headers and the
// public GLSL), as an engine would use it: its own instance, device, swapchain and
// G-buffer; libroma's map build, animator, AO and light effects recorded into its command
// buffers with two frames in flight; its own compute pass tracing ROMA rays for the debug
// views. --headless renders without a window (tests, scripts).
// The parts, a file each: options, scene_setup (the scene, its map, libroma's objects), frame
// (one frame's commands), pictures, window_loop, headless, stats; viewer.h joins them.
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>

#include "viewer.h"

int main(int argc, char **argv)
{
    viewer v;
    int parsed = parse_args(argc, argv, v.opt);
    if (parsed >= 0)
        return parsed;
    v.s = v.opt.settings;
    if (!v.opt.headless) {
        if (!glfwInit()) {
            std::fprintf(stderr, "roma-viewer: cannot open a window (no display?); --headless renders without one\n");
            return 1;
        }
        glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
        v.window = glfwCreateWindow(int(v.opt.width), int(v.opt.height), "roma-viewer", nullptr, nullptr);
        if (!v.window || !glfwVulkanSupported()) {
            std::fprintf(stderr, "roma-viewer: cannot open a Vulkan window; --headless renders without one\n");
            glfwTerminate();
            return 1;
        }
    }
    int status = 1;
    if (vk_base_create(v.base, v.window, v.opt.validation, v.opt.device.empty() ? nullptr : v.opt.device.c_str()) &&
        create_frame_objects(v) && create_libroma(v) && gbuffer_pass_create(v.base, v.gb) &&
        compose_pass_create(v.base, v.cp) && open_scene(v, v.opt.scene)) {
        v.info.device = v.base.properties.deviceName;
        if (v.opt.has_camera)
            camera_control_set(v.cam, v.opt.camera);
        if (v.opt.headless) {
            status = run_headless(v);
        } else {
            int fw = 0, fh = 0;
            glfwGetFramebufferSize(v.window, &fw, &fh);
            if (swapchain_create(v.base, v.sc, uint32_t(fw), uint32_t(fh)) && init_imgui(v) &&
                resize_images(v, v.sc.extent.width, v.sc.extent.height))
                status = run_window(v);
        }
    }
    if (!v.opt.stats.empty() && !write_stats(v, status))
        status = 1;
    uint32_t messages = v.base.validation_messages;
    destroy(v);
    messages = std::max(messages, v.base.validation_messages);
    if (!v.opt.headless)
        glfwTerminate();
    if (v.opt.validation && messages) {
        std::fprintf(stderr, "roma-viewer: %u validation messages\n", messages);
        return 1;
    }
    return status;
}
