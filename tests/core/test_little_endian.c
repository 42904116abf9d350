/* Numbers as little-endian bytes (core/little_endian.h), the byte order of
 * subsurf's table and grid files on any machine: the bytes of known values,
 * and each read giving back what was written. */
#include "core/little_endian.h"

#include <criterion/criterion.h>
#include <float.h>
#include <math.h>

Test(little_endian, known_values_give_their_bytes_lowest_first) {
  unsigned char b[8];
  ss_le_put_u32(b, 0x01020304u);
  const unsigned char u32[4] = {0x04, 0x03, 0x02, 0x01};
  cr_expect_arr_eq(b, u32, 4);
  ss_le_put_u64(b, 0x0102030405060708ull);
  const unsigned char u64[8] = {0x08, 0x07, 0x06, 0x05, 0x04, 0x03, 0x02, 0x01};
  cr_expect_arr_eq(b, u64, 8);
  ss_le_put_f32(b, 1.0f); /* IEEE 754 single: 0x3f800000 */
  const unsigned char f32[4] = {0x00, 0x00, 0x80, 0x3f};
  cr_expect_arr_eq(b, f32, 4);
  ss_le_put_f64(b, -2.0); /* IEEE 754 double: 0xc000000000000000 */
  const unsigned char f64[8] = {0, 0, 0, 0, 0, 0, 0, 0xc0};
  cr_expect_arr_eq(b, f64, 8);
}

Test(little_endian, what_is_written_reads_back) {
  unsigned char b[8];
  const uint32_t u32[] = {0u, 1u, 0x80000000u, 0xdeadbeefu, UINT32_MAX};
  for (size_t i = 0; i < sizeof u32 / sizeof *u32; ++i) {
    ss_le_put_u32(b, u32[i]);
    cr_expect_eq(ss_le_get_u32(b), u32[i]);
  }
  const uint64_t u64[] = {0u, 1u, 0x8000000000000000ull, 0x0123456789abcdefull, UINT64_MAX};
  for (size_t i = 0; i < sizeof u64 / sizeof *u64; ++i) {
    ss_le_put_u64(b, u64[i]);
    cr_expect_eq(ss_le_get_u64(b), u64[i]);
  }
  const double f64[] = {0.0, -0.0, 1.0 / 3.0, -1e-310, 1.7976931348623157e308};
  for (size_t i = 0; i < sizeof f64 / sizeof *f64; ++i) {
    ss_le_put_f64(b, f64[i]);
    double d = ss_le_get_f64(b);
    cr_expect(!memcmp(&d, &f64[i], sizeof d), "%a read back as %a", f64[i], d);
  }
  const float f32[] = {0.0f, -0.0f, 1.0f / 3.0f, -1e-40f, FLT_MAX};
  for (size_t i = 0; i < sizeof f32 / sizeof *f32; ++i) {
    ss_le_put_f32(b, f32[i]);
    float f = ss_le_get_f32(b);
    cr_expect(!memcmp(&f, &f32[i], sizeof f), "%a read back as %a", (double)f32[i], (double)f);
  }
  ss_le_put_f32(b, NAN);
  cr_expect(isnan(ss_le_get_f32(b)));
}
