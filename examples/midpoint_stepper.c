/*
 * A stepper from outside rollbench: the explicit midpoint rule on the flat
 * view, y_{n+1} = y_n + h F(y_n + h/2 F(y_n)), in plain C against
 * integrators/plugin/rollbench_stepper.h and nothing else of the suite.
 *
 *   cc -O2 -shared -fPIC -I path/to/rollbench examples/midpoint_stepper.c -o libmidpoint_stepper.so
 *   rollbench run --stepper ./libmidpoint_stepper.so --integrators midpoint-plugin,midpoint ...
 *
 * It does the same arithmetic as the built-in `midpoint`
 * (integrators/steppers/explicit_midpoint.hpp), so the two give the same numbers.
 */
#include "integrators/plugin/rollbench_stepper.h"

static const struct rollbench_stepper_info info = {
    "midpoint-plugin", "plugin", 2, "explicit midpoint rule in C, loaded with --stepper (examples/midpoint_stepper.c)",
    ROLLBENCH_VIEW_FLAT};

unsigned rollbench_stepper_abi_version(void) { return ROLLBENCH_STEPPER_ABI_VERSION; }

const struct rollbench_stepper_info* rollbench_stepper_info(void) { return &info; }

int rollbench_stepper_step(const struct rollbench_problem* problem, double t, double h,
                           const double y[ROLLBENCH_FLAT_SIZE], double y_next[ROLLBENCH_FLAT_SIZE], char* message,
                           size_t message_size) {
  /* stage storage on the stack: reentrant, no allocation per step */
  double k[ROLLBENCH_FLAT_SIZE], mid[ROLLBENCH_FLAT_SIZE];
  (void)t;
  (void)message;
  (void)message_size;
  problem->flat_rhs(problem->context, y, k);
  for (int i = 0; i < ROLLBENCH_FLAT_SIZE; ++i) mid[i] = y[i] + (0.5 * h) * k[i];
  problem->flat_rhs(problem->context, mid, k);
  for (int i = 0; i < ROLLBENCH_FLAT_SIZE; ++i) y_next[i] = y[i] + h * k[i];
  return 0;
}
