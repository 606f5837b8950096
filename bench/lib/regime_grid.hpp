#pragma once
// The regime study's grid (docs/usage.md, "The regime study"): the axes a
// scene is generated along, inertia ratio x spin x roughness x time horizon,
// and the text that gives them (rollbench run --regime).
#include <string>
#include <vector>

namespace rb {

struct RegimeGrid {
  // largest / smallest principal moment of the ball: 1 is the homogeneous
  // ball, 3 the limit the moments' triangle inequality allows (a flat disc)
  std::vector<double> inertia;
  std::vector<double> spin;       // s0 = omega . N at the start, rad/s, >= 0
  std::vector<double> roughness;  // amplitude x wave number of the bumps (their largest slope), >= 0
  std::vector<double> t_end;      // the time horizon, s, > 0
};

// The axes' names in the grid text and in the report, in cell order.
inline const std::vector<std::string> kRegimeAxes = {"inertia", "spin", "roughness", "t_end"};

// The grid of `--preset regime` (minutes on 2 cores) and the full one (a
// study for a cluster: docs/usage.md has its measured cost).
RegimeGrid default_regime_grid();
RegimeGrid full_regime_grid();

// "default", "full", or axes "inertia=1,2;spin=0.1,5,50;roughness=0,0.3;t_end=1,10"
// (';' between axes, ',' between values): the axes given replace those of
// base. Throws InputError (key "regime") naming the axis and the value.
RegimeGrid parse_regime_grid(const std::string& text, const RegimeGrid& base);

// One point of the grid and the name of the scene generated there.
struct RegimeCell {
  double inertia = 1.0, spin = 0.0, roughness = 0.0, t_end = 1.0;
  std::string scene;  // regime-i<inertia>-s<spin>-r<roughness>-t<t_end>
};

// Every cell, t_end slowest and inertia fastest (a report's scene order).
std::vector<RegimeCell> regime_cells(const RegimeGrid& grid);

}  // namespace rb
