// The command line's bad input, message by message (docs/bad-input.md,
// "Command line"): exit status 2 and one line on standard error that names
// the option; a run that stops early exits 3 and says why.
#include "tests/robustness/helpers.hpp"

namespace rb::robustness {
namespace {

struct CliCase {
  std::string args;  // after "rollbench"; OUT is replaced by a temp file
  int code;
  std::string err;  // a line standard error must contain
};

void expect_cli(const CliCase& c) {
  std::string args = c.args;
  if (const auto at = args.find("OUT"); at != std::string::npos) args.replace(at, 3, temp_path("cli.out").string());
  const CliOutcome o = rollbench(args);
  EXPECT_EQ(o.code, c.code) << "rollbench " << args << "\n" << o.err;
  EXPECT_NE(o.err.find(c.err), std::string::npos) << "rollbench " << args << "\nstderr: " << o.err;
}

TEST(CliErrors, TrajectoryOptionsNameTheirOption) {
  const std::vector<CliCase> cases = {
      {"trajectory plane --integrator rk4 --out OUT", 2,
       "rollbench: 'h': 'rk4' is a fixed-step method and needs --h > 0\n"},
      {"trajectory plane --integrator rk4 --h -0.1 --out OUT", 2,
       "rollbench: 'h': 'rk4' is a fixed-step method and needs --h > 0\n"},
      {"trajectory plane --integrator odeint-dopri5-adaptive --out OUT", 2,
       "rollbench: 'rtol': an adaptive method needs rtol > 0 or atol > 0\n"},
      {"trajectory plane --integrator gsl-rkf45-adaptive --rtol 1e-6 --atol -1 --out OUT", 2,
       "rollbench: 'atol': an adaptive method needs a finite tolerance >= 0\n"},
      {"trajectory plane --integrator odeint-dopri5-adaptive --rtol 1e-6 --atol nan --out OUT", 2,
       "rollbench: 'atol': an adaptive method needs a finite tolerance >= 0\n"},
      // given to a fixed-step method, checked where they enter all the same
      {"trajectory plane --integrator rk4 --h 0.1 --rtol -1 --out OUT", 2,
       "rollbench: 'rtol': an adaptive method needs a finite tolerance >= 0\n"},
      {"trajectory plane --integrator odeint-dopri5-adaptive --rtol 1e-6 --h -1 --out OUT", 2,
       "rollbench: 'h': the step h must be a finite number >= 0 (0: an adaptive method chooses its first step)\n"},
      {"trajectory plane --integrator rk4 --h 0.1 --dt-out 0.01 --out OUT", 2,
       "rollbench: 'dt-out': the output spacing must not be smaller than the step h = 0.100000\n"},
      {"trajectory plane --integrator rk5000 --h 0.1 --out OUT", 2,
       "rollbench: 'integrator': unknown integrator 'rk5000' (`rollbench list` shows them all)\n"},
      {"trajectory no-such-scene --integrator rk4 --h 0.1 --out OUT", 2,
       "rollbench: 'scene': unknown scene 'no-such-scene' (shipped: "},
      {"trajectory /no/such/scene.json --integrator rk4 --h 0.1 --out OUT", 2,
       "rollbench: 'scene': cannot read the scene file '/no/such/scene.json' (No such file or directory)\n"},
      {"trajectory plane --integrator rk4 --h 0.1 --out /no/such/dir/x.csv", 2,
       "rollbench: 'out': cannot open '/no/such/dir/x.csv' for writing\n"},
      {"trajectory plane --integrator rk4 --h abc --out OUT", 2, "rollbench: "},
      {"trajectory plane --integrator rk4 --h 0.1 --bogus 1 --out OUT", 2,
       "rollbench: The following arguments were not expected: 1 --bogus\n"},
      {"", 2, "rollbench: A subcommand is required\n"},
  };
  for (const CliCase& c : cases) expect_cli(c);
}

TEST(CliErrors, RunAndMergeOptionsNameTheirOption) {
  const std::vector<CliCase> cases = {
      {"run --preset huge --out OUT", 2,
       "rollbench: 'preset': unknown preset 'huge' (quick, default, full or regime)\n"},
      {"run --h 0,1 --out OUT", 2, "rollbench: 'h': expected positive numbers separated by commas, got '0'\n"},
      {"run --tol 1e-6,abc --out OUT", 2,
       "rollbench: 'tol': expected positive numbers separated by commas, got 'abc'\n"},
      {"run --h 2^-3..2^-1 --out OUT", 2, "rollbench: 'h': expected a range like 2^-3..2^-8, got '2^-3..2^-1'\n"},
      {"run --integrators rk4,nope --scenes plane --out OUT", 2,
       "rollbench: 'integrator': unknown integrator 'nope' (`rollbench list` shows them all)\n"},
      {"run --preset quick --shard 3/2 --out OUT", 2,
       "rollbench: 'shard': '3/2' is not I/N with 0 <= I < N <= 100000\n"},
      {"merge /no/such/report.json --out OUT", 2,
       "rollbench: 'report': cannot read the report '/no/such/report.json' (No such file or directory)\n"},
      {"merge " RB_SCENE_DIR "/plane.json --out OUT", 2, "is not a rollbench.report/2 report\n"},
  };
  for (const CliCase& c : cases) expect_cli(c);
}

TEST(CliErrors, RunsThatStopEarlyExitThreeWithTheReason) {
  const std::vector<CliCase> cases = {
      {"trajectory " RB_TEST_DATA "/stop-domain.json --integrator rkmk4 --h 0.01 --out OUT", 3,
       ": domain: the contact point ("},
      {"trajectory " RB_TEST_DATA "/stop-curvature.json --integrator rk4 --h 0.01 --out OUT", 3,
       ": curvature: r * max curvature reached "},
      {"trajectory " RB_TEST_DATA "/stop-steep-bowl.json --integrator rk4 --h 0.001 --dt-out 1 --out OUT", 3,
       ": curvature: r * max curvature reached "},
      // steps that jump the region where r kappa > 1: a stage sees it
      {"trajectory " RB_TEST_DATA "/stop-steep-bowl.json --integrator rk4 --h 0.05 --out OUT", 3,
       ": curvature: r * max curvature reached "},
      {"trajectory " RB_TEST_DATA
       "/stop-steep-bowl.json --integrator rkmk-f78-adaptive --rtol 1e-2 --atol 1e-2 --out OUT",
       3, ": curvature: "},
      // a loose step whose stages all miss the region its path crosses
      // (issue 32's case): stopped for every output spacing
      {"trajectory " RB_TEST_DATA
       "/stop-steep-elliptic-bowl.json --integrator rkmk-f78-adaptive --rtol 1e-2 --atol 1e-2 --dt-out 1 --out OUT",
       3, ": curvature: "},
      {"trajectory " RB_TEST_DATA
       "/stop-steep-elliptic-bowl.json --integrator rkmk-f78-adaptive --rtol 1e-2 --atol 1e-2 --dt-out 0.01 --out OUT",
       3, ": curvature: "},
      {"trajectory " RB_TEST_DATA "/stop-nonfinite.json --integrator euler --h 0.01 --out OUT", 3,
       ": diverged: the landscape or its derivatives are not finite at the contact point\n"},
      {"trajectory plane --integrator gsl-rkf45-adaptive --rtol 1e-300 --atol 1e-300 --out OUT", 3,
       ": step-underflow: the tolerances rtol = 1e-300, atol = 1e-300 are below the rounding of the state"},
      {"trajectory plane --integrator rk4 --h 1e-300 --out OUT", 3,
       "rollbench: run stopped early at t = 0: max-steps: the step count overflows\n"},
  };
  for (const CliCase& c : cases) expect_cli(c);
}

// Every class of bad ball.inertia: exit 2 and the key, with the exact text.
TEST(CliErrors, BadInertiaNamesTheKey) {
  const std::string ball = R"("ball": {"radius": 0.1, "mass": 1.0})";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"[0.004, 0.004]", "'ball.inertia': must be an array of 3 numbers, not 2"},
      {"0.004", "'ball.inertia': must be an array of 3 numbers, not number"},
      {R"([0.004, "a", 0.004])", "'ball.inertia': must be an array of 3 numbers; element 1 is a string"},
      {"[0.004, 0, 0.004]", "'ball.inertia': each principal moment [I1, I2, I3] must be > 0, not I2 = 0"},
      {"[-0.001, 0.004, 0.004]", "'ball.inertia': each principal moment [I1, I2, I3] must be > 0, not I1 = -0.001"},
      {"[0.001, 0.002, 0.004]",
       "'ball.inertia': the moments must obey the triangle inequality, but I3 = 0.004 > the other two's sum 0.003"},
      {"[0.008, 0.008, 0.008]",
       "'ball.inertia': the moments do not fit a ball of this mass and radius: I1 + I2 + I3 = 0.024 > 2 m r^2 = "
       "0.02"},
  };
  for (const auto& [inertia, err] : cases) {
    const std::filesystem::path file = temp_path("inertia.json");
    std::ofstream(file) << replaced(base_scene_text(), ball,
                                    R"("ball": {"radius": 0.1, "mass": 1.0, "inertia": )" + inertia + "}");
    expect_cli({"trajectory " + file.string() + " --integrator rk4 --h 0.1 --out OUT", 2, "rollbench: " + err + "\n"});
  }
}

// Options out of range must be refused, not replaced by a default
// (docs/formats.md: bad input exits with status 2 and names the option).
TEST(CliErrors, NegativeOrNonFiniteOptionsAreRefusedNotDefaulted) {
  const std::vector<CliCase> cases = {
      {"trajectory plane --integrator rk4 --h 0.1 --t-end -5 --out OUT", 2, "'t-end'"},
      {"trajectory plane --integrator rk4 --h 0.1 --dt-out -1 --out OUT", 2, "'dt-out'"},
      {"trajectory plane --integrator rk4 --h inf --out OUT", 2, "'h'"},
  };
  for (const CliCase& c : cases) expect_cli(c);
}

}  // namespace
}  // namespace rb::robustness
