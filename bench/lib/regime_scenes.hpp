#pragma once
// The regime study's scenes, generated from its grid (docs/usage.md, "The
// regime study"), and the report's "regime" section (docs/formats.md,
// "Regime"): one bumpy bowl, one ball, one start, with the cell's inertia
// ratio, spin, roughness and t_end. Each scene is JSON text read by the
// scene parser, so it passes the checks a scene file does.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/lib/regime_grid.hpp"
#include "problems/scene.hpp"

namespace rb {

// The scene file of one cell.
std::string regime_scene_json(const RegimeCell& cell);

// The principal moments of a cell's ball, empty for ratio 1 (the
// homogeneous ball, given without "inertia").
std::vector<double> regime_moments(double inertia_ratio);

// Every cell's scene, parsed and checked; a cell the scene check refuses
// throws InputError (key "regime") naming the cell and the reason.
std::vector<Scene> regime_scenes(const RegimeGrid& grid);

// The grid's axes as the report's options hold them.
nlohmann::json regime_axes_json(const RegimeGrid& grid);

// The report's "regime" section: the axes, what every scene shares, and per
// cell its scene name, coordinates, moments and start rates.
nlohmann::json regime_json(const RegimeGrid& grid, const std::vector<Scene>& scenes);

}  // namespace rb
