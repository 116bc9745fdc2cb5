#include "script.h"

#include <cstdio>
#include <fstream>
#include <sstream>

bool script_load(const char *path, script &out)
{
    static const char *verbs[] = {"wait", "key", "drag", "wheel", "set", "view", "res", "angular", "camera", "resize",
                                  "minimize", "restore", "drop", "screenshot", "reference", "quit"};
    std::ifstream in(path);
    if (!in) {
        std::fprintf(stderr, "roma-viewer: cannot read the script %s\n", path);
        return false;
    }
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
        ++number;
        size_t hash = line.find('#');
        if (hash != std::string::npos)
            line.resize(hash);
        std::istringstream words(line);
        script_step step;
        step.line = number;
        if (!(words >> step.verb))
            continue;
        std::string w;
        while (words >> w)
            step.args.push_back(w);
        bool known = false;
        for (const char *v : verbs)
            known = known || step.verb == v;
        if (!known) {
            std::fprintf(stderr, "roma-viewer: %s:%d: unknown step '%s'\n", path, number, step.verb.c_str());
            return false;
        }
        out.steps.push_back(step);
    }
    return true;
}
