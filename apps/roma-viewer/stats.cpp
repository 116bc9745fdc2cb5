// roma-viewer --stats FILE.json: a run's facts for the tests, written at exit whatever the run's
// outcome (the exit status is one of them).
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

#include "camera_control.h"
#include "stats_json.h"
#include "viewer.h"

// --stats: what a script or a person needs to check a run.
bool write_stats(const viewer &v, int status)
{
    FILE *f = std::fopen(v.opt.stats.c_str(), "w");
    if (!f) {
        std::fprintf(stderr, "roma-viewer: cannot write %s: %s\n", v.opt.stats.c_str(), std::strerror(errno));
        return false;
    }
    roma_json j{};
    j.f = f;
    roma_json_begin_object(&j, nullptr);
    roma_json_string(&j, "tool", "roma-viewer");
    roma_json_string(&j, "device", v.info.device.c_str());
    roma_json_string(&j, "scene", v.info.scene_name.c_str());
    roma_json_int(&j, "frames", v.frame);
    roma_json_int(&j, "width", v.gb.width);
    roma_json_int(&j, "height", v.gb.height);
    roma_json_string(&j, "view", kViewNames[v.s.view]);
    roma_json_string(&j, "camera", camera_to_string(camera_control_get(v.cam)).c_str());
    roma_json_int(&j, "accumulated", v.accumulated);
    roma_map_info mi{}; // the map's own RES and A: what the last build used
    if (v.map)
        roma_map_get_info(v.map, &mi);
    roma_json_int(&j, "resolution", mi.resolution);
    roma_json_int(&j, "angular", mi.angular);
    roma_json_int(&j, "levels", mi.levels);
    roma_json_int(&j, "resolution_divisor", v.s.resolution_divisor);
    roma_json_number(&j, "sky", v.s.ambient);
    roma_json_begin_array(&j, "passes"); // of the last recorded frame
    for (const std::string &p : v.passes)
        roma_json_string(&j, nullptr, p.c_str());
    roma_json_end_array(&j);
    roma_json_begin_object(&j, "last_frame_ms");
    roma_json_string(&j, "clock", v.timings.clock.c_str());
    roma_json_number(&j, "animate", v.timings.animate_ms);
    roma_json_number(&j, "build", v.timings.build_ms);
    roma_json_number(&j, "gbuffer", v.timings.gbuffer_ms);
    roma_json_number(&j, "effects", v.timings.effects_ms);
    roma_json_number(&j, "compose", v.timings.compose_ms);
    roma_json_end_object(&j);
    roma_json_int(&j, "scene_failures", v.scene_failures);
    roma_json_int(&j, "validation_messages", v.base.validation_messages);
    roma_json_int(&j, "libroma_device_memory_bytes", (long long)v.info.device_memory);
    roma_json_int(&j, "exit_status", status);
    roma_json_end_object(&j);
    bool ok = !j.failed && !std::ferror(f);
    ok = std::fclose(f) == 0 && ok;
    return ok;
}
