// The observed order of every registered fixed-step integrator, measured on
// the seminar's default landscape with a sideways start and on a scene where
// R feeds back (problems/scenes/chaplygin-bowl.json): a new integrator is
// checked here with no new test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "integrators/registry.hpp"
#include "problems/input_error.hpp"
#include "problems/scene.hpp"
#include "tests/integrators/convergence.hpp"
#include "tests/integrators/fixtures.hpp"
#include "tests/integrators/order_scene.hpp"
#include "tests/registry_names.hpp"

namespace rb {
namespace {

constexpr double kTEnd = 1.0;

using testing::valley;

// rkmk4 at h = 5e-5 on a problem: its error (~1e-17, rounding ~1e-15) is
// far below every error fitted.
FlatState reference_of(const Problem& problem) {
  RunOptions options;
  options.t_end = kTEnd;
  options.h = 5e-5;
  return find_integrator("rkmk4").integrate(problem, options).final_state;
}

const FlatState& reference() {
  static const FlatState ref = reference_of(valley());
  return ref;
}

// the seminar's valley with an anisotropic ball: R feeds back into (v, alpha)
const Problem& chaplygin_valley() {
  static const Problem problem = make_problem(load_scene("chaplygin-valley"));
  return problem;
}

const FlatState& chaplygin_reference() {
  static const FlatState ref = reference_of(chaplygin_valley());
  return ref;
}

// The registry-wide order test where R feeds back, on
// problems/scenes/chaplygin-bowl.json to t = 1: an anisotropic ball in a
// paraboloid bowl (r kappa = 0.4), 2 cm off centre, spinning at 3 rad/s.
// omega = T(R)^-1 v turns with R, so R's error enters the contact point and
// omega: after 1 s the contact is 8 mm from the homogeneous ball's on a 2 cm
// orbit, and at h = 0.0125 rk4's contact error is 3.9e-8, rkmk4's 7.2e-8.
// Why this scene: the bowl's period (~1 s) is close to R's turning time, so
// no term of the error expansion outgrows the leading one, and an order-8
// method is asymptotic well above rounding (rkmk8: local slopes 7.93-8.07 in
// contact, omega and R from h = 0.08 to 0.02, errors 1e-9 ... 1e-14). On
// chaplygin-plane, the test's scene before, rkmk8's contact read 7.47-7.79
// before rounding; where the spin is much faster than the landscape
// (chaplygin-valley) the h^9 terms rule odeint-fehlberg78 down to rounding.
// The spin is still fast enough for rkmk4-seminar's lost order to reach the
// motion (contact and omega: local slopes 2.98-3.03 from h = 6e-4 down).
// - The reference is rkmk8 at h = 1/128: its truncation error (~1e-17 in the
//   contact, ~1e-15 in omega) is below its rounding.
// - The floor is measured, not guessed (testing::rounding_floor): rkmk8's
//   runs of 128 to 5793 steps differ from each other by rounding only,
//   scaled to 128 steps at most 3e-16 in the contact, 2e-14 in omega and
//   8e-15 in R. A run of n steps has it times sqrt(n / 128), and errors
//   below 10 times that are not fitted (cf4's last points: local slope 4.00
//   down to 2e-13, 3.72 at 1.2e-14 after 4096 steps, which a floor taken
//   from one pair of runs would have let in).
// - h falls by sqrt(2) from 0.25 to 1e-5, recorded at the step the driver
//   took (t_end / steps: sqrt(2) does not divide t_end, and the nominal h
//   makes the local slopes of order 8 zigzag by +-1.5), until the contact
//   error is on its floor; the slope is fitted over the three smallest steps
//   above it.
using testing::chaplygin_bowl;

constexpr long kBowlReferenceSteps = 128;

const FlatState& chaplygin_bowl_reference() {
  static const FlatState ref =
      testing::run_at(find_integrator("rkmk8"), chaplygin_bowl(), kTEnd, kTEnd / kBowlReferenceSteps).final_state;
  return ref;
}

const testing::Ladder& chaplygin_bowl_ladder() {
  static const testing::Ladder ladder{
      0.25,
      1e-5,
      std::sqrt(2.0),
      testing::rounding_floor(find_integrator("rkmk8"), chaplygin_bowl(), kTEnd, kBowlReferenceSteps),
      kBowlReferenceSteps,
      3,
      0.0};
  return ladder;
}

// How far an observed order may lie below and above the expected one.
struct Tolerance {
  double below, above;
};

constexpr Tolerance kPointTwo{0.2, 0.2};

// Where R feeds back: 0.2 below, as everywhere (a method declared one order
// too high reads a whole order low), and 0.5 above, for one method:
// odeint-fehlberg78 (the flat view: R is nine free numbers) approaches its
// order 8 from above and is still on the way when it meets rounding. Its
// local slopes, from h = 0.125 down to the floor at h = 0.022: contact 8.66,
// 8.52, 8.36, 8.24, 8.13; omega 8.94, 8.75, 8.56, 8.38, 8.20; R 8.84, 8.71,
// 8.60, 8.49, 8.44 (fits of the three smallest steps 8.18, 8.28, 8.47).
// rkmk8, the same Fehlberg weights on the Lie-group view, reads 8.00 there,
// so it is the flat R's higher-order error, not the scene, that rules down
// to 1e-13. 0.5 still fails a method declared one order too low (it reads a
// whole order high); every other method is within 0.07 of its expected order
// (gsl-rk4imp's R: 4.17).
// Why no other scene, measured (fits contact / omega / R, this ladder):
// odeint-fehlberg78's excess comes with the anisotropic ball's spin. With
// equal moments given, spins 0, 1, 3, 5: 7.99-8.05 throughout; with this
// ball's moments: spin 0 8.03 / 7.84 / 8.04, 1 7.98 / 8.15 / 8.05, 3 8.18 /
// 8.28 / 8.47, 5 8.53 / 8.74 / 8.45 (rkmk8 7.84-8.16). Below spin 2,
// though, rkmk4-seminar's lost order no longer reaches the contact (4.03
// at spin 0, 4.24 at 1). t_end from 0.3 to 3 keeps its R at 8.21-8.76;
// faster spins (6 to 30) take rkmk8 above 8.2 too. Of 400 scenes drawn at
// random (bowl a, spin, start, orientation, moments, t_end), one put
// fehlberg78, rkmk8 and rkmk4-seminar within 0.12 of their orders, but
// failed others (gsl-rk4imp's omega 3.79 on its solver's floor,
// odeint-dopri5's R 5.11); of 150 drawn with eight methods checked, none
// came closer than 0.30.
constexpr Tolerance kWhereRFeedsBack{0.2, 0.5};

// adaptive methods are checked by tolerance proportionality instead
// adaptive methods are checked by tolerance proportionality instead
std::vector<std::string> fixed_step_names() {
  std::vector<std::string> names;
  for (const auto& integrator : registry())
    if (!integrator->adaptive()) names.push_back(integrator->name());
  return names;
}

// The order the motion (contact point, omega) converges with. Where R feeds
// back (an anisotropic ball), an error of order q in R enters omega = T(R)^-1
// v and G(R, z) at order q, so the motion converges with min(p, q): a method
// whose rotation loses an order (rkmk4-seminar's sign error) loses it in the
// contact point and omega too. Otherwise R enters nothing and the motion
// keeps the declared order p.
int motion_order(const Integrator& method, const Problem& problem) {
  return problem.model().anisotropic() ? std::min(method.declared_order(), method.rotation_order())
                                       : method.declared_order();
}

bool within(double observed, int expected, Tolerance tolerance) {
  return observed >= expected - tolerance.below && observed <= expected + tolerance.above;
}

// What fails when method's observed orders are checked against the expected
// ones (motion: contact point and omega; rotation: R), with the data that
// shows why; empty when it passes.
std::vector<std::string> order_failures(const Integrator& method, const Problem& problem, const FlatState& ref,
                                        const testing::Ladder& ladder, Tolerance tolerance, int motion, int rotation) {
  const testing::Convergence c = testing::measure_convergence(method, problem, kTEnd, ref, ladder);
  std::vector<std::string> failures;
  const auto fail = [&](const std::string& what, double observed, int expected) {
    std::ostringstream line;
    line.precision(3);
    line << method.name() << " on " << problem.name() << ": " << what << " observed " << observed << ", expected "
         << expected << " (-" << tolerance.below << ", +" << tolerance.above << ")";
    for (std::size_t i = 0; i < c.h.size(); ++i)
      line << "\n  h " << c.h[i] << ": contact " << c.contact[i] << ", omega " << c.omega[i] << ", rotation "
           << c.rotation[i];
    failures.push_back(line.str());
  };
  if (c.contact_fit.points < 3) fail("too few points in the asymptotic range", c.contact_fit.points, 3);
  if (!within(c.contact_fit.slope, motion, tolerance)) fail("contact point", c.contact_fit.slope, motion);
  if (!within(c.omega_fit.slope, motion, tolerance)) fail("omega", c.omega_fit.slope, motion);
  if (c.final_defect < 1e-12) {
    // R stays on SO(3): its angle converges like the rest
    if (!within(c.rotation_fit.slope, rotation, tolerance)) fail("rotation", c.rotation_fit.slope, rotation);
  } else if (!(c.rotation_fit.slope >= rotation - 0.5)) {
    // R drifts off SO(3) and the angle after projection converges unevenly
    // (for odd orders the leading error is symmetric, which projection
    // removes, so it may even read one order higher); a rotation that does not
    // converge at its order still fails here
    fail("rotation (R off SO(3))", c.rotation_fit.slope, rotation);
  }
  return failures;
}

void expect_expected_order(const Integrator& method, const Problem& problem, const FlatState& ref,
                           const testing::Ladder& ladder, Tolerance tolerance) {
  for (const std::string& failure :
       order_failures(method, problem, ref, ladder, tolerance, motion_order(method, problem), method.rotation_order()))
    ADD_FAILURE() << failure;
}

class RegistryOrder : public ::testing::TestWithParam<std::string> {};

TEST_P(RegistryOrder, ObservedOrderWithinPointTwoOfDeclared) {
  expect_expected_order(find_integrator(GetParam()), valley(), reference(), {}, kPointTwo);
}

INSTANTIATE_TEST_SUITE_P(AllRegistered, RegistryOrder, ::testing::ValuesIn(fixed_step_names()),
                         testing::registry_test_name);

// The same check where R feeds back; scene, reference, ladder and tolerance
// above kWhereRFeedsBack.
class RegistryOrderAnisotropic : public ::testing::TestWithParam<std::string> {};

TEST_P(RegistryOrderAnisotropic, ObservedOrderWithinToleranceOfExpected) {
  expect_expected_order(find_integrator(GetParam()), chaplygin_bowl(), chaplygin_bowl_reference(),
                        chaplygin_bowl_ladder(), kWhereRFeedsBack);
}

INSTANTIATE_TEST_SUITE_P(AllRegistered, RegistryOrderAnisotropic, ::testing::ValuesIn(fixed_step_names()),
                         testing::registry_test_name);

TEST(RegistryOrder, SeminarSignErrorCostsAnOrderInRotationOnly) {
  const Integrator& seminar = find_integrator("rkmk4-seminar");
  const testing::Convergence c = testing::measure_convergence(seminar, valley(), kTEnd, reference());
  EXPECT_NEAR(c.rotation_fit.slope, 3.0, 0.2);
  EXPECT_NEAR(c.contact_fit.slope, 4.0, 0.2);
}

// Where R feeds back, the rotation's lost order reaches the contact point.
TEST(RegistryOrder, SeminarSignErrorCostsAnOrderInTheContactWhereRFeedsBack) {
  const Integrator& seminar = find_integrator("rkmk4-seminar");
  const testing::Convergence c =
      testing::measure_convergence(seminar, chaplygin_valley(), kTEnd, chaplygin_reference());
  EXPECT_NEAR(c.rotation_fit.slope, 3.0, 0.2);
  EXPECT_NEAR(c.contact_fit.slope, 3.0, 0.2);
}

// The check where R feeds back can fail: a method declared one order too
// high or too low, and rkmk4-seminar read at its declared order (as if its
// rotation's lost order did not reach the motion), each fail it.
std::size_t failures_where_r_feeds_back(const std::string& name, int motion, int rotation) {
  return order_failures(find_integrator(name), chaplygin_bowl(), chaplygin_bowl_reference(), chaplygin_bowl_ladder(),
                        kWhereRFeedsBack, motion, rotation)
      .size();
}

TEST(RegistryOrderAnisotropicCheck, FailsAMethodDeclaredOneOrderOff) {
  EXPECT_EQ(failures_where_r_feeds_back("rk4", 4, 4), 0u);
  EXPECT_GE(failures_where_r_feeds_back("rk4", 5, 5), 2u);  // contact and omega at least
  EXPECT_GE(failures_where_r_feeds_back("rk3", 4, 4), 2u);
  EXPECT_GE(failures_where_r_feeds_back("rkmk5", 6, 6), 3u);
  EXPECT_GE(failures_where_r_feeds_back("rkmk4", 3, 3), 3u);  // one order too low
  EXPECT_GE(failures_where_r_feeds_back("rkmk8", 7, 7), 3u);
}

TEST(RegistryOrderAnisotropicCheck, FailsTheSeminarsMethodReadAtItsDeclaredOrder) {
  EXPECT_EQ(failures_where_r_feeds_back("rkmk4-seminar", 3, 3), 0u);
  EXPECT_EQ(failures_where_r_feeds_back("rkmk4-seminar", 4, 4), 3u);  // contact, omega and R
}

TEST(Registry, NamesAreUniqueAndLookupFails) {
  std::vector<std::string> names;
  for (const auto& integrator : registry()) names.push_back(integrator->name());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(std::adjacent_find(names.begin(), names.end()), names.end());
  try {
    find_integrator("rk5000");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "integrator");
    EXPECT_STREQ(e.what(), "'integrator': unknown integrator 'rk5000' (`rollbench list` shows them all)");
  }
}

}  // namespace
}  // namespace rb
