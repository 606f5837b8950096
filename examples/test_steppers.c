/*
 * Broken steppers for the tests (tests/integrators/test_plugin_stepper.cpp),
 * one per build-time variant (examples/CMakeLists.txt): the explicit
 * midpoint rule of midpoint_stepper.c, spoiled in exactly one way.
 *   RB_VARIANT_NO_STEP     does not export rollbench_stepper_step
 *   RB_VARIANT_BAD_ABI     reports ABI version 99
 *   RB_VARIANT_BAD_ORDER   declares order 0
 *   RB_VARIANT_BAD_NAME    declares a name with a space
 *   RB_VARIANT_FAILS       returns error code 7 with a reason from t >= 0.5
 *   RB_VARIANT_NAN         writes a NaN state from t >= 0.5
 */
#include <math.h>
#include <stdio.h>

#include "integrators/plugin/rollbench_stepper.h"

#ifdef RB_VARIANT_BAD_NAME
#undef RB_VARIANT_NAME
#define RB_VARIANT_NAME "bad name"
#endif
#ifdef RB_VARIANT_BAD_ORDER
#define RB_ORDER 0
#else
#define RB_ORDER 2
#endif

static const struct rollbench_stepper_info info = {RB_VARIANT_NAME, "plugin", RB_ORDER,
                                                   "a broken stepper for the tests", ROLLBENCH_VIEW_FLAT};

unsigned rollbench_stepper_abi_version(void) {
#ifdef RB_VARIANT_BAD_ABI
  return 99u;
#else
  return ROLLBENCH_STEPPER_ABI_VERSION;
#endif
}

const struct rollbench_stepper_info* rollbench_stepper_info(void) { return &info; }

#ifndef RB_VARIANT_NO_STEP
int rollbench_stepper_step(const struct rollbench_problem* problem, double t, double h,
                           const double y[ROLLBENCH_FLAT_SIZE], double y_next[ROLLBENCH_FLAT_SIZE], char* message,
                           size_t message_size) {
  double k[ROLLBENCH_FLAT_SIZE], mid[ROLLBENCH_FLAT_SIZE];
  (void)t;  /* the variants that fail look at it */
#ifdef RB_VARIANT_FAILS
  if (t >= 0.5) {
    snprintf(message, message_size, "the linear solve did not converge (residual %.1e)", 1e-3);
    return 7;
  }
#else
  (void)message;
  (void)message_size;
#endif
  problem->flat_rhs(problem->context, y, k);
  for (int i = 0; i < ROLLBENCH_FLAT_SIZE; ++i) mid[i] = y[i] + (0.5 * h) * k[i];
  problem->flat_rhs(problem->context, mid, k);
  for (int i = 0; i < ROLLBENCH_FLAT_SIZE; ++i) y_next[i] = y[i] + h * k[i];
#ifdef RB_VARIANT_NAN
  if (t >= 0.5) y_next[12] = NAN;
#endif
  return 0;
}
#endif
