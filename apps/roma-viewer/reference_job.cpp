#include "reference_job.h"

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

std::string reference_tool_path()
{
    char self[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    if (n <= 0)
        return "roma-render";
    self[n] = '\0';
    char *slash = std::strrchr(self, '/');
    if (!slash)
        return "roma-render";
    *slash = '\0';
    return std::string(self) + "/roma-render";
}

static std::string shell_quote(const std::string &s)
{
    std::string q = "'";
    for (char c : s)
        q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

bool reference_job_start(reference_job &job, const std::string &tool, const std::string &camera, uint32_t width,
                         uint32_t height, uint32_t spp, float ao_radius, const std::string &scene,
                         const std::string &scene_options)
{
    if (job.running) // its worker may still write job.message: leave it alone
        return false;
    reference_job_cleanup(job);
    char folder[] = "/tmp/roma-viewer-reference-XXXXXX";
    if (!mkdtemp(folder)) {
        job.message = std::string("cannot make a temporary folder: ") + std::strerror(errno);
        return false;
    }
    job.folder = folder;
    char args[512];
    std::snprintf(args, sizeof args, " --tracer embree --effects ao,direct --size %ux%u --spp %u --ao-radius %.9g",
                  width, height, spp, double(ao_radius));
    job.command = shell_quote(tool) + " --scene " + shell_quote(scene) + " --camera " + shell_quote(camera) + args +
                  scene_options + " --out " + shell_quote(job.folder) + " 2>&1";
    job.percent = 0;
    job.ok = false;
    job.message.clear();
    job.finished = false;
    job.cancelled = false;
    job.running = true;
    job.worker = std::thread([&job] {
        // sh -c "exec roma-render ..." in a process group of its own, so that a cancel stops it
        // (popen gives no pid). Between fork and exec the child calls only what is safe there.
        std::string shell_command = "exec " + job.command;
        int fds[2];
        pid_t pid = -1;
        if (pipe(fds) == 0) {
            pid = fork();
            if (pid == 0) {
                setpgid(0, 0);
                dup2(fds[1], 1);
                dup2(fds[1], 2);
                close(fds[0]);
                close(fds[1]);
                execl("/bin/sh", "sh", "-c", shell_command.c_str(), static_cast<char *>(nullptr));
                _exit(127);
            }
            close(fds[1]);
            if (pid < 0)
                close(fds[0]);
        }
        FILE *p = pid > 0 ? fdopen(fds[0], "r") : nullptr;
        if (!p) {
            job.message = "cannot run roma-render";
            if (pid > 0) {
                close(fds[0]);
                kill(-pid, SIGTERM);
                waitpid(pid, nullptr, 0);
            }
        } else {
            setpgid(pid, pid); // also here: a cancel right after the fork finds the group
            job.pid = pid;
            char line[1024];
            std::string last;
            while (std::fgets(line, sizeof line, p)) {
                const char *pc = std::strchr(line, '%');
                if (pc && pc - line >= 3) // "roma-render: rendering  40%"
                    job.percent = std::atoi(pc - 3);
                else if (std::strncmp(line, "wrote ", 6) != 0)
                    last = line;
            }
            std::fclose(p);
            int status = 0;
            waitpid(pid, &status, 0);
            job.pid = 0;
            job.ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
            if (!job.ok)
                job.message = job.cancelled ? "the reference was cancelled" : "roma-render failed: " + last;
        }
        job.finished = true;
        job.running = false;
    });
    return true;
}

void reference_job_join(reference_job &job)
{
    if (job.worker.joinable())
        job.worker.join();
}

void reference_job_cancel(reference_job &job)
{
    pid_t pid = job.pid;
    if (job.running && pid > 0) {
        job.cancelled = true;
        kill(-pid, SIGTERM);
    }
}

void reference_job_cleanup(reference_job &job)
{
    reference_job_join(job);
    if (!job.folder.empty()) {
        std::error_code ignored;
        std::filesystem::remove_all(job.folder, ignored);
        job.folder.clear();
    }
}

bool reference_job_image(const reference_job &job, const char *name, roma_image *out)
{
    std::string path = job.folder + "/" + name + ".pfm";
    return roma_image_read_pfm(path.c_str(), out) == ROMA_SUCCESS;
}
