/* The fuzzers' random numbers (splitmix64): a case's or sequence's whole content follows from
 * its seed, so that a finding is reproduced by its seed and number. And a monotonic clock for
 * their time budgets. */
#ifndef ROMA_TEST_FUZZ_RANDOM_H
#define ROMA_TEST_FUZZ_RANDOM_H

#include <stdint.h>
#include <time.h>

typedef struct rng {
    uint64_t s;
} rng;

/* The generator of case or sequence `index` of `seed`. */
static inline rng rng_of(uint64_t seed, uint64_t index)
{
    return (rng){seed * 0x632be59bd9b4e019ull ^ (index + 1) * 0x9e3779b97f4a7c15ull};
}

static inline uint64_t next_u64(rng *r)
{
    uint64_t z = (r->s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* Uniform in [0, n). */
static inline uint32_t below(rng *r, uint32_t n)
{
    return (uint32_t)(next_u64(r) % n);
}

/* Uniform in [0, 1). */
static inline float unit(rng *r)
{
    return (float)(next_u64(r) >> 40) * 0x1p-24f;
}

static inline double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

#endif /* ROMA_TEST_FUZZ_RANDOM_H */
