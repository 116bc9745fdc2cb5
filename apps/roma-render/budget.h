/* roma-render --budget-ms T: the most accurate quality preset (roma/presets.h) whose time
 * per frame on this device, scene, size and effects fits T. Times come from a cache of
 * earlier measurements, else from a short calibration run of each preset, fastest first,
 * stopping at the first over the budget (the presets lie on the measured front, so each is
 * slower than the one before). */
#ifndef ROMA_RENDER_BUDGET_H
#define ROMA_RENDER_BUDGET_H

#include "roma/presets.h"

/* Measures one preset's milliseconds per frame; < 0 on failure. */
typedef double (*budget_measure_fn)(roma_preset preset, void *user_data);

typedef struct budget_choice {
    roma_preset preset;                  /* the choice: ROMA_PRESET_LOW when none fits */
    int fits;                            /* 0: even the fastest is over the budget */
    double ms[ROMA_PRESET_COUNT + 1];    /* per preset (index roma_preset), < 0: not measured */
    int cached[ROMA_PRESET_COUNT + 1];   /* 1: ms came from the cache */
} budget_choice;

/* The cache file: $XDG_CACHE_HOME/libroma/budget.tsv, else ~/.cache/libroma/budget.tsv; NULL
 * when neither variable is set. Static storage. */
const char *budget_default_cache(void);

/* Chooses for `budget_ms`. key names the device, scene, size and effects (no tabs or line
 * breaks); cache_path may be NULL (measure, keep nothing). New measurements are appended
 * to the cache (its folder made when missing; a cache that cannot be written is only
 * noted on stderr). Returns 0 when a measurement failed. */
int budget_choose(double budget_ms, const char *key, const char *cache_path, budget_measure_fn measure,
                  void *user_data, budget_choice *out);

#endif /* ROMA_RENDER_BUDGET_H */
