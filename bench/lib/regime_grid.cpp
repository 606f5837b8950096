#include "bench/lib/regime_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "problems/input_error.hpp"

namespace rb {

namespace {

constexpr const char* kKey = "regime";

// A value as it appears in a scene name: short, and the same text for the
// same number on every machine.
std::string label(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  std::string out = text;
  // "1e+06" -> "1e06": a scene name takes no '+' (problems/safe_name.hpp)
  out.erase(std::remove(out.begin(), out.end(), '+'), out.end());
  return out;
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, separator)) parts.push_back(item);
  if (!text.empty() && text.back() == separator) parts.push_back("");
  return parts;
}

// Each axis's own range; the rest (a start the landscape cannot carry) is
// the scene check's, which every generated scene passes through.
void check_value(const std::string& axis, double v) {
  if (axis == "inertia" && !(v >= 1.0 && v <= 3.0))
    throw InputError("inertia: the ratio " + label(v) +
                         " is outside [1, 3] (1: the homogeneous ball; above 3 the moments break the triangle "
                         "inequality)",
                     kKey);
  if ((axis == "spin" || axis == "roughness") && !(v >= 0.0))
    throw InputError(axis + ": " + label(v) + " is negative (expected a number >= 0)", kKey);
  if ((axis == "t_end" || axis == "speed") && !(v > 0.0))
    throw InputError(axis + ": " + label(v) + " is not > 0", kKey);
  // the ball must fit the bowl's bottom: r kappa = 2 a r < 1 (docs/model.md)
  if (axis == "bowl" && !(v > 0.0 && 2.0 * v * kRegimeRadius < 1.0))
    throw InputError("bowl: a = " + label(v) + " is outside (0, " + label(0.5 / kRegimeRadius) +
                         ") (the bowl's curvature 2a must be > 0 and the ball of radius " + label(kRegimeRadius) +
                         " m must fit its bottom, r 2a < 1)",
                     kKey);
}

std::vector<double> parse_values(const std::string& axis, const std::string& text) {
  std::vector<double> values;
  for (const std::string& item : split(text, ',')) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(v))
      throw InputError(axis + ": expected finite numbers separated by commas, got '" + text + "'", kKey);
    check_value(axis, v);
    // two values one name apart would make two scenes of one name
    for (double seen : values)
      if (label(seen) == label(v))
        throw InputError(axis + ": the value " + label(v) + " is given twice (values must differ in 6 digits)", kKey);
    values.push_back(v);
  }
  return values;
}

std::vector<double>& axis_of(RegimeGrid& grid, const std::string& axis) {
  if (axis == "inertia") return grid.inertia;
  if (axis == "spin") return grid.spin;
  if (axis == "roughness") return grid.roughness;
  if (axis == "bowl") return grid.bowl;
  if (axis == "speed") return grid.speed;
  return grid.t_end;
}

}  // namespace

RegimeGrid default_regime_grid() {
  // 2 x 3 x 2 x 1 x 3 x 2 = 72 scenes: the homogeneous ball against the
  // triangle inequality's limit; spin from far slower than the rolling to
  // ten times it; smooth and bumpy; bowls from bumpy-long's shallow a = 0.1
  // to chaplygin-bowl's steep a = 2 (r kappa = 0.4), rolled slowly
  // (chaplygin-bowl's 0.1 m/s) and at 0.5 m/s: the ball's rate over the
  // bowl's frequency |omega0| / Omega from about 0.2 to 40, both sides of
  // the crossover (docs/usage.md, "The regime study")
  return {{1.0, 3.0}, {0.1, 5.0, 50.0}, {0.0, 0.3}, {1.0}, {0.1, 0.5, 2.0}, {0.1, 0.5}};
}

