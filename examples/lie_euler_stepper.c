/*
 * A Lie-group stepper from outside rollbench: the exponential Euler method,
 * R_{n+1} = exp(h hat(omega(R_n, z_n))) R_n, z_{n+1} = z_n + h G(R_n, z_n),
 * through the ABI's Lie-group right-hand side and its so(3) exponential
 * (integrators/plugin/rollbench_stepper.h). R stays on SO(3) to rounding.
 */
#include "integrators/plugin/rollbench_stepper.h"

static const struct rollbench_stepper_info info = {
    "exp-euler-plugin", "plugin", 1,
    "exponential (Lie) Euler in C, loaded with --stepper (examples/lie_euler_stepper.c)", ROLLBENCH_VIEW_LIE};

unsigned rollbench_stepper_abi_version(void) { return ROLLBENCH_STEPPER_ABI_VERSION; }

const struct rollbench_stepper_info* rollbench_stepper_info(void) { return &info; }

int rollbench_stepper_step(const struct rollbench_problem* problem, double t, double h,
                           const double y[ROLLBENCH_FLAT_SIZE], double y_next[ROLLBENCH_FLAT_SIZE], char* message,
                           size_t message_size) {
  const double* R = y;     /* y[0..8]: R row by row */
  const double* z = y + 9; /* y[9..13]: z = (v, alpha) */
  double omega[3], dz[ROLLBENCH_Z_SIZE], u[3], E[9];
  (void)t;
  (void)message;
  (void)message_size;
  problem->lie_rhs(problem->context, R, z, omega, dz);
  for (int i = 0; i < 3; ++i) u[i] = h * omega[i];
  problem->so3_exp(problem->context, u, E);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      y_next[3 * i + j] = E[3 * i + 0] * R[0 + j] + E[3 * i + 1] * R[3 + j] + E[3 * i + 2] * R[6 + j];
  for (int i = 0; i < ROLLBENCH_Z_SIZE; ++i) y_next[9 + i] = z[i] + h * dz[i];
  return 0;
}
