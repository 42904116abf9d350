#include "subsurf/rng.h"

void ss_rng_seed(ss_rng *rng, uint64_t seed, uint64_t stream) {
  rng->state = 0u;
  rng->inc = (stream << 1u) | 1u;
  ss_rng_next_u32(rng);
  rng->state += seed;
  ss_rng_next_u32(rng);
}

void ss_rng_seed_item(ss_rng *rng, uint64_t seed, uint64_t index) {
  uint64_t key = ss_hash64(index ^ ss_hash64(seed));
  ss_rng_seed(rng, ss_hash64(key), key);
}

void ss_rng_advance(ss_rng *rng, uint64_t delta) {
  uint64_t cur_mult = SS_PCG32_MULT, cur_plus = rng->inc;
  uint64_t acc_mult = 1u, acc_plus = 0u;
  while (delta > 0) {
    if (delta & 1u) {
      acc_mult *= cur_mult;
      acc_plus = acc_plus * cur_mult + cur_plus;
    }
    cur_plus = (cur_mult + 1u) * cur_plus;
    cur_mult *= cur_mult;
    delta >>= 1u;
  }
  rng->state = acc_mult * rng->state + acc_plus;
}

uint64_t ss_hash64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}
