#include "core/codes/gf7_6.h"

#include <array>
#include <stdexcept>

namespace markerbench {
namespace {

using Digits = std::array<int, 6>;

Digits DigitsOf(Gf76::Element a) {
  Digits d{};
  for (int k = 0; k < 6; ++k, a /= 7) d[k] = static_cast<int>(a % 7);
  return d;
}

Gf76::Element ElementOf(const Digits& d) {
  Gf76::Element a = 0;
  for (int k = 5; k >= 0; --k) a = 7 * a + static_cast<Gf76::Element>(d[k]);
  return a;
}

// x^6 + 6x^5 + 2x^3 + 6x + 1: the coefficients of x^0..x^5 (x^6's is 1).
constexpr Digits kFieldPolynomial = {1, 6, 0, 2, 0, 6};

}  // namespace

Gf76::Element Gf76::Add(Element a, Element b) {
  const Digits x = DigitsOf(a), y = DigitsOf(b);
  Digits sum;
  for (int k = 0; k < 6; ++k) sum[k] = (x[k] + y[k]) % 7;
  return ElementOf(sum);
}

Gf76::Element Gf76::Negate(Element a) {
  Digits d = DigitsOf(a);
  for (int& c : d) c = (7 - c) % 7;
  return ElementOf(d);
}

Gf76::Element Gf76::MultiplyByPolynomials(Element a, Element b) {
  const Digits x = DigitsOf(a), y = DigitsOf(b);
  std::array<int, 11> product{};
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) product[i + j] = (product[i + j] + x[i] * y[j]) % 7;
  }
  for (int k = 10; k >= 6; --k) {  // x^k = x^(k-6) * (-(the field polynomial's lower terms))
    const int c = product[k];
    product[k] = 0;
    for (int t = 0; t < 6; ++t)
      product[k - 6 + t] = (product[k - 6 + t] + 7 * 7 - c * kFieldPolynomial[t]) % 7;
  }
  return ElementOf({product[0], product[1], product[2], product[3], product[4], product[5]});
}

Gf76::Gf76() : antilog_(kSize - 1), log_(kSize, 0) {
  // The first element, in integer order, whose powers run through the whole group.
  for (Element generator = 2; generator < kSize; ++generator) {
    Element power = 1;
    size_t k = 0;
    for (; k < antilog_.size(); ++k) {
      if (k > 0 && power == 1) break;
      antilog_[k] = power;
      power = MultiplyByPolynomials(power, generator);
    }
    if (k == antilog_.size() && power == 1) {
      for (size_t i = 0; i < antilog_.size(); ++i) log_[antilog_[i]] = static_cast<uint32_t>(i);
      return;
    }
  }
  throw std::logic_error("GF(7^6): no primitive element");
}

const Gf76& Gf76::Get() {
  static const Gf76 field;
  return field;
}

Gf76::Element Gf76::Multiply(Element a, Element b) const {
  if (a == 0 || b == 0) return 0;
  return antilog_[(log_[a] + log_[b]) % (kSize - 1)];
}

Gf76::Element Gf76::Inverse(Element a) const {
  return antilog_[(kSize - 1 - log_[a]) % (kSize - 1)];
}

Gf76::Element Gf76::Power(Element a, int64_t n) const {
  if (a == 0) return n == 0 ? 1 : 0;
  const int64_t order = kSize - 1;
  const int64_t k = ((static_cast<int64_t>(log_[a]) * (n % order)) % order + order) % order;
  return antilog_[static_cast<size_t>(k)];
}

}  // namespace markerbench
