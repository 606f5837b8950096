#pragma once
// The regime study's scenes, generated from its grid (docs/usage.md, "The
// regime study"), and the report's "regime" section (docs/formats.md,
// "Regime"): one bumpy bowl, one ball, one start, with the cell's inertia
// ratio, spin, roughness and t_end. Each scene is built as a value and
// checked by checked_scene, the checks a scene file passes.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/lib/regime_grid.hpp"
#include "problems/scene.hpp"

namespace rb {

// The scene of one cell, as built (not yet checked: checked_scene).
Scene regime_scene(const RegimeCell& cell);

// The principal moments of a cell's ball, empty for ratio 1 (the
// homogeneous ball, given without "inertia").
std::vector<double> regime_moments(double inertia_ratio);

// Omega, the angular frequency of a ball (radius r, mass m, mean principal
// moment I) rolling to and fro at the bottom of a bowl of curvature kappa:
// its centre moves on a sphere of radius 1 / kappa - r, so
// Omega^2 = g kappa / ((1 - r kappa) (1 + I / (m r^2))); 0 where kappa <= 0.
double bowl_frequency(double kappa, double radius, double mass, double mean_moment, double gravity);

// The regime's two rates at a scene's start: |omega0| and Omega of the
// largest principal curvature at the start contact. The crossover's
// predictor is their ratio (analysis/regime.py).
struct RegimeRates {
  double omega0 = 0.0;
  double bowl_frequency = 0.0;
};
RegimeRates regime_rates(const Scene& scene);

// Every cell's scene, checked, then (when grid.held_out) the
// held-out scenes: regime_held_out_cells() and the shipped chaplygin-*
// scenes; a cell the scene check refuses throws InputError (key "regime")
// naming the cell and the reason.
std::vector<Scene> regime_scenes(const RegimeGrid& grid);

// The grid's axes as the report's options hold them.
nlohmann::json regime_axes_json(const RegimeGrid& grid);

// The report's "regime" section: the axes, what every scene shares, per
// cell its scene name, coordinates, moments, start and rates, and the
// held-out scenes with their rates.
nlohmann::json regime_json(const RegimeGrid& grid, const std::vector<Scene>& scenes);

}  // namespace rb
