/* Minimal test harness: CHECK macros that count failures, a logger that counts
 * errors, a validated Vulkan context, and the shared-scenes folder. */
#ifndef ROMA_TEST_HARNESS_H
#define ROMA_TEST_HARNESS_H

#include <math.h>
#include <stdio.h>

#include "roma/result.h"

typedef struct roma_context roma_context;

extern int roma_test_failures;

#define CHECK(cond)                                                                          \
    do {                                                                                     \
        if (!(cond)) {                                                                       \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond);         \
            ++roma_test_failures;                                                            \
        }                                                                                    \
    } while (0)

#define CHECK_RESULT(expr, expected)                                                          \
    do {                                                                                     \
        roma_result r_ = (expr);                                                             \
        if (r_ != (expected)) {                                                              \
            fprintf(stderr, "%s:%d: %s returned '%s', expected '%s'\n", __FILE__, __LINE__,  \
                    #expr, roma_result_string(r_), roma_result_string(expected));            \
            ++roma_test_failures;                                                            \
        }                                                                                    \
    } while (0)

#define CHECK_NEAR(a, b, tol)                                                                \
    do {                                                                                     \
        double a_ = (double)(a), b_ = (double)(b), t_ = (double)(tol);                       \
        if (!(fabs(a_ - b_) <= t_)) {                                                        \
            fprintf(stderr, "%s:%d: CHECK_NEAR failed: %s = %.9g, %s = %.9g, tol %.3g\n",   \
                    __FILE__, __LINE__, #a, a_, #b, b_, t_);                                 \
            ++roma_test_failures;                                                            \
        }                                                                                    \
    } while (0)

/* Logger that records messages: errors/warnings counted, last message kept. */
typedef struct roma_test_log {
    int errors;
    int warnings;
    roma_result last_code; /* the code the last error came with */
    char last[1024];
} roma_test_log;

roma_logger roma_test_logger(roma_test_log *log);
/* The same, printing only validation messages (ROMA_TEST_VERBOSE: everything), for tests that
 * make many calls fail on purpose. */
roma_logger roma_test_logger_quiet(roma_test_log *log);

/* ROMA_CONTEXT_SYNC_VALIDATION for tests that record frames in flight, except in the
 * sanitizer suite (ROMA_TEST_PLAIN_VALIDATION set): there Mesa 22.3's LLVM leaks under the
 * synchronization-validation layer, outside libroma; plain validation stays on. */
unsigned roma_test_sync_validation_flags(void);

/* Context with validation on; on failure prints why and returns NULL. */
roma_context *roma_test_context(void);
/* The same with more roma_context_flags. */
roma_context *roma_test_context_flags(unsigned flags);
/* Destroys ctx after checking it saw no validation error (counts a failure if it did). */
void roma_test_context_finish(roma_context *ctx);

/* Path of a file of the repository's scenes/ (ROMA_SCENES_DIR/<file>) into buf; returns 1.
 * A missing file is a failed check (returns 0): the scenes are part of the repository. */
int roma_test_scene_file(const char *file, char *buf, size_t size);

/* Writable scratch path: ROMA_TEST_TMPDIR (or /tmp) + "/" + name. */
const char *roma_test_tmp_path(const char *name, char *buf, size_t size);

/* Prints a summary and returns the process exit code (0 ok, 1 failures). */
int roma_test_finish(const char *test_name);

#endif /* ROMA_TEST_HARNESS_H */
