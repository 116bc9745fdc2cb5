// roma-viewer --script FILE: input events for tests and demonstrations, one per line,
// run in order as frames pass ('#' starts a comment):
//   wait N                       let N frames pass
//   key F | key TAB | key F12    press a key (frame the scene, orbit/fly, screenshot)
//   drag left|right DX DY N      drag with a mouse button by (DX, DY) pixels over N frames
//   wheel STEPS                  scroll
//   set ao|direct|gi|accumulate|filter on|off
//   view NAME                    as --view (composed, ao, direct, albedo, normal, map, ...)
//   res R | angular A            the ROMA array
//   camera K                     the scene's camera K (a glTF file's, as the interface lists them)
//   resize W H                   the window (1 1 is allowed)
//   minimize | restore
//   drop FILE                    as if FILE were dropped on the window
//   screenshot FILE.png          the picture once this frame is drawn
//   reference                    start the Embree reference of the view (the interface's button)
//   quit                         (a reference still rendering is stopped)
#pragma once

#include <cstdint>
#include <string>
#include <vector>

struct script_step {
    std::string verb;
    std::vector<std::string> args;
    int line = 0;
};

struct script {
    std::vector<script_step> steps;
    size_t next = 0;        // the step to run
    uint32_t wait = 0;      // frames still to let pass before it
    // a drag in progress
    int drag_button = -1;
    float drag_dx = 0, drag_dy = 0;
    uint32_t drag_frames = 0;
};

// false (message printed) for an unreadable file or an unknown verb.
bool script_load(const char *path, script &out);
