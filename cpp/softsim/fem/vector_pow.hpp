#pragma once
// x^y for x > 0 without a library call, so that the Ogden kernel's element loop vectorises
// (std::pow is a scalar call there; its vector variants exist only under -ffast-math). Written
// as exp(y ln x) with only bit operations, multiplies and adds:
//   ln x: x = m 2^e with m in [√½, √2), ln m = 2 atanh t, t = (m − 1)/(m + 1), |t| ≤ 0.172,
//         by its series to t^23 (the next term is below 1e-19);
//   exp z: z = n ln 2 + r, |r| ≤ ½ ln 2, ln 2 split in two parts (Cody–Waite) so that r is exact,
//          e^r by its Taylor series to r^14 (the next term is below 3e-18), times 2^n.
// A few ulp from std::pow for normal x and |y ln x| < 700 (tested against it); what the kernels
// ask of it is the Ogden law's λ̄^α with stretches of a deforming tissue, far inside that.
#include <cstdint>
#include <cstring>

namespace softsim::fem {

inline double bits_to_double(std::uint64_t b) {
  double d;
  std::memcpy(&d, &b, sizeof d);
  return d;
}

inline std::uint64_t double_to_bits(double d) {
  std::uint64_t b;
  std::memcpy(&b, &d, sizeof b);
  return b;
}

inline double vector_log(double x) {
  // x = m 2^k with m in [√½, √2): k + 1024 from the bits of x shifted by those of √½ and by
  // 2^62, so that every quantity stays unsigned (no 64-bit arithmetic shift in AVX2).
  constexpr std::uint64_t kSqrtHalf = 0x3fe6a09e667f3bcdULL, kOffset = 1024ULL << 52;
  const std::uint64_t bits = double_to_bits(x);
  const std::uint64_t k_biased = (bits - kSqrtHalf + kOffset) >> 52;  // k + 1024
  const double m = bits_to_double(bits - (k_biased << 52) + kOffset);
  // k as a double without an int64 → double conversion (none in AVX2): (2^52 + k + 1024) − 2^52 − 1024.
  const double e = bits_to_double(0x4330000000000000ULL | k_biased) - 4503599627370496.0 - 1024.0;
  const double t = (m - 1.0) / (m + 1.0);
  const double t2 = t * t;
  double s = 1.0 / 23.0;
  s = s * t2 + 1.0 / 21.0;
  s = s * t2 + 1.0 / 19.0;
  s = s * t2 + 1.0 / 17.0;
  s = s * t2 + 1.0 / 15.0;
  s = s * t2 + 1.0 / 13.0;
  s = s * t2 + 1.0 / 11.0;
  s = s * t2 + 1.0 / 9.0;
  s = s * t2 + 1.0 / 7.0;
  s = s * t2 + 1.0 / 5.0;
  s = s * t2 + 1.0 / 3.0;
  const double ln_m = 2.0 * t + 2.0 * t * t2 * s;
  constexpr double kLn2Hi = 6.93147180369123816490e-01, kLn2Lo = 1.90821492927058770002e-10;
  return e * kLn2Hi + (ln_m + e * kLn2Lo);
}

inline double vector_exp(double z) {
  constexpr double kInvLn2 = 1.44269504088896338700e+00;
  constexpr double kLn2Hi = 6.93147180369123816490e-01, kLn2Lo = 1.90821492927058770002e-10;
  constexpr double kRound = 6755399441055744.0;  // 1.5 · 2^52: adding it rounds to an integer
  const double shifted = z * kInvLn2 + kRound;
  const double n = shifted - kRound;
  const double r = (z - n * kLn2Hi) - n * kLn2Lo;
  double p = 1.0 / 87178291200.0;  // 1/14!
  p = p * r + 1.0 / 6227020800.0;
  p = p * r + 1.0 / 479001600.0;
  p = p * r + 1.0 / 39916800.0;
  p = p * r + 1.0 / 3628800.0;
  p = p * r + 1.0 / 362880.0;
  p = p * r + 1.0 / 40320.0;
  p = p * r + 1.0 / 5040.0;
  p = p * r + 1.0 / 720.0;
  p = p * r + 1.0 / 120.0;
  p = p * r + 1.0 / 24.0;
  p = p * r + 1.0 / 6.0;
  p = p * r + 0.5;
  p = p * r + 1.0;
  p = p * r + 1.0;
  // 2^n from n's bits in the low word of `shifted` (two's complement).
  const std::uint64_t n_bits = double_to_bits(shifted) & 0xffffffffULL;
  const std::uint64_t scale = ((n_bits + 1023ULL) & 0x7ffULL) << 52;
  return p * bits_to_double(scale);
}

inline double vector_pow(double x, double y) { return vector_exp(y * vector_log(x)); }

}  // namespace softsim::fem
