/*
 * rollbench_problem.h: the C ABI of the problem itself, for programs outside
 * rollbench (SciPy through ctypes, Julia, Fortran, ...) that want to solve the
 * very problem the suite benchmarks and have `rollbench score` measure it.
 *
 * librollbench_problem.so (built by the release preset) loads a scene as
 * `rollbench run` does and offers its flat view y' = F(y) on R^14: the same
 * right-hand side, compiled from the same source with the same flags, as the
 * suite's flat methods call, its exact Jacobian, the start and the model's
 * limits. docs/peers.md describes it with an example.
 *
 * The state, 14 doubles (rb_problem_component_name gives the names):
 *   y[0..8]   R, the orientation (body to world), row by row: r00 ... r22;
 *   y[9..11]  v = T omega, the angular momentum about the contact point:
 *             v0, v1, v2 (world frame);
 *   y[12..13] alpha = (x, y), the contact point.
 *
 * Rules:
 *   - Nothing crashes on bad input: a scene that cannot be loaded gives NULL
 *     and the loader's message (naming the file and the key); a NULL handle
 *     or array gives ROLLBENCH_PROBLEM_BAD_ARGUMENT.
 *   - A handle is not thread-safe (it counts evaluations and keeps the last
 *     message); open one per thread. Every array is the caller's.
 */
#ifndef ROLLBENCH_PROBLEM_H
#define ROLLBENCH_PROBLEM_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The version of this ABI; bumped on any change to the functions below. */
#define ROLLBENCH_PROBLEM_ABI_VERSION 1u

#define ROLLBENCH_PROBLEM_STATE_SIZE 14   /* R (9), v (3), alpha (2) */
#define ROLLBENCH_PROBLEM_DERIVED_SIZE 10 /* what rb_problem_derived writes */

/* What rb_problem_rhs, rb_problem_jacobian and rb_problem_check return: 0,
 * or the limit of the model the state is beyond (the report's statuses
 * diverged, lift-off, curvature, domain; rb_problem_message says why), or a
 * bad argument. */
enum rb_problem_code {
  ROLLBENCH_PROBLEM_OK = 0,
  ROLLBENCH_PROBLEM_DIVERGED = 1,  /* the state or the landscape at it is not finite */
  ROLLBENCH_PROBLEM_LIFT_OFF = 2,  /* the normal force F . N <= 0 */
  ROLLBENCH_PROBLEM_CURVATURE = 3, /* r max curvature >= 1, or E singular */
  ROLLBENCH_PROBLEM_DOMAIN = 4,    /* the contact point left the scene's domain */
  ROLLBENCH_PROBLEM_BAD_ARGUMENT = -1
};

typedef struct rb_problem rb_problem; /* opaque */

/* ROLLBENCH_PROBLEM_ABI_VERSION as the library was built. */
unsigned rb_problem_abi_version(void);

/* Loads a scene: a shipped scene's name ("chaplygin-valley") or a scene JSON
 * file's path. NULL on failure, with a NUL-terminated message (at most
 * error_size bytes) in error when error is not NULL. t_end > 0 shortens the
 * scene's end time to at most t_end (as `rollbench run --t-end`); 0 keeps it. */
rb_problem* rb_problem_open(const char* scene, double t_end, char* error, size_t error_size);

/* Frees a handle; NULL is fine. */
void rb_problem_close(rb_problem* problem);

/* The scene's name; "" for NULL. Lives as long as the handle. */
const char* rb_problem_name(const rb_problem* problem);

/* ROLLBENCH_PROBLEM_STATE_SIZE (14); -1 for NULL. */
int rb_problem_state_size(const rb_problem* problem);

/* The name of flat component i ("r00" ... "r22", "v0", "v1", "v2", "x", "y")
 * and its offset is i; NULL for i outside 0..13. */
const char* rb_problem_component_name(int i);

/* The start y0 into y0[14]; 0, or ROLLBENCH_PROBLEM_BAD_ARGUMENT. */
int rb_problem_initial_state(const rb_problem* problem, double* y0);

/* The end time (the scene's, or the one given to open); NaN for NULL. */
double rb_problem_t_end(const rb_problem* problem);

/* dy = F(y) (the problem is autonomous: t is for the caller's convenience
 * and unused). Always writes dy and counts one evaluation; returns 0, or the
 * code of the model's limit the state is beyond (the validity margins of the
 * same evaluation, the test the suite's drivers make after each step; the
 * domain is not looked at: see rb_problem_check). */
int rb_problem_rhs(rb_problem* problem, double t, const double* y, double* dy);

/* J = dF/dy at y, 14 x 14 row by row (J[14 i + j] = dF_i/dy_j), exact (forward
 * automatic differentiation), costing about 14 evaluations of F; counts one
 * Jacobian evaluation. Returns 0, or ROLLBENCH_PROBLEM_DIVERGED when J is not
 * finite, or ROLLBENCH_PROBLEM_BAD_ARGUMENT. */
int rb_problem_jacobian(rb_problem* problem, double t, const double* y, double* jacobian);

/* Every check of the model at a state, as the suite makes at each accepted
 * state: finite, inside the domain, then the model's limits. Not counted as
 * an evaluation. */
int rb_problem_check(rb_problem* problem, const double* y);

/* The quantities of the trajectory CSV (docs/formats.md) the state does not
 * hold, as `rollbench trajectory` writes them: the centre cx, cy, cz; omega
 * (world frame) wx, wy, wz; energy, normal_force, spin, rotation_defect
 * (rb_problem_derived_name gives the names). Not counted as an evaluation.
 * Returns 0 or ROLLBENCH_PROBLEM_BAD_ARGUMENT. */
int rb_problem_derived(const rb_problem* problem, const double* y, double* derived);
const char* rb_problem_derived_name(int i); /* NULL for i outside 0..9 */

/* Why the last call on this handle returned a non-zero code ("the normal
 * force fell to -0.25", ...); "" after a 0. Lives until the next call. */
const char* rb_problem_message(const rb_problem* problem);

/* Evaluations since open or the last reset; -1 for NULL. */
long rb_problem_rhs_evals(const rb_problem* problem);
long rb_problem_jacobian_evals(const rb_problem* problem);
void rb_problem_reset_counters(rb_problem* problem);

#ifdef __cplusplus
}
#endif

#endif /* ROLLBENCH_PROBLEM_H */
