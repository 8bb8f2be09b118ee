#include "core/codes/runetag_cyclic_code.h"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>

#include "core/codes/gf7_6.h"

namespace markerbench {
namespace {

using Element = Gf76::Element;
using Values = std::array<int, kRuneSectors>;  // symbol values 0..6, -1 erased

constexpr int kFirstZero = 8, kZeros = 28;  // the consecutive zeros w^8..w^35
// w = x^5 + 4x^4 + 5x^2 + 6x as the integer Σ c_k 7^k.
constexpr Element kW = 6 * 7 + 5 * 49 + 4 * 2401 + 1 * 16807;

// Alignment over GF(173) (173 = 4 · 43 + 1): 2 generates its multiplicative group, so
// ω = 2^4 has order 43.
constexpr int kAlignPrime = 173;

struct AlignTables {
  std::array<int, kAlignPrime - 1> power{};  // 2^k
  std::array<int, kAlignPrime> log{};        // log_2
  AlignTables() {
    int a = 1;
    for (int k = 0; k < kAlignPrime - 1; ++k, a = 2 * a % kAlignPrime) {
      power[k] = a;
      log[a] = k;
    }
  }
};

const AlignTables& Align() {
  static const AlignTables tables;
  return tables;
}

// The canonical rotation r of a word (its rotation a_j = c_(j + r) has Fourier coefficient
// 2^k with k < 4), or nullopt for a constant word (coefficient 0).
std::optional<int> CanonicalRotation(const Values& c) {
  const AlignTables& t = Align();
  int coefficient = 0;
  for (int j = 0; j < kRuneSectors; ++j) {
    coefficient = (coefficient + t.power[(4 * j) % (kAlignPrime - 1)] * c[j]) % kAlignPrime;
  }
  if (coefficient == 0) return std::nullopt;
  return t.log[coefficient] / 4;  // rotating by r divides the coefficient by ω^r = 2^(4r)
}

Values Rotate(const Values& c, int r) {
  Values a;
  for (int j = 0; j < kRuneSectors; ++j) a[j] = c[(j + r) % kRuneSectors];
  return a;
}

// d0..d5 of c / g(x) as a base-7 number (d0 least significant).
int IndexOf(const Values& c) {
  const std::array<int, 37>& g = RuneGenerator();  // g0 = 1
  std::array<int, 6> d{};
  for (int k = 0; k < 6; ++k) {
    int v = c[k];
    for (int j = 0; j < k; ++j) v -= d[j] * g[k - j];
    d[k] = ((v % 7) + 7) % 7;
  }
  int index = 0;
  for (int k = 5; k >= 0; --k) index = 7 * index + d[k];
  return index;
}

RuneWord Printed(const Values& c) {
  RuneWord word;
  for (int i = 0; i < kRuneSectors; ++i) word[i] = static_cast<uint8_t>(c[i] + 1);
  return word;
}

struct Dictionary {
  std::map<int, RuneWord> words;
  std::vector<int> ids;
};

// The original's code list (its codegen): see the header.
Dictionary BuildDictionary() {
  const std::array<int, 37>& g = RuneGenerator();
  Dictionary dictionary;
  for (int message = 0; static_cast<int>(dictionary.words.size()) < kRuneIdCount; ++message) {
    if (message >= 117649) throw std::logic_error("RUNETag: too few codewords");
    Values c{};
    int digits = message;
    for (int shift = 0; digits > 0; ++shift, digits /= 7) {
      for (int i = 0; i < 37; ++i) c[shift + i] = (c[shift + i] + (digits % 7) * g[i]) % 7;
    }
    const std::optional<int> rotation = CanonicalRotation(c);
    if (!rotation) continue;
    const Values aligned = Rotate(c, *rotation);
    dictionary.words[IndexOf(aligned)] = Printed(aligned);
  }
  for (const auto& [id, word] : dictionary.words) dictionary.ids.push_back(id);
  return dictionary;
}

const Dictionary& TheDictionary() {
  static const Dictionary dictionary = BuildDictionary();
  return dictionary;
}

// Polynomials over GF(7^6), x^0 first.
using Polynomial = std::vector<Element>;

Element Evaluate(const Polynomial& p, Element x) {
  const Gf76& f = Gf76::Get();
  Element value = 0;
  for (auto it = p.rbegin(); it != p.rend(); ++it) value = Gf76::Add(f.Multiply(value, x), *it);
  return value;
}

Polynomial Multiply(const Polynomial& a, const Polynomial& b, size_t max_terms) {
  const Gf76& f = Gf76::Get();
  Polynomial product(std::min(a.size() + b.size() - 1, max_terms), 0);
  for (size_t i = 0; i < a.size(); ++i) {
    for (size_t j = 0; j < b.size() && i + j < product.size(); ++j) {
      product[i + j] = Gf76::Add(product[i + j], f.Multiply(a[i], b[j]));
    }
  }
  return product;
}

// S_j = c(w^(8 + j)), j < 28, of a word of symbol values (erased ones, -1, count as 0): all
// zero exactly for a codeword.
Polynomial Syndromes(const Values& c) {
  const Gf76& f = Gf76::Get();
  Polynomial syndromes(kZeros, 0);
  for (int j = 0; j < kZeros; ++j) {
    for (int i = 0; i < kRuneSectors; ++i) {
      if (c[i] <= 0) continue;
      syndromes[j] = Gf76::Add(
          syndromes[j], f.Multiply(static_cast<Element>(c[i]), f.Power(kW, i * (kFirstZero + j))));
    }
  }
  return syndromes;
}

bool AllZero(const Polynomial& p) {
  return std::all_of(p.begin(), p.end(), [](Element e) { return e == 0; });
}

// The codeword nearest to `received` within 2 × errors + erasures ≤ kZeros, or nullopt.
std::optional<Values> Correct(const Values& received) {
  const Gf76& f = Gf76::Get();
  int erasures = 0;
  Polynomial erasure_locator = {1};  // Γ(x) = Π (1 - X_l x), X_l = w^l
  for (int i = 0; i < kRuneSectors; ++i) {
    if (received[i] >= 0) continue;
    ++erasures;
    erasure_locator = Multiply(erasure_locator, {1, Gf76::Negate(f.Power(kW, i))}, 64);
  }
  if (erasures > kZeros) return std::nullopt;
  const Polynomial syndromes = Syndromes(received);
  Values corrected = received;
  for (int& v : corrected) v = std::max(v, 0);
  if (erasures == 0 && AllZero(syndromes)) return corrected;
  // Berlekamp-Massey on the erasure-modified (Forney) syndromes T_j, j >= erasures.
  const Polynomial modified = Multiply(syndromes, erasure_locator, kZeros);
  Polynomial locator = {1}, previous = {1};
  int length = 0, gap = 1;
  Element previous_discrepancy = 1;
  for (int n = 0; n + erasures < kZeros; ++n) {
    Element discrepancy = modified[n + erasures];
    for (int i = 1; i <= length && i < static_cast<int>(locator.size()); ++i) {
      discrepancy = Gf76::Add(discrepancy, f.Multiply(locator[i], modified[n + erasures - i]));
    }
    if (discrepancy == 0) {
      ++gap;
      continue;
    }
    const Element scale = f.Multiply(discrepancy, f.Inverse(previous_discrepancy));
    Polynomial updated = locator;
    updated.resize(std::max(locator.size(), previous.size() + gap), 0);
    for (size_t i = 0; i < previous.size(); ++i) {
      updated[i + gap] = Gf76::Subtract(updated[i + gap], f.Multiply(scale, previous[i]));
    }
    if (2 * length <= n) {
      previous = locator;
      length = n + 1 - length;
      previous_discrepancy = discrepancy;
      gap = 1;
    } else {
      ++gap;
    }
    locator = updated;
  }
  if (2 * length + erasures > kZeros) return std::nullopt;
  // Ψ = ΛΓ locates errors and erasures; Ω = SΨ mod x^28 gives their magnitudes (Forney):
  // e_i = -X_i^(1 - 8) Ω(X_i^-1) / Ψ'(X_i^-1).
  const Polynomial both = Multiply(locator, erasure_locator, 64);
  const Polynomial evaluator = Multiply(syndromes, both, kZeros);
  Polynomial derivative;
  for (size_t k = 1; k < both.size(); ++k) {
    Element term = 0;
    for (size_t m = 0; m < k % 7; ++m) term = Gf76::Add(term, both[k]);  // k · coefficient
    derivative.push_back(term);
  }
  int roots = 0;
  for (int i = 0; i < kRuneSectors; ++i) {
    const Element x_inverse = f.Power(kW, -i);
    if (Evaluate(both, x_inverse) != 0) continue;
    ++roots;
    const Element denominator = Evaluate(derivative, x_inverse);
    if (denominator == 0) return std::nullopt;
    const Element magnitude = Gf76::Negate(
        f.Multiply(f.Multiply(f.Power(kW, i * (1 - kFirstZero)), Evaluate(evaluator, x_inverse)),
                   f.Inverse(denominator)));
    if (magnitude >= 7) return std::nullopt;  // not in GF(7): no codeword within reach
    corrected[i] = (corrected[i] + 7 - static_cast<int>(magnitude)) % 7;
  }
  const size_t degree =
      both.size() - 1 -
      static_cast<size_t>(
          std::find_if(both.rbegin(), both.rend(), [](Element e) { return e != 0; }) -
          both.rbegin());
  if (roots != static_cast<int>(degree)) return std::nullopt;
  if (!AllZero(Syndromes(corrected))) return std::nullopt;  // the result must be a codeword
  return corrected;
}

}  // namespace

const std::array<int, 37>& RuneGenerator() {
  static const std::array<int, 37> generator = [] {
    const Gf76& f = Gf76::Get();
    std::vector<bool> zero(kRuneSectors, false);  // the cyclotomic cosets of 8..35 under ×7
    for (int i = kFirstZero; i < kFirstZero + kZeros; ++i) {
      for (int j = i, k = 0; k < 6; ++k, j = j * 7 % kRuneSectors) zero[j] = true;
    }
    Polynomial g = {1};
    for (int i = 0; i < kRuneSectors; ++i) {
      if (zero[i]) g = Multiply(g, {Gf76::Negate(f.Power(kW, i)), 1}, 64);
    }
    if (g.size() != 37)
      throw std::logic_error("RUNETag: generator degree " + std::to_string(g.size() - 1));
    std::array<int, 37> coefficients;
    for (size_t k = 0; k < g.size(); ++k) {
      if (g[k] >= 7) throw std::logic_error("RUNETag: generator not over GF(7)");
      coefficients[k] = static_cast<int>(g[k]);
    }
    return coefficients;
  }();
  return generator;
}

bool IsRuneId(int id) { return TheDictionary().words.count(id) > 0; }

const std::vector<int>& RuneIds() { return TheDictionary().ids; }

const RuneWord& RuneCodeword(int id) {
  const auto found = TheDictionary().words.find(id);
  if (found == TheDictionary().words.end()) {
    throw std::out_of_range("RUNETag: no marker with id " + std::to_string(id));
  }
  return found->second;
}

std::optional<RuneDecoded> RuneDecode(const RuneWord& read) {
  Values received;
  for (int i = 0; i < kRuneSectors; ++i) received[i] = read[i] == 0 ? -1 : read[i] - 1;
  const std::optional<Values> corrected = Correct(received);
  if (!corrected) return std::nullopt;
  const std::optional<int> rotation = CanonicalRotation(*corrected);
  if (!rotation) return std::nullopt;
  const Values aligned = Rotate(*corrected, *rotation);
  const int id = IndexOf(aligned);
  if (!IsRuneId(id) || RuneCodeword(id) != Printed(aligned)) return std::nullopt;
  RuneDecoded decoded{id, (kRuneSectors - *rotation) % kRuneSectors, 0, 0};
  for (int i = 0; i < kRuneSectors; ++i) {
    if (received[i] < 0) {
      ++decoded.erasures;
    } else if (received[i] != (*corrected)[i]) {
      ++decoded.mismatches;
    }
  }
  return decoded;
}

std::optional<RuneDecoded> RuneDecodeMissingDots(const RuneWord& read, int id) {
  const RuneWord& word = RuneCodeword(id);
  constexpr int kLimit = (kRuneMinDistance - 1) / 2;
  for (int rotation = 0; rotation < kRuneSectors; ++rotation) {
    int lost = 0, added = 0;
    for (int i = 0; i < kRuneSectors; ++i) {
      const int expected = word[(i + rotation) % kRuneSectors];
      lost += __builtin_popcount(expected & ~read[i]);
      added += __builtin_popcount(read[i] & ~expected);
    }
    if (lost + 2 * added <= kLimit) return RuneDecoded{id, rotation, added, lost};
  }
  return std::nullopt;
}

}  // namespace markerbench
