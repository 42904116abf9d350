/* PCG32 random numbers (O'Neill 2014, pcg32 "XSH RR" output) with
 * independent streams: one stream per (seed, path or pixel index) makes every
 * result independent of how work is scheduled across threads. */
#ifndef SUBSURF_RNG_H
#define SUBSURF_RNG_H

#include <stdint.h>

typedef struct {
  uint64_t state;
  uint64_t inc; /* stream selector, always odd */
} ss_rng;

#define SS_PCG32_MULT 6364136223846793005ULL

static inline uint32_t ss_rng_next_u32(ss_rng *rng) {
  uint64_t old = rng->state;
  rng->state = old * SS_PCG32_MULT + rng->inc;
  uint32_t xorshifted = (uint32_t)(((old >> 18u) ^ old) >> 27u);
  uint32_t rot = (uint32_t)(old >> 59u);
  return (xorshifted >> rot) | (xorshifted << ((-rot) & 31u));
}

/* Uniform double in [0, 1) with 32 random bits (enough for sampling). */
static inline double ss_rng_uniform(ss_rng *rng) { return ss_rng_next_u32(rng) * 0x1p-32; }

/* Seeds the generator: `seed` picks the starting point, `stream` one of 2^63
 * independent sequences (O'Neill's pcg32_srandom_r). */
void ss_rng_seed(ss_rng *rng, uint64_t seed, uint64_t stream);

/* The generator of item `index` (a path, a chunk of samples) of a run seeded
 * with `seed`, from (seed, index) alone. Seeding PCG32 with (seed, index)
 * directly starts consecutive items from states in arithmetic progression:
 * the n-th draws of items 0, 1, ... form a Weyl sequence, so a run is mildly
 * stratified beyond what its batches show (the half-space reference's
 * standard errors were 10-20 % too large, rms z-score 0.82 against
 * Chandrasekhar), and item i + 1 of seed s begins like item i of seed s + 2.
 * Hashing (seed, index) into both the state and the stream decorrelates them. */
void ss_rng_seed_item(ss_rng *rng, uint64_t seed, uint64_t index);

/* Skips `delta` draws ahead in O(log delta) (Brown 1994, "Random number
 * generation with arbitrary strides"). */
void ss_rng_advance(ss_rng *rng, uint64_t delta);

/* A well-mixed 64-bit hash (splitmix64 finaliser) for deriving streams. */
uint64_t ss_hash64(uint64_t x);

#endif
