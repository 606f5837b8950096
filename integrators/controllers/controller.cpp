#include "integrators/controllers/controller.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "problems/input_error.hpp"

namespace rb {

namespace {

constexpr double kSafety = 0.9;
constexpr double kFacMin = 0.2;
constexpr double kFacMax = 10.0;
// errors are kept above these in the history: a step that happens to be
// exact must not make the next one explode
constexpr double kErrFloor = 1e-10;
constexpr double kHistoryFloor = 1e-4;

}  // namespace

const std::vector<ControllerKind>& filter_controllers() {
  static const std::vector<ControllerKind> all = {
      {"i", 1.0, 0.0, 0.0, "elementary controller, h * (1/err)^(1/k)"},
      {"pi", 0.7, -0.4, 0.0, "Gustafsson's PI controller, (1/err_n)^(0.7/k) err_n-1^(0.4/k)"},
      {"pid", 1.0 / 18, 1.0 / 9, 1.0 / 18, "Söderlind's H312PID digital filter over the last three errors"},
  };
  return all;
}

std::string controller_names() {
  std::string names = std::string(kConstantController) + ", " + kLibraryController;
  for (const ControllerKind& k : filter_controllers()) names += std::string(", ") + k.name;
  return names;
}

void require_controller(std::string_view controller, std::initializer_list<std::string_view> supported,
                        std::string_view method, std::string_view way) {
  std::string takes;
  for (const std::string_view name : supported) {
    if (name == controller) return;
    takes += (takes.empty() ? "'" : " or '") + std::string(name) + "'";
  }
  if (supported.size() == 1) takes += " only";
  throw InputError("'" + std::string(method) + "': " + std::string(way) + " takes the controller " + takes + ", not '" +
                       std::string(controller) + "'",
                   "controller");
}

std::string controller_title(std::string_view name) {
  std::string title(name);
  for (char& ch : title) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  return title;
}

const ControllerKind& filter_controller(std::string_view name) {
  for (const ControllerKind& k : filter_controllers())
    if (name == k.name) return k;
  throw InputError("unknown step-size controller '" + std::string(name) + "' (known: " + controller_names() + ")",
                   "controller");
}

FilterController::FilterController(const ControllerKind& kind, int error_order)
    : e1_(-kind.b1 / error_order),
      e2_(-kind.b2 / error_order),
      e3_(-kind.b3 / error_order),
      k_inv_(1.0 / error_order) {}

StepDecision FilterController::decide(double err, double h) {
  if (err > 1.0) {
    rejected_last_ = true;
    return {false, h * std::max(kFacMin, kSafety * std::pow(err, -k_inv_))};
  }
  const double fac_max = rejected_last_ ? 1.0 : kFacMax;
  // zero exponents are skipped: the I and PI filters then compute exactly
  // what a filter of their own length would
  double fac = kSafety * std::pow(std::max(err, kErrFloor), e1_);
  if (e2_ != 0.0) fac *= std::pow(err_prev_, e2_);
  if (e3_ != 0.0) fac *= std::pow(err_prev2_, e3_);
  err_prev2_ = err_prev_;
  err_prev_ = std::max(err, kHistoryFloor);
  rejected_last_ = false;
  return {true, h * std::clamp(fac, kFacMin, fac_max)};
}

double FilterController::shrink(double h) {
  rejected_last_ = true;
  return h * kFacMin;
}

}  // namespace rb
