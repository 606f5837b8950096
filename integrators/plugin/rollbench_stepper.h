/*
 * rollbench_stepper.h: the C ABI of a stepper built outside rollbench.
 *
 * A shared library built against this header (and nothing else of
 * rollbench) is loaded by `rollbench run|trajectory|list --stepper
 * PATH.so` and driven by the suite's own fixed-step driver, like a built-in
 * method: the same right-hand side, the same counters, the same validity
 * checks after every step, the same timing. The library exports three
 * functions, with C linkage:
 *
 *   unsigned rollbench_stepper_abi_version(void);
 *       returns ROLLBENCH_STEPPER_ABI_VERSION as the library was built;
 *       rollbench refuses a library built for another version.
 *
 *   const struct rollbench_stepper_info* rollbench_stepper_info(void);
 *       the method's facts, in storage that lives as long as the library.
 *
 *   int rollbench_stepper_step(const struct rollbench_problem* problem,
 *                              double t, double h,
 *                              const double y[ROLLBENCH_FLAT_SIZE],
 *                              double y_next[ROLLBENCH_FLAT_SIZE],
 *                              char* message, size_t message_size);
 *       one step from (t, y) to t + h: writes the new state into y_next
 *       (never the same array as y) and returns 0, or returns a non-zero
 *       error code and may write a NUL-terminated reason (at most
 *       message_size bytes, NUL included) into message; the run then ends
 *       with status "error" and that reason, at the last state before it.
 *
 * The state (the problem's flat view, docs/model.md), 14 doubles:
 *   y[0..8]   R, the orientation (body to world), row by row;
 *   y[9..11]  v = T omega, the angular momentum about the contact point;
 *   y[12..13] alpha = (x, y), the contact point.
 * The Lie-group view keeps R apart and integrates z = y[9..13] (5 doubles):
 * R' = hat(omega(R, z)) R, z' = G(R, z).
 *
 * Rules for a stepper:
 *   - Evaluate the problem only through the callbacks in *problem: rollbench
 *     counts every call (rhs_evals, exp_evals, dexpinv_evals in the report),
 *     exactly as it counts a built-in method's.
 *   - Be reentrant: rollbench runs many runs at once on several threads,
 *     each with its own problem pointer; keep no mutable global state and
 *     keep stage storage on the stack (no allocation per step).
 *   - Do not crash: a failure is a non-zero return. A non-finite y_next is
 *     the usual "diverged" status; rollbench checks it, so you need not.
 *   - Fixed steps only: rollbench picks h (it lands on output times, so h
 *     may be slightly shorter than the nominal step on the last step before
 *     an output).
 */
#ifndef ROLLBENCH_STEPPER_H
#define ROLLBENCH_STEPPER_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The version of this ABI; bumped on any change to the structs or the
 * exported functions. */
#define ROLLBENCH_STEPPER_ABI_VERSION 1u

#define ROLLBENCH_FLAT_SIZE 14 /* flat state: R (9), v (3), alpha (2) */
#define ROLLBENCH_Z_SIZE 5     /* Lie-group view's z = (v, alpha) */

/* Which view of the problem the method integrates (rollbench reports it). */
enum rollbench_view {
  ROLLBENCH_VIEW_FLAT = 0, /* y' = F(y) on R^14: R may drift off SO(3) */
  ROLLBENCH_VIEW_LIE = 1   /* R on SO(3) through so(3) exponentials */
};

/* The problem as the stepper sees it: callbacks into rollbench and an
 * opaque context to pass back to each. All arrays are the caller's. */
struct rollbench_problem {
  void* context; /* pass to every callback unchanged */

  /* The flat right-hand side dy = F(y), 14 doubles each (one rhs_eval). */
  void (*flat_rhs)(void* context, const double y[ROLLBENCH_FLAT_SIZE], double dy[ROLLBENCH_FLAT_SIZE]);

  /* The Lie-group right-hand side at orientation R (row by row, 9
   * doubles): omega(R, z) in the world frame (3 doubles) and dz = G(R, z)
   * (5 doubles); one rhs_eval. */
  void (*lie_rhs)(void* context, const double R[9], const double z[ROLLBENCH_Z_SIZE], double omega[3],
                  double dz[ROLLBENCH_Z_SIZE]);

  /* R = exp(hat(u)) by Rodrigues' formula, row by row (one exp_eval). */
  void (*so3_exp)(void* context, const double u[3], double R[9]);

  /* out = dexpinv_u(w), the inverse of the derivative of exp at u applied
   * to w, in closed form (one dexpinv_eval); NaN when |u| is near 2 pi,
   * where it has a pole. */
  void (*so3_dexpinv)(void* context, const double u[3], const double w[3], double out[3]);
};

/* The method's facts. name: the registry name (letters, digits and
 * . _ + -; not one rollbench already has); family: a short group name for
 * the plots (e.g. "rk"); order >= 1: the declared order the report tests;
 * description: one line for `rollbench list`; view: a rollbench_view. */
struct rollbench_stepper_info {
  const char* name;
  const char* family;
  int order;
  const char* description;
  int view;
};

/* The three symbols a stepper library exports. */
unsigned rollbench_stepper_abi_version(void);
const struct rollbench_stepper_info* rollbench_stepper_info(void);
int rollbench_stepper_step(const struct rollbench_problem* problem, double t, double h,
                           const double y[ROLLBENCH_FLAT_SIZE], double y_next[ROLLBENCH_FLAT_SIZE], char* message,
                           size_t message_size);

#ifdef __cplusplus
}
#endif

#endif /* ROLLBENCH_STEPPER_H */
