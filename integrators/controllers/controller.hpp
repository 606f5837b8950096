#pragma once
// Step-size controllers: the part of an adaptive integrator that turns a
// step's error estimate into a decision (accept or reject) and the next step.
// A stepper that estimates its error leaves the decision to one of these;
// a library's stepper (odeint, GSL) brings its own, "library".
//
// The suite's controllers are Söderlind's digital filters on the error
// history (Digital filters in adaptive time-stepping, ACM TOMS 29, 2003):
// after an accepted step of h with error norm err_n (<= 1 meets the
// tolerance; k the order of the estimate),
//   h_new = h * clamp(safety * err_n^(-b1/k) err_n-1^(-b2/k) err_n-2^(-b3/k),
//                     fac_min, fac_max)
// with fac_max = 1 right after a rejection; a rejected step shrinks by the
// elementary rule h * max(fac_min, safety * err^(-1/k)).
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace rb {

// What a controller is called (RunOptions::controller, `--controller`, the
// report) and the filter it applies.
struct ControllerKind {
  const char* name;
  double b1, b2, b3;  // the exponents above, times k
  const char* what;   // one line for `rollbench list` and the docs
};

// "constant": fixed steps of h, landing on the outputs (no error estimate);
// "library": the library stepper's own controller (odeint, GSL);
// "i": the elementary controller (b = 1, 0, 0);
// "pi": Gustafsson's PI (b = 0.7, -0.4, 0), the RKMK pairs' default;
// "pid": Söderlind's H312PID (b = 1/18, 1/9, 1/18), a smoother step sequence.
inline constexpr const char* kConstantController = "constant";
inline constexpr const char* kLibraryController = "library";

// The filters: i, pi, pid.
const std::vector<ControllerKind>& filter_controllers();

// Every controller name, "constant" and "library" included, for messages.
std::string controller_names();

// The filter called name; throws InputError (key "controller") naming the
// known ones when there is none.
const ControllerKind& filter_controller(std::string_view name);

// What a way of stepping that takes only some controllers does with the one
// its registry line names: nothing when it is among supported, otherwise
// InputError (key "controller") naming the method, what it is and what it
// takes, e.g. "'dg2': the discrete-gradient method takes the controller
// 'constant' only, not 'pi'".
void require_controller(std::string_view controller, std::initializer_list<std::string_view> supported,
                        std::string_view method, std::string_view way);

// The name as a description writes it: "pi" -> "PI".
std::string controller_title(std::string_view name);

// What a controller decided about one attempt.
struct StepDecision {
  bool accepted = false;
  double h_next = 0.0;  // the step to try next
};

// A filter controller's state over one run.
class FilterController {
 public:
  // error_order: k, the order of the error estimate (err = O(h^k)).
  FilterController(const ControllerKind& kind, int error_order);

  // The decision after a step of h whose error norm is err (finite, >= 0).
  StepDecision decide(double err, double h);

  // A step that left where the right-hand side is finite: reject and
  // shrink hard (as odeint and GSL do).
  double shrink(double h);

 private:
  double e1_, e2_, e3_;  // -b_i / k
  double k_inv_;         // 1 / k
  double err_prev_ = 1e-4, err_prev2_ = 1e-4;
  bool rejected_last_ = false;
};

}  // namespace rb
