/* Candidate directions of the ray-aligned maps: equal-area concentric mapping
 * between the unit square and the hemisphere z >= 0, stratified A x A.
 * include/roma/trace.glsl mirrors roma_direction_to_map. */
#ifndef ROMA_DIRECTIONS_H
#define ROMA_DIRECTIONS_H

#include <stdint.h>

/* (u, v) in [0,1]^2 -> unit direction with z >= 0; strata keep equal solid angle. */
void roma_square_to_hemisphere(float u, float v, float out_dir[3]);

/* Inverse for unit d with d.z >= 0; (u, v) in [0,1]^2. */
void roma_hemisphere_to_square(const float d[3], float *u, float *v);

/* Unit vector of d, as roma_unit_direction in GLSL: components below FLT_MIN count
 * as zero; d is divided by its largest component before the length is taken, so
 * d * 2^k gives the same bits. Returns 0 (unit = 0) for zero, NaN or infinite d. */
int roma_unit_direction(const float d[3], float unit[3]);

/* Map index (stratum sy * A + sx) of a unit direction; *folded is 1 when
 * unit.z < 0 and -unit was used. */
uint32_t roma_unit_direction_to_map(const float unit[3], uint32_t angular, int *folded);

/* The same for any direction; invalid ones (see above) map to 0, not folded. */
uint32_t roma_direction_to_map(const float d[3], uint32_t angular, int *folded);

/* The candidate of stratum k (sx = k % A, sy = k / A) at (ju, jv) within it; the
 * jitter is clamped to [1e-4, 1 - 1e-4] so that the candidate selects map k. */
void roma_stratum_candidate(uint32_t angular, uint32_t k, float ju, float jv, float out_dir[3]);

/* A*A candidates (3 floats each), candidate k inside stratum k. jitter = 0 puts
 * each at its stratum centre; otherwise the position in the stratum comes from
 * roma_random(seed, k, frame, 0..1). */
void roma_candidate_directions(uint32_t angular, uint32_t seed, uint32_t frame, int jitter,
                               float *out_dirs);

#endif /* ROMA_DIRECTIONS_H */
