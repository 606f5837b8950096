// The embedded pairs' shared parts: the try/accept skeleton (when the first
// stage is evaluated), the error norm against its closed form, and the one
// stage-sum type's sums over the non-zero terms only.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "integrators/methods/kutta3.hpp"
#include "integrators/methods/rk38.hpp"
#include "integrators/methods/rk4.hpp"
#include "integrators/stage_terms.hpp"
#include "integrators/steppers/embedded_pair.hpp"
#include "integrators/steppers/error_norm.hpp"

namespace rb {
namespace {

// A pair that records what the skeleton asks of it.
class CountingPair : public EmbeddedPair<CountingPair> {
 public:
  int first_stages = 0, attempts = 0, commits = 0, backs = 0;
  bool fsal = false;   // commit has the next first stage
  bool finite = true;  // the next attempt's step is finite
  double error = 0.5;  // the next attempt's error norm
  void first_stage(Cost& cost) {
    ++first_stages;
    ++cost.rhs_evals;
  }
  double attempt(double, Cost&) {
    ++attempts;
    return error;
  }
  bool tried_finite() const { return finite; }
  bool commit(double, double, Cost&) {
    ++commits;
    return fsal;
  }
  void go_back(const FlatState&) { ++backs; }
};

TEST(EmbeddedPair, TheFirstStageIsEvaluatedOnceUntilAStepIsAccepted) {
  CountingPair pair;
  Cost cost;
  EXPECT_EQ(pair.try_step(0.0, 0.1, cost), 0.5);
  EXPECT_EQ(pair.try_step(0.0, 0.05, cost), 0.5);  // a rejected attempt's retry reuses it
  EXPECT_EQ(pair.first_stages, 1);
  EXPECT_EQ(pair.attempts, 2);
  pair.accept(0.0, 0.05, cost);
  pair.try_step(0.05, 0.05, cost);
  EXPECT_EQ(pair.first_stages, 2);  // no FSAL: evaluated again at the new state
  EXPECT_EQ(cost.rhs_evals, 2);
}

TEST(EmbeddedPair, AnFsalPairSkipsTheFirstStageAfterAcceptingButNotAfterGoingBack) {
  CountingPair pair;
  pair.fsal = true;
  Cost cost;
  pair.try_step(0.0, 0.1, cost);
  pair.accept(0.0, 0.1, cost);
  pair.try_step(0.1, 0.1, cost);
  EXPECT_EQ(pair.first_stages, 1);
  pair.restore(FlatState::Zero());
  EXPECT_EQ(pair.backs, 1);
  pair.try_step(0.1, 0.1, cost);
  EXPECT_EQ(pair.first_stages, 2);
}

TEST(EmbeddedPair, AStepThatIsNotFiniteHasNoErrorNorm) {
  CountingPair pair;
  Cost cost;
  pair.finite = false;
  EXPECT_TRUE(std::isnan(pair.try_step(0.0, 0.1, cost)));
  pair.finite = true;
  pair.error = std::numeric_limits<double>::infinity();  // the norm's own overflow is the controller's to see
  EXPECT_TRUE(std::isinf(pair.try_step(0.0, 0.1, cost)));
}

TEST(ErrorNorm, IsTheRootMeanSquareOfEachComponentAgainstItsOwnScale) {
  const Tolerances tol(0.5, 0.25);
  using V = Eigen::Vector3d;
  const V y(1.0, -2.0, 0.0), y_new(-3.0, 1.0, 0.0);
  const V scale = value_scale(tol, y, y_new);
  EXPECT_EQ(scale, V(0.25 + 0.5 * 3.0, 0.25 + 0.5 * 2.0, 0.25));
  const V e(1.75, -2.5, 0.5);  // 1, -2 and 2 scales
  EXPECT_DOUBLE_EQ(scaled_squares(e, scale), 1.0 + 4.0 + 4.0);
  EXPECT_DOUBLE_EQ(rms_error(scaled_squares(e, scale), 3), std::sqrt(3.0));
  EXPECT_EQ(rotation_scale(tol), 0.75);
}

TEST(ErrorNorm, TheStretchedCombinationIsHairersDop853) {
  // e2 / sqrt((e2 + e3 / 100) n): 4 / sqrt((4 + 96 / 100) 8)
  EXPECT_DOUBLE_EQ(stretched_rms_error(4.0, 96.0, 8), 4.0 / std::sqrt(4.96 * 8.0));
  EXPECT_EQ(stretched_rms_error(0.0, 0.0, 8), 0.0);
  // a small e3 leaves the plain estimate's sqrt(e2 / n)
  EXPECT_NEAR(stretched_rms_error(4.0, 0.0, 8), std::sqrt(4.0 / 8.0), 1e-15);
}

TEST(StageSums, ARowKeepsItsNonZeroWeightsAndSumsThemInOrder) {
  const std::vector<double> w = {0.5, 0.0, -0.25, 0.0, 2.0};
  const StageTerms::Row row(w.data(), 5);
  ASSERT_EQ(row.count, 3);
  EXPECT_EQ(row.index[1], 2);
  std::array<Eigen::Vector2d, kMaxStages> k;
  for (std::size_t j = 0; j < 5; ++j) k[j] = Eigen::Vector2d(1.0 + static_cast<double>(j), -1.0);
  k[1] = k[3] = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());  // never read
  // (h c_0) k_0 + (h c_1) k_1 + ..., and with a base y + (h c_0) k_0 + ...
  Eigen::Vector2d sum, from_base;
  row.sum(sum, 2.0, k);
  row.sum(from_base, Eigen::Vector2d(1.0, 1.0), 2.0, k);
  EXPECT_EQ(sum, Eigen::Vector2d(1.0 * 1.0 - 0.5 * 3.0 + 4.0 * 5.0, -1.0 + 0.5 - 4.0));
  EXPECT_EQ(from_base, Eigen::Vector2d(1.0 + 1.0 * 1.0 - 0.5 * 3.0 + 4.0 * 5.0, 1.0 - 1.0 + 0.5 - 4.0));
}

// sum_first<J> (a fixed step's unrolled stages) adds the same terms in the
// same order as sum: bit for bit, over every pattern of zeros in a row of
// J <= 4 terms, with and without a base, the pattern read at run time and
// known at compile time (a StageShape's row); a zero's stage is never read.
template <int J, unsigned Pattern>
void expect_sum_first_is_sum_for(const double (&weights)[4]) {
  std::vector<double> w(J, 0.0);
  std::array<ZState, kMaxStages> k;
  for (int j = 0; j < J; ++j) {
    const bool term = (Pattern >> j & 1u) != 0;
    w[static_cast<std::size_t>(j)] = term ? weights[j] : 0.0;
    k[static_cast<std::size_t>(j)] = term ? ZState(ZState::LinSpaced(0.37 * (j + 1), 1.9 / (j + 2)))
                                          : ZState(ZState::Constant(std::numeric_limits<double>::quiet_NaN()));
  }
  const StageTerms::Row row(w.data(), J);
  const ZState base = ZState::LinSpaced(-1.3, 0.7);
  const double h = 0.013;
  ZState sum, first, known, sum_base, first_base, known_base;
  row.sum(sum, h, k);
  row.sum_first<J>(first, h, k);
  row.sum_first<J, Pattern>(known, h, k);
  row.sum(sum_base, base, h, k);
  row.sum_first<J>(first_base, base, h, k);
  row.sum_first<J, Pattern>(known_base, base, h, k);
  for (int e = 0; e < kZSize; ++e) {
    const std::uint64_t bits = std::bit_cast<std::uint64_t>(sum[e]);
    const std::uint64_t bits_base = std::bit_cast<std::uint64_t>(sum_base[e]);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(first[e]), bits) << J << " " << Pattern;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(known[e]), bits) << J << " " << Pattern;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(first_base[e]), bits_base) << J << " " << Pattern;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(known_base[e]), bits_base) << J << " " << Pattern;
  }
  if constexpr (Pattern == 0) {
    EXPECT_EQ(first, ZState::Zero());
    EXPECT_EQ(known, ZState::Zero());
  }
}

