#include "core/codes/artkplus_bch_code.h"

#include <array>
#include <bitset>

namespace markerbench {
namespace {

constexpr int kFieldOrder = 63;        // GF(2^6)^*
constexpr int kPrimitive = 0b1000011;  // x^6 + x + 1
constexpr int kCodeLength = 36;
constexpr int kParityBits = 24;
constexpr int kDesignedDistance = 2 * kBchCorrectableBits + 1;

// GF(2^6) in exponent/log form: exp_[i] = alpha^i (i < 126 so products need no modulo).
struct GaloisField64 {
  std::array<int, 2 * kFieldOrder> exp{};
  std::array<int, kFieldOrder + 1> log{};

  GaloisField64() {
    int a = 1;
    for (int i = 0; i < kFieldOrder; ++i) {
      exp[i] = exp[i + kFieldOrder] = a;
      log[a] = i;
      a <<= 1;
      if (a & 64) a ^= kPrimitive;
    }
  }
  int Mul(int a, int b) const { return a && b ? exp[log[a] + log[b]] : 0; }
  int Div(int a, int b) const { return a ? exp[log[a] - log[b] + kFieldOrder] : 0; }
  int Pow(int i) const { return exp[((i % kFieldOrder) + kFieldOrder) % kFieldOrder]; }
};

const GaloisField64& Field() {
  static const GaloisField64 field;
  return field;
}

// Product of two GF(2) polynomials (bit i = coefficient of x^i).
uint64_t MultiplyBinary(uint64_t a, uint64_t b) {
  uint64_t product = 0;
  for (; b; b >>= 1, a <<= 1) {
    if (b & 1) product ^= a;
  }
  return product;
}

int Degree(uint64_t p) { return 63 - __builtin_clzll(p); }

// Minimal polynomial of alpha^i: the product of (x + alpha^j) over its cyclotomic coset.
uint64_t MinimalPolynomial(int i) {
  const GaloisField64& f = Field();
  std::array<int, 7> coeffs{1};  // over GF(64), low degree first
  int degree = 0;
  int j = i;
  do {
    for (int k = degree + 1; k >= 1; --k) coeffs[k] = coeffs[k - 1] ^ f.Mul(coeffs[k], f.Pow(j));
    coeffs[0] = f.Mul(coeffs[0], f.Pow(j));
    ++degree;
    j = 2 * j % kFieldOrder;
  } while (j != i % kFieldOrder);
  uint64_t binary = 0;  // the coefficients of a minimal polynomial lie in GF(2)
  for (int k = 0; k <= degree; ++k) binary |= static_cast<uint64_t>(coeffs[k] & 1) << k;
  return binary;
}

uint64_t ComputeGenerator() {
  uint64_t g = 1;
  std::array<bool, kFieldOrder> in_coset{};
  for (int i = 1; i < kDesignedDistance; ++i) {
    if (in_coset[i]) continue;
    for (int j = i; !in_coset[j]; j = 2 * j % kFieldOrder) in_coset[j] = true;
    g = MultiplyBinary(g, MinimalPolynomial(i));
  }
  return g;
}

uint64_t Remainder(uint64_t a, uint64_t m) {
  const int dm = Degree(m);
  while (a && Degree(a) >= dm) a ^= m << (Degree(a) - dm);
  return a;
}

}  // namespace

uint64_t BchGenerator() {
  static const uint64_t g = ComputeGenerator();
  return g;
}

uint64_t BchEncode(int id) {
  const uint64_t data = static_cast<uint64_t>(id) << kParityBits;
  return (data | Remainder(data, BchGenerator())) ^ kBchMask;
}

std::optional<DecodedId> BchDecode(uint64_t word) {
  const GaloisField64& f = Field();
  uint64_t r = (word ^ kBchMask) & ((1ULL << kCodeLength) - 1);
  // Syndromes S_j = r(alpha^j), j = 1..2t.
  std::array<int, kDesignedDistance> s{};
  bool clean = true;
  for (int j = 1; j < kDesignedDistance; ++j) {
    for (int i = 0; i < kCodeLength; ++i) {
      if ((r >> i) & 1) s[j] ^= f.Pow(i * j);
    }
    clean = clean && s[j] == 0;
  }
  if (clean) return DecodedId{static_cast<int>(r >> kParityBits), 0};

  // Berlekamp-Massey: the error locator lambda(x) of degree L.
  std::array<int, kDesignedDistance> lambda{1}, previous{1};
  int L = 0, shift = 1, previous_discrepancy = 1;
  for (int n = 1; n < kDesignedDistance; ++n) {
    int d = s[n];
    for (int i = 1; i <= L; ++i) d ^= f.Mul(lambda[i], s[n - i]);
    if (d == 0) {
      ++shift;
      continue;
    }
    const std::array<int, kDesignedDistance> before = lambda;
    const int scale = f.Div(d, previous_discrepancy);
    for (int i = shift; i < kDesignedDistance; ++i) lambda[i] ^= f.Mul(scale, previous[i - shift]);
    if (2 * L <= n - 1) {
      L = n - L;
      previous = before;
      previous_discrepancy = d;
      shift = 1;
    } else {
      ++shift;
    }
  }
  if (L > kBchCorrectableBits) return std::nullopt;

  // Chien search: position i is in error when lambda(alpha^-i) = 0.
  int roots = 0;
  for (int i = 0; i < kFieldOrder; ++i) {
    int value = 0;
    for (int k = 0; k <= L; ++k) value ^= f.Mul(lambda[k], f.Pow(-i * k));
    if (value != 0) continue;
    if (i >= kCodeLength) return std::nullopt;  // an error in a shortened-away position
    r ^= 1ULL << i;
    ++roots;
  }
  if (roots != L) return std::nullopt;
  return DecodedId{static_cast<int>(r >> kParityBits), L};
}

}  // namespace markerbench
