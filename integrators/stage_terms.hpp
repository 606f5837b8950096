#pragma once
// A tableau's non-zero stage terms, as every tableau stepper sums them in its
// one stage loop, fixed steps and embedded pairs alike: the rk family's
// (rk_stepper.hpp), the RKMK ones (families/rkmk/) and the exponential
// products' (exp_product_stepper.hpp). The one stage-sum type.
#include <array>
#include <cstddef>
#include <type_traits>
#include <utility>

#include "integrators/tableau.hpp"

namespace rb {

// The patterns of non-zero terms of a fixed step's rows, known at compile
// time (a stage shape): bit j of row i set where a_ij != 0, rows 1..S-1 of
// A and b as row S, 4 bits a row (row i at bits 4 (i - 1)); S <= 4. A step
// of known shape sums each row by its own pattern, with no choice among
// the 2^J sums of StageTerms::Row::sum_first at every stage (callgrind,
// rkmk4: 3142 -> 3085 instructions a step, docs/performance-history.md, seventh
// pass).
// kRuntimeShape: the patterns are read at run time.
using StageShape = unsigned;
inline constexpr StageShape kRuntimeShape = 0;
// row i's pattern in a shape; kAnyPattern for kRuntimeShape
inline constexpr unsigned kAnyPattern = ~0u;
constexpr unsigned shape_row(StageShape shape, int i) {
  return shape == kRuntimeShape ? kAnyPattern : (shape >> (4 * (i - 1))) & 15u;
}
// Each stage from the one before (a_i,i-1 only: classical RK4, Heun), b full.
constexpr StageShape chain_shape(int stages) {
  StageShape shape = 0;
  for (int i = 1; i < stages; ++i) shape |= (1u << (i - 1)) << (4 * (i - 1));
  return shape | ((1u << stages) - 1u) << (4 * (stages - 1));
}
// Every a_ij (j < i) and b_j non-zero (Kutta's third order, the 3/8 rule).
constexpr StageShape dense_shape(int stages) {
  StageShape shape = 0;
  for (int i = 1; i <= stages; ++i) shape |= ((1u << i) - 1u) << (4 * (i - 1));
  return shape;
}

// A tableau's non-zero coefficients, gathered once per run so that the step
// loops of the tableau steppers (rk_stepper.hpp, rkmk_stepper.hpp) skip the
// zeros without testing them and read no std::vector in the step.
struct StageTerms {
  struct Row {
    int count = 0;                              // non-zero terms
    std::array<int, kMaxStages> index{};        // j of each term, increasing
    std::array<double, kMaxStages> coeff{};     // a_ij (or b_j) of each term
    std::array<double, kMaxStages> by_stage{};  // a_ij (or b_j) by j, 0 where there is no term
    unsigned pattern = 0;                       // bit j set: a term at j (j < kMaxStages = 32)
    Row() = default;
    // the non-zero ones of the first count weights w[0..count)
    Row(const double* w, int count) {
      for (int j = 0; j < count; ++j) add(j, w[j]);
    }
    void add(int j, double value) {
      if (value == 0.0) return;
      index[static_cast<std::size_t>(count)] = j;
      coeff[static_cast<std::size_t>(count)] = value;
      by_stage[static_cast<std::size_t>(j)] = value;
      pattern |= 1u << j;
      ++count;
    }
    // out = base + h c_0 k[j_0] + h c_1 k[j_1] + ...: for up to four terms
    // one pass over the vector with the sums in registers, instead of one
    // pass per term through memory; the same additions in the same order.
    // out must not be one of the k. Inlined: a call would pass the sum
    // through memory once more. The Lie view's short vectors (z, u: 5 and
    // 3 numbers) are summed entry by entry, which GCC keeps inline; for
    // the flat view's 14 Eigen's packets do better (callgrind: rkmk4 -64
    // instructions a step, rk4 +137 had it been written out too).
    template <class V, class K>
    [[gnu::always_inline]] void sum(V& out, const V& base, double h, const K& k) const {
      if constexpr (V::SizeAtCompileTime <= kShortVector) {
        scalar_sum<true>(out, &base, h, k);
        return;
      }
      const auto term = [&](std::size_t n) { return (h * coeff[n]) * k[static_cast<std::size_t>(index[n])]; };
      switch (count) {
        case 0: out = base; break;
        case 1: out.noalias() = base + term(0); break;
        case 2: out.noalias() = base + term(0) + term(1); break;
        case 3: out.noalias() = base + term(0) + term(1) + term(2); break;
        default:
          out.noalias() = base + term(0) + term(1) + term(2) + term(3);
          for (std::size_t n = 4; n < static_cast<std::size_t>(count); ++n) out += term(n);
      }
    }
    // The same without a base: h c_0 k[j_0] + h c_1 k[j_1] + ... (0 if none).
    template <class V, class K>
    [[gnu::always_inline]] void sum(V& out, double h, const K& k) const {
      if constexpr (V::SizeAtCompileTime <= kShortVector) {
        scalar_sum<false>(out, static_cast<const V*>(nullptr), h, k);
        return;
      }
      const auto term = [&](std::size_t n) { return (h * coeff[n]) * k[static_cast<std::size_t>(index[n])]; };
      switch (count) {
        case 0: out.setZero(); break;
        case 1: out.noalias() = term(0); break;
        case 2: out.noalias() = term(0) + term(1); break;
        case 3: out.noalias() = term(0) + term(1) + term(2); break;
        default:
          out.noalias() = term(0) + term(1) + term(2) + term(3);
          for (std::size_t n = 4; n < static_cast<std::size_t>(count); ++n) out += term(n);
      }
    }