template <int J>
void expect_sum_first_is_sum() {
  const double weights[4] = {0.1, -2.0 / 3.0, 1.0 / 7.0, 0.3};
  [&]<unsigned... pattern>(std::integer_sequence<unsigned, pattern...>) {
    (expect_sum_first_is_sum_for<J, pattern>(weights), ...);
  }
  (std::make_integer_sequence<unsigned, 1u << J>{});
}

TEST(StageSums, SumFirstAddsTheSameTermsAsSumBitForBitOverEveryPatternOfZeros) {
  expect_sum_first_is_sum<1>();
  expect_sum_first_is_sum<2>();
  expect_sum_first_is_sum<3>();
  expect_sum_first_is_sum<4>();
}

// A fixed step's shape: rows 1..S-1 of A and b (as row S), 4 bits a row.
TEST(StageSums, TheShapeOfATableauIsItsRowsPatternsOfNonZeroTerms) {
  // classical RK4: each stage from the one before, b full
  EXPECT_EQ(chain_shape(4), 0x1u | 0x2u << 4 | 0x4u << 8 | 0xFu << 12);
  EXPECT_EQ(dense_shape(3), 0x1u | 0x3u << 4 | 0x7u << 8);
  EXPECT_EQ(StageTerms(methods::rk4()).shape(4), chain_shape(4));
  // Kutta's third order and the 3/8 rule: every term
  EXPECT_EQ(StageTerms(methods::kutta3()).shape(3), dense_shape(3));
  EXPECT_EQ(StageTerms(methods::rk38()).shape(4), dense_shape(4));
  // the midpoint rule: b_1 = 0, neither
  const StageShape midpoint = StageTerms(Tableau("midpoint", 2, {0, 0, 0.5, 0}, {0, 1}, {0, 0.5})).shape(2);
  EXPECT_EQ(midpoint, 0x1u | 0x2u << 4);
  EXPECT_NE(midpoint, chain_shape(2));
  EXPECT_NE(midpoint, dense_shape(2));
  EXPECT_EQ(shape_row(midpoint, 2), 0x2u);
  EXPECT_EQ(shape_row(kRuntimeShape, 2), kAnyPattern);
}

}  // namespace
}  // namespace rb
