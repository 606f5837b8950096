#pragma once
// The regime study's grid (docs/usage.md, "The regime study"): the axes a
// scene is generated along, inertia ratio x spin x roughness x time horizon
// x bowl curvature x rolling speed, and the text that gives them (rollbench
// run --regime).
#include <string>
#include <vector>

namespace rb {

// The ball of every generated scene: radius (m), mass (kg) and the mean of
// its principal moments (the homogeneous ball's 2/5 m r^2).
constexpr double kRegimeRadius = 0.1, kRegimeMass = 1.0,
                 kRegimeMeanMoment = 0.4 * kRegimeMass * kRegimeRadius * kRegimeRadius;

struct RegimeGrid {
  // largest / smallest principal moment of the ball: 1 is the homogeneous
  // ball, 3 the limit the moments' triangle inequality allows (a flat disc)
  std::vector<double> inertia;
  std::vector<double> spin;       // s0 = omega . N at the start, rad/s, >= 0
  std::vector<double> roughness;  // amplitude x wave number of the bumps (their largest slope), >= 0
  std::vector<double> t_end;      // the time horizon, s, > 0
  // a of the bowl a (x^2 + y^2): its curvature at the bottom is 2a, > 0,
  // and the ball must fit there (r 2a < 1)
  std::vector<double> bowl;
  std::vector<double> speed;  // the rolling speed at the start, m/s, > 0
  // the held-out scenes (regime_held_out_cells, the shipped chaplygin-*)
  // run beside the grid: the crossover fitted on the grid is checked there
  bool held_out = true;
};

// The axes' names in the grid text and in the report, in cell order.
inline const std::vector<std::string> kRegimeAxes = {"inertia", "spin", "roughness", "t_end", "bowl", "speed"};

// The grid of `--preset regime` (minutes on 2 cores) and the full one (a
// study for a cluster: docs/usage.md has its measured cost).
RegimeGrid default_regime_grid();
RegimeGrid full_regime_grid();

// "default", "full", or axes "inertia=1,2;spin=0.1,5,50;roughness=0,0.3;t_end=1,10;bowl=0.1,2;speed=0.5"
// (';' between axes, ',' between values): the axes given replace those of
// base; "held_out=none" (or "default") leaves out (or keeps) the held-out
// scenes. Throws InputError (key "regime") naming the axis and the value.
RegimeGrid parse_regime_grid(const std::string& text, const RegimeGrid& base);

// One point of the grid and the name of the scene generated there.
struct RegimeCell {
  double inertia = 1.0, spin = 0.0, roughness = 0.0, t_end = 1.0, bowl = 0.1, speed = 0.5;
  std::string scene;  // regime-i<inertia>-s<spin>-r<roughness>-t<t_end>-a<bowl>-v<speed>
};

// Every cell, t_end slowest, then roughness, bowl, speed, spin, and inertia
// fastest (a report's scene order).
std::vector<RegimeCell> regime_cells(const RegimeGrid& grid);

// The generated held-out scenes: cells whose bowl and speed lie off the
// default and full grids' values, on both sides of the crossover, fixed
// before any fit (named regime-offgrid-i...).
std::vector<RegimeCell> regime_held_out_cells();

}  // namespace rb
