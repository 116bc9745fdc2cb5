// roma-viewer: "compare with reference". The current view rendered by the Embree reference
// (roma-render --tracer embree, the tool installed beside the viewer) in the background,
// so the viewer itself stays on libroma's public API; its progress, then its images.
#pragma once

#include <roma/image.h>

#include <sys/types.h>

#include <atomic>
#include <string>
#include <thread>

struct reference_job {
    std::thread worker;
    std::atomic<int> percent{0};
    std::atomic<bool> running{false}, finished{false}, cancelled{false};
    std::atomic<pid_t> pid{0}; // roma-render's, in a process group of its own (0: none)
    bool ok = false;
    std::string folder;  // roma-render's --out
    std::string message; // the error, when not ok
    std::string command;
};

// roma-render beside the running executable.
std::string reference_tool_path();
// Starts roma-render; false if a job is still running (message untouched) or it cannot start
// (message set). scene_options: more roma-render options that make its scene the viewer's
// (--up, --time, --clip), each argument already quoted for the shell.
bool reference_job_start(reference_job &job, const std::string &tool, const std::string &camera, uint32_t width,
                         uint32_t height, uint32_t spp, float ao_radius, const std::string &scene,
                         const std::string &scene_options);
// Once finished: joins the worker. Reads <folder>/<name>.pfm into out (caller frees).
void reference_job_join(reference_job &job);
// Stops a running roma-render (its process group gets SIGTERM); the job finishes not ok.
void reference_job_cancel(reference_job &job);
// Joins and removes the folder.
void reference_job_cleanup(reference_job &job);
bool reference_job_image(const reference_job &job, const char *name, roma_image *out);