    // The same two sums over the stages j < J, J known at compile time (a
    // fixed step's unrolled stage loop, k local to the step): the same
    // terms added in the same order, each k_j addressed at compile time, so
    // that the stages' derivatives stay in registers. Summed through memory
    // at run-time indices, each stage reloaded what the one before had just
    // stored, in wider loads than its stores, which the CPU cannot forward
    // (docs/performance-history.md, "rkmk4 at the limit").
    // Pattern: the row's pattern where the caller knows it at compile time
    // (a StageShape's row, which the row's own must be), else kAnyPattern.
    template <int J, unsigned Pattern = kAnyPattern, class V, class K>
    [[gnu::always_inline]] void sum_first(V& out, const V& base, double h, const K& k) const {
      first_terms<J, Pattern, true>(out, &base, h, k);
    }
    template <int J, unsigned Pattern = kAnyPattern, class V, class K>
    [[gnu::always_inline]] void sum_first(V& out, double h, const K& k) const {
      first_terms<J, Pattern, false>(out, static_cast<const V*>(nullptr), h, k);
    }
    // Stage i's sums over the stages before it: sum where i is known at
    // run time, sum_first<i> where it is a compile-time constant
    // (std::integral_constant: a fixed step's unrolled stages), by its row
    // of Shape.
    template <StageShape Shape = kRuntimeShape, class Index, class V, class K>
    [[gnu::always_inline]] void sum_before(Index /*i*/, V& out, const V& base, double h, const K& k) const {
      if constexpr (std::is_integral_v<Index>) sum(out, base, h, k);
      else sum_first<Index::value, shape_row(Shape, Index::value)>(out, base, h, k);
    }
    template <StageShape Shape = kRuntimeShape, class Index, class V, class K>
    [[gnu::always_inline]] void sum_before(Index /*i*/, V& out, double h, const K& k) const {
      if constexpr (std::is_integral_v<Index>) sum(out, h, k);
      else sum_first<Index::value, shape_row(Shape, Index::value)>(out, h, k);
    }