RegimeGrid full_regime_grid() {
  // 4 x 5 x 4 x 4 x 3 x 3 = 2880 scenes, to t_end = 1000 (references alone
  // take minutes a scene there): a cluster's study, docs/usage.md
  return {{1.0, 1.5, 2.0, 3.0}, {0.1, 1.0, 5.0, 20.0, 50.0},
          {0.0, 0.1, 0.3, 0.5}, {1.0, 10.0, 100.0, 1000.0},
          {0.1, 0.5, 2.0},      {0.1, 0.5, 1.0}};
}

RegimeGrid parse_regime_grid(const std::string& text, const RegimeGrid& base) {
  if (text == "default") return default_regime_grid();
  if (text == "full") return full_regime_grid();
  if (text.empty()) throw InputError("the grid is empty (give default, full or AXIS=V1,V2;...)", kKey);
  RegimeGrid grid = base;
  std::vector<std::string> given;
  for (const std::string& part : split(text, ';')) {
    const auto eq = part.find('=');
    if (eq == std::string::npos)
      throw InputError("expected AXIS=V1,V2,... for each axis, separated by ';' (or default, full), got '" + part + "'",
                       kKey);
    const std::string axis = part.substr(0, eq);
    if (axis == "held_out") {
      if (std::find(given.begin(), given.end(), axis) != given.end()) throw InputError("held_out is given twice", kKey);
      given.push_back(axis);
      const std::string value = part.substr(eq + 1);
      if (value != "none" && value != "default")
        throw InputError("held_out: expected none or default, got '" + value + "'", kKey);
      grid.held_out = value == "default";
      continue;
    }
    if (std::find(kRegimeAxes.begin(), kRegimeAxes.end(), axis) == kRegimeAxes.end())
      throw InputError(
          "unknown axis '" + axis + "' (known: inertia, spin, roughness, t_end, bowl, speed; and held_out)", kKey);
    if (std::find(given.begin(), given.end(), axis) != given.end())
      throw InputError("the axis " + axis + " is given twice", kKey);
    given.push_back(axis);
    axis_of(grid, axis) = parse_values(axis, part.substr(eq + 1));
  }
  for (const std::string& axis : kRegimeAxes)
    if (axis_of(grid, axis).empty()) throw InputError(axis + ": the axis has no values", kKey);
  return grid;
}

namespace {

RegimeCell named(RegimeCell c, const std::string& prefix) {
  c.scene = prefix + "-i" + label(c.inertia) + "-s" + label(c.spin) + "-r" + label(c.roughness) + "-t" +
            label(c.t_end) + "-a" + label(c.bowl) + "-v" + label(c.speed);
  return c;
}

}  // namespace

std::vector<RegimeCell> regime_cells(const RegimeGrid& grid) {
  std::vector<RegimeCell> cells;
  for (double t : grid.t_end)
    for (double r : grid.roughness)
      for (double a : grid.bowl)
        for (double v : grid.speed)
          for (double s : grid.spin)
            for (double i : grid.inertia) cells.push_back(named({i, s, r, t, a, v, ""}, "regime"));
  return cells;
}

std::vector<RegimeCell> regime_held_out_cells() {
  // inertia, spin, roughness, t_end, bowl, speed: bowl and speed off every
  // value of the default and full grids (most others too); |omega0| / Omega
  // about 0.17, 0.18, 1.6, 2.7 and 18
  const std::vector<RegimeCell> cells = {{2.5, 0.5, 0.0, 1.0, 1.0, 0.05, ""},
                                         {2.8, 1.0, 0.05, 1.0, 3.0, 0.15, ""},
                                         {2.2, 2.0, 0.2, 1.0, 0.3, 0.2, ""},
                                         {1.5, 10.0, 0.2, 2.0, 1.0, 0.3, ""},
                                         {2.5, 30.0, 0.0, 2.0, 0.2, 0.8, ""}};
  std::vector<RegimeCell> out;
  for (const RegimeCell& c : cells) out.push_back(named(c, "regime-offgrid"));
  return out;
}

}  // namespace rb
