#include "ui.h"

#include <imgui.h>
#include <roma/presets.h>
#include <roma/trace_types.h>

#include <cstdio>
#include <cstring>

namespace {
const char *kViews[VIEW_COUNT] = {"composed", "ambient occlusion", "direct light", "albedo", "normal",
                                  "ROMA map per pixel (ray along the normal)", "ROMA hit distance along the normal",
                                  "base occupancy map slice (captured)", "reference (Embree)",
                                  "difference to the reference", "indirect light (one bounce)",
                                  "un-snapped steps to the first light (magenta: gave up)",
                                  "one rotated map along its direction",
                                  "AO rays whose start meets another surface",
                                  "cascade levels (black: the faces of their cubes)"};
const uint32_t kResolutions[4] = {32, 64, 128, 256};
} // namespace

void ui_draw(viewer_settings &s, const viewer_timings &t, const viewer_info &info, ui_actions &out)
{
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(470, 0), ImGuiCond_FirstUseEver);
    ImGui::Begin("libroma viewer");
    ImGui::Text("%s", info.device.c_str());
    ImGui::Text("%s: %u triangles, %u punctual lights, %u emissive triangles", info.scene_name.c_str(),
                info.triangles, info.lights, info.area_light_triangles);
    ImGui::Text("%ux%u, %u frames accumulated", info.width, info.height, info.accumulated);
    if (info.validation_messages)
        ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "%u validation messages (see the terminal)",
                           info.validation_messages);

    if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) {
        int v = static_cast<int>(s.view);
        if (ImGui::Combo("view", &v, kViews, VIEW_COUNT)) {
            s.view = static_cast<view_mode>(v);
            out.reset_accumulation = true;
        }
        out.reset_accumulation |= ImGui::SliderFloat("exposure", &s.exposure, 0.05f, 20.0f, "%.2f",
                                                     ImGuiSliderFlags_Logarithmic);
        out.reset_accumulation |= ImGui::SliderFloat("sky (ambient x AO)", &s.ambient, 0.0f, 2.0f);
        out.reset_accumulation |= ImGui::Checkbox("accumulate while still", &s.accumulate);
        ImGui::SameLine();
        ImGui::Checkbox("filter while moving", &s.filter);
    }
    if (ImGui::CollapsingHeader("Effects", ImGuiTreeNodeFlags_DefaultOpen)) {
        out.reset_accumulation |= ImGui::Checkbox("ambient occlusion", &s.ao_on);
        ImGui::SameLine();
        out.reset_accumulation |= ImGui::Checkbox("direct light", &s.direct_on);
        ImGui::SameLine();
        out.reset_accumulation |= ImGui::Checkbox("GI", &s.gi_on);
        int scale = s.resolution_divisor == 4 ? 2 : s.resolution_divisor == 2 ? 1 : 0;
        if (ImGui::Combo("traced pixels", &scale, "every pixel\0one in 2x2\0one in 4x4\0")) {
            s.resolution_divisor = 1u << scale;
            out.reset_accumulation = true;
        }
        int samples = static_cast<int>(s.ao_samples);
        if (ImGui::SliderInt("AO rays per pixel", &samples, 1, 64)) {
            s.ao_samples = static_cast<uint32_t>(samples);
            out.reset_accumulation = true;
        }
        float shown = s.ao_radius > 0.0f ? s.ao_radius : s.auto_ao_radius;
        if (ImGui::SliderFloat("AO radius", &shown, 0.001f * s.auto_ao_radius, 20.0f * s.auto_ao_radius, "%.4g",
                               ImGuiSliderFlags_Logarithmic)) {
            s.ao_radius = shown;
            out.reset_accumulation = true;
        }
        int many = static_cast<int>(s.many_lights);
        if (ImGui::SliderInt("many lights (added to direct)", &many, 0, 4096, "%d", ImGuiSliderFlags_Logarithmic)) {
            s.many_lights = static_cast<uint32_t>(many);
            out.reset_accumulation = true;
        }
        int per_frame = static_cast<int>(s.lights_per_frame);
        if (s.many_lights > 0 && ImGui::SliderInt("of them per pixel and frame", &per_frame, 1, 64)) {
            s.lights_per_frame = static_cast<uint32_t>(per_frame);
            out.reset_accumulation = true;
        }
        int area = static_cast<int>(s.area_samples);
        if (ImGui::SliderInt("area-light samples per pixel", &area, 1, 64)) {
            s.area_samples = static_cast<uint32_t>(area);
            out.reset_accumulation = true;
        }
        int steps = static_cast<int>(s.max_steps);
        if (ImGui::SliderInt("shadow max steps", &steps, 1, 64)) {
            s.max_steps = static_cast<uint32_t>(steps);
            out.reset_accumulation = true;
        }
        out.reset_accumulation |= ImGui::SliderFloat("AO skip (cells, 0 = default)", &s.ao_skip, 0.0f, 4.0f);
        out.reset_accumulation |= ImGui::Checkbox("AO start through the surface grid (fine geometry, slower)",
                                                  &s.ao_surfaces);
        out.reset_accumulation |= ImGui::Checkbox("AO rays through the surface grid (close to the reference, slower)",
                                                  &s.ao_surface_rays);
        out.reset_accumulation |= ImGui::SliderFloat("shadow skip (cells, 0 = default)", &s.shadow_skip, 0.0f, 4.0f);
        out.reset_accumulation |= ImGui::SliderFloat("origin offset (cells, 0 = default)", &s.offset, 0.0f, 4.0f);
    }
    if (ImGui::CollapsingHeader("Effect plan")) {
        ImGui::TextWrapped("%s", info.plan.c_str());
    }
    if (ImGui::CollapsingHeader("ROMA array", ImGuiTreeNodeFlags_DefaultOpen)) {
        int r = 0;
        for (int i = 0; i < 4; ++i)
            if (kResolutions[i] == s.res)
                r = i;
        const char *names[4] = {"32", "64", "128", "256"};
        if (ImGui::Combo("RES", &r, names, 4)) {
            s.res = kResolutions[r];
            out.rebuild_map = out.reset_accumulation = true;
        }
        int a = static_cast<int>(s.angular);
        if (ImGui::SliderInt("A (A x A directions)", &a, 1, 16)) {
            s.angular = static_cast<uint32_t>(a);
            out.rebuild_map = out.reset_accumulation = true;
        }
        int levels = static_cast<int>(s.cascades);
        if (ImGui::SliderInt("cascade levels (0 = chosen)", &levels, 0, ROMA_MAX_LEVELS)) {
            s.cascades = static_cast<uint32_t>(levels);
            out.rebuild_map = out.reset_accumulation = true;
        }
        // The quality presets (roma/presets.h): the points of ROMA's measured accuracy-time front.
        ImGui::TextUnformatted("preset:");
        for (unsigned p = ROMA_PRESET_LOW; p <= ROMA_PRESET_COUNT; ++p) {
            uint32_t pr = 0, pa = 0;
            roma_preset_map_settings(roma_preset(p), &pr, &pa);
            const bool current = pr == s.res && pa == s.angular;
            ImGui::SameLine();
            if (ImGui::RadioButton(roma_preset_name(roma_preset(p)), current) && !current) {
                s.res = pr;
                s.angular = pa;
                out.rebuild_map = out.reset_accumulation = true;
            }
        }
        ImGui::Text("%u maps, %.1f MiB, cell %.4g", info.levels * s.angular * s.angular,
                    double(info.map_bytes) / (1 << 20), double(info.grid_cell));
        if (info.levels > 1)
            ImGui::Text("%u levels around the camera, the finest %.4g wide", info.levels,
                        double(info.finest_extent));
        ImGui::Text("libroma holds %.1f MiB of device memory", double(info.device_memory) / (1 << 20));
    }
    if (ImGui::CollapsingHeader("What the rays see")) {
        const char *axes[3] = {"x", "y", "z"};
        int axis = static_cast<int>(s.slice_axis);
        if (ImGui::Combo("slice axis", &axis, axes, 3)) {
            s.slice_axis = static_cast<uint32_t>(axis);
            out.reset_accumulation = true;
        }
        int depth = static_cast<int>(s.slice_depth);
        if (ImGui::SliderInt("slice depth (cells)", &depth, 0, static_cast<int>(s.res) - 1)) {
            s.slice_depth = static_cast<uint32_t>(depth);
            out.reset_accumulation = true;
        }
        int map = static_cast<int>(s.map_index);
        if (ImGui::SliderInt("rotated map", &map, 0, static_cast<int>(s.angular * s.angular) - 1)) {
            s.map_index = static_cast<uint32_t>(map);
            s.view = VIEW_ROTATED_MAP;
        }
        if (ImGui::Button("capture the occupancy map")) {
            out.capture_bom = true;
            s.view = VIEW_BOM_SLICE;
        }
        if (info.bom_captured) {
            ImGui::SameLine();
            ImGui::TextDisabled("red: occupied cells of the layer, blue: empty");
        }
        ImGui::Separator();
        int spp = static_cast<int>(s.reference_spp);
        if (ImGui::SliderInt("reference samples", &spp, 4, 1024, "%d", ImGuiSliderFlags_Logarithmic))
            s.reference_spp = static_cast<uint32_t>(spp);
        if (info.reference_running) {
            ImGui::ProgressBar(float(info.reference_percent) / 100.0f, ImVec2(-1, 0), "Embree reference");
        } else {
            out.start_reference |= ImGui::Button("compare with reference (AO, or direct in the direct view)");
        }
        if (info.reference_ready) {
            out.measure |= ImGui::Button("measure MAE");
            ImGui::SameLine();
            // These views accumulate the compared quantity, not the one shown before: start over.
            if (ImGui::Button("show reference"))
                s.view = VIEW_REFERENCE, out.reset_accumulation = true;
            ImGui::SameLine();
            if (ImGui::Button("show difference"))
                s.view = VIEW_DIFFERENCE, out.reset_accumulation = true;
        }
        if (!info.reference_status.empty())
            ImGui::TextWrapped("%s", info.reference_status.c_str());
    }
    if (s.animated && ImGui::CollapsingHeader("Animation", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::Checkbox("play", &s.playing);
        ImGui::SameLine();
        ImGui::SliderFloat("speed", &s.speed, 0.0f, 4.0f);
        if (ImGui::SliderFloat("time", &s.time, 0.0f, s.duration > 0.0f ? s.duration : 1.0f, "%.3f s"))
            out.reset_accumulation = true;
        int clip = static_cast<int>(s.clip);
        if (s.clip_count > 1 && ImGui::SliderInt("clip", &clip, 0, static_cast<int>(s.clip_count) - 1)) {
            s.clip = static_cast<uint32_t>(clip);
            out.reset_accumulation = true;
        }
    }
    if (ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::TextWrapped("%s", info.camera_string.c_str());
        if (ImGui::Button("copy"))
            ImGui::SetClipboardText(info.camera_string.c_str());
        ImGui::SameLine();
        if (ImGui::Button("paste")) {
            const char *clip = ImGui::GetClipboardText();
            if (clip) {
                std::snprintf(out.camera_text, sizeof out.camera_text, "%s", clip);
                out.camera_pasted = true;
            }
        }
        ImGui::SameLine();
        out.frame_scene |= ImGui::Button("frame the scene (F)");
        for (size_t i = 0; i < info.scene_cameras.size(); ++i)
            if (ImGui::Button(info.scene_cameras[i].c_str()))
                out.scene_camera = static_cast<int>(i);
        ImGui::TextDisabled("left drag: orbit, right drag: pan, wheel: zoom; Tab: fly (WASD, QE)");
    }
    if (ImGui::CollapsingHeader("Timing", ImGuiTreeNodeFlags_DefaultOpen)) {
        const char *clock = t.clock.c_str();
        ImGui::Text("frame %.1f ms (host)", t.frame_ms);
        ImGui::Text("%s: animate %.2f, build %.2f, G-buffer %.2f, effects %.2f, compose %.2f ms", clock,
                    t.animate_ms, t.build_ms, t.gbuffer_ms, t.effects_ms, t.compose_ms);
        if (!t.history.empty())
            ImGui::PlotLines("frame ms", t.history.data(), static_cast<int>(t.history.size()), 0, nullptr, 0.0f,
                             FLT_MAX, ImVec2(0, 60));
    }
    out.screenshot |= ImGui::Button("screenshot (F12)");
    ImGui::End();
}