   private:
    static constexpr int kShortVector = 5;
    // sum_first: (base + t_0) + t_1 + ... over the non-zero terms, or
    // t_0 + t_1 + ... (0 if none) without a base, as scalar_sum adds them.
    // The row's pattern of non-zero terms (bit j: a term at stage j) picks
    // one of the 2^J sums, each with its terms at compile time; a Pattern
    // known at compile time is that sum, with no choice.
    template <int J, unsigned Pattern, bool Base, class V, class K>
    [[gnu::always_inline]] void first_terms(V& out, const V* base, double h, const K& k) const {
      static_assert(J <= 4, "sum_first unrolls up to four stages (2^J sums)");
      constexpr unsigned all = (1u << J) - 1u;
      if constexpr (Pattern != kAnyPattern) {
        static_assert((Pattern & ~all) == 0u, "a pattern of terms beyond the first J stages");
        pattern_terms<Pattern, J, Base>(out, base, h, k);
      } else {
        const unsigned p = pattern & all;  // the terms are at j < J: p is pattern
        [&]<unsigned... m>(std::integer_sequence<unsigned, m...>) __attribute__((always_inline)) {
          if (!((p == m ? (pattern_terms<m, J, Base>(out, base, h, k), true) : false) || ...))
            pattern_terms<all, J, Base>(out, base, h, k);
        }
        (std::make_integer_sequence<unsigned, all>{});
      }
    }
    template <unsigned Pattern, int J, bool Base, class V, class K>
    [[gnu::always_inline]] void pattern_terms(V& out, const V* base, double h, const K& k) const {
      // the row read once, before anything is stored (out might alias it)
      double c[J > 0 ? J : 1];
      for (int j = 0; j < J; ++j) c[j] = h * by_stage[static_cast<std::size_t>(j)];
      for (int e = 0; e < V::SizeAtCompileTime; ++e) {
        double s = Base ? base->data()[e] : 0.0;
        bool started = Base;
        [&]<std::size_t... j>(std::index_sequence<j...>) __attribute__((always_inline)) {
          const auto add = [&](std::size_t n) __attribute__((always_inline)) {
            const double t = c[n] * k[n].data()[e];
            s = started ? s + t : t;
            started = true;
          };
          ((Pattern >> j & 1u ? add(j) : void()), ...);
        }
        (std::make_index_sequence<J>{});
        out.data()[e] = s;
      }
    }
    // the same sums entry by entry, in the same order: (base + t_0) + t_1 + ...
    template <bool Base, class V, class K>
    [[gnu::always_inline]] void scalar_sum(V& out, const V* base, double h, const K& k) const {
      switch (count) {
        case 0:
          if constexpr (Base) out = *base;
          else out.setZero();
          break;
        case 1: terms<1, Base>(out, base, h, k); break;
        case 2: terms<2, Base>(out, base, h, k); break;
        case 3: terms<3, Base>(out, base, h, k); break;
        case 4: terms<4, Base>(out, base, h, k); break;
        default: long_sum<Base>(out, base, h, k);
      }
    }
    // The embedded pairs' longer rows (verner7: up to 9 terms) unrolled as
    // well, apart so that the short rows' dispatch stays as it is
    // (callgrind, chaplygin-bumpy-long at 1e-9: rkmk-verner7-adaptive -13 %,
    // rkmk-dp54-adaptive -10 % a step; the same sums in the same order).
    template <bool Base, class V, class K>
    [[gnu::always_inline]] void long_sum(V& out, const V* base, double h, const K& k) const {
      switch (count) {
        case 5: terms<5, Base>(out, base, h, k); break;
        case 6: terms<6, Base>(out, base, h, k); break;
        case 7: terms<7, Base>(out, base, h, k); break;
        case 8: terms<8, Base>(out, base, h, k); break;
        case 9: terms<9, Base>(out, base, h, k); break;
        default: terms<0, Base>(out, base, h, k);
      }
    }
    // C terms (0: count of them)
    template <int C, bool Base, class V, class K>
    [[gnu::always_inline]] void terms(V& out, const V* base, double h, const K& k) const {
      constexpr int size = V::SizeAtCompileTime;
      const int n_terms = C > 0 ? C : count;
      const double* kp[kMaxStages];
      double c[kMaxStages];
      for (int m = 0; m < n_terms; ++m) {
        kp[m] = k[static_cast<std::size_t>(index[static_cast<std::size_t>(m)])].data();
        c[m] = h * coeff[static_cast<std::size_t>(m)];
      }
      double* o = out.data();
      for (int e = 0; e < size; ++e) {
        double s = Base ? base->data()[e] + c[0] * kp[0][e] : c[0] * kp[0][e];
        for (int m = 1; m < n_terms; ++m) s += c[m] * kp[m][e];
        o[e] = s;
      }
    }
  };
  // A tableau's terms for every stage a step may evaluate: the rows of A up
  // to total_stages() (the attempt's and the dense output's), b, and the
  // error weights e and e_stretched (count 0 without them).
  int stages;                     // propagating: a fixed step's
  int attempt;                    // an adaptive attempt's (stages without an error estimate)
  std::array<Row, kMaxStages> a;  // row i: the terms of stage i
  Row b, e, e3;

  explicit StageTerms(const Tableau& tableau) : stages(tableau.stages()), attempt(tableau.attempt_stages()) {
    const int total = tableau.total_stages();
    for (int i = 0; i < total; ++i)
      a[static_cast<std::size_t>(i)] = Row(&tableau.a_row_major()[static_cast<std::size_t>(i * total)], i);
    // b_j = 0 past stages(): the same terms over either count
    b = Row(tableau.b_weights().data(), stages);
    if (!tableau.e().empty()) e = Row(tableau.e().data(), attempt);
    if (!tableau.e_stretched().empty()) e3 = Row(tableau.e_stretched().data(), attempt);
  }

  // The shape of a fixed step of s <= 4 stages: rows 1..s-1 and b.
  StageShape shape(int s) const {
    StageShape packed = 0;
    for (int i = 1; i <= s; ++i) {
      const Row& row = i < s ? a[static_cast<std::size_t>(i)] : b;
      packed |= row.pattern << (4 * (i - 1));
    }
    return packed;
  }
};

}  // namespace rb
