// GF(7^6) = GF(7)[x] / (x^6 + 6x^5 + 2x^3 + 6x + 1), the field of the original RUNETag's
// code (Bergamasco et al.; core/codes/runetag_cyclic_code.h). An element is the integer
// Σ c_k 7^k of its coefficients c_k (of x^k), so GF(7) is the elements 0..6.
#pragma once

#include <cstdint>
#include <vector>

namespace markerbench {

class Gf76 {
 public:
  using Element = uint32_t;
  static constexpr Element kSize = 117649;  // 7^6

  static const Gf76& Get();  // built once: log and antilog tables of a primitive element

  static Element Add(Element a, Element b);
  static Element Negate(Element a);
  static Element Subtract(Element a, Element b) { return Add(a, Negate(b)); }
  Element Multiply(Element a, Element b) const;
  Element Inverse(Element a) const;  // a != 0
  Element Power(Element a, int64_t n) const;

  // The product of two polynomials in x reduced modulo the field polynomial: the slow
  // multiplication the tables are built from (tested against them).
  static Element MultiplyByPolynomials(Element a, Element b);

 private:
  Gf76();
  std::vector<Element> antilog_;  // antilog_[k] = g^k, k < kSize - 1
  std::vector<uint32_t> log_;     // log_[g^k] = k
};

}  // namespace markerbench
