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
 *   RB_VARIANT_BAD_UTF8    fails like FAILS with a reason holding the bytes 0xFF 0xFE
 *   RB_VARIANT_CRASH       dereferences a null pointer (SIGSEGV) from t >= 0.5
 *   RB_VARIANT_ABORT       calls abort() (SIGABRT) from t >= 0.5
 *   RB_VARIANT_HANG        spins forever from t >= 0.5
 *   RB_VARIANT_CTOR_SEGV   raises SIGSEGV in its constructor (at dlopen)
 *   RB_VARIANT_INFO_NULL   rollbench_stepper_info() returns NULL from its second call
 *   RB_VARIANT_FORKS       forks a grandchild that holds every open descriptor for 60 s
 *                          and writes its pid to $RB_TEST_GRANDCHILD_PID_FILE
 *   RB_VARIANT_FLOOD       writes 400 MiB to every descriptor from 3 to 63 at t >= 0.5
 *   RB_VARIANT_EXIT        calls exit(3) at t >= 0.5
 *   RB_VARIANT_OFF_GROUP   a Lie-view exponential Euler step that, from
 *                          t >= 0.5, scales R by 1.1 (R^T R = 1.21 I)
 */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

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

#ifdef RB_VARIANT_OFF_GROUP
#define RB_VIEW ROLLBENCH_VIEW_LIE
#undef RB_ORDER
#define RB_ORDER 1
#else
#define RB_VIEW ROLLBENCH_VIEW_FLAT
#endif

static const struct rollbench_stepper_info info = {RB_VARIANT_NAME, "plugin", RB_ORDER,
                                                   "a broken stepper for the tests", RB_VIEW};

unsigned rollbench_stepper_abi_version(void) {
#ifdef RB_VARIANT_BAD_ABI
  return 99u;
#else
  return ROLLBENCH_STEPPER_ABI_VERSION;
#endif
}

#ifdef RB_VARIANT_CTOR_SEGV
__attribute__((constructor)) static void crash_at_load(void) { raise(SIGSEGV); }
#endif

#ifdef RB_VARIANT_INFO_NULL
const struct rollbench_stepper_info* rollbench_stepper_info(void) {
  static int calls = 0;
  return calls++ == 0 ? &info : NULL;
}
#else
const struct rollbench_stepper_info* rollbench_stepper_info(void) { return &info; }
#endif

#ifdef RB_VARIANT_OFF_GROUP
/* examples/lie_euler_stepper.c, spoiled from t >= 0.5 */
int rollbench_stepper_step(const struct rollbench_problem* problem, double t, double h,
                           const double y[ROLLBENCH_FLAT_SIZE], double y_next[ROLLBENCH_FLAT_SIZE], char* message,
                           size_t message_size) {
  const double* R = y;
  const double* z = y + 9;
  double omega[3], dz[ROLLBENCH_Z_SIZE], u[3], E[9];
  const double scale = t >= 0.5 ? 1.1 : 1.0;
  (void)message;
  (void)message_size;
  problem->lie_rhs(problem->context, R, z, omega, dz);
  for (int i = 0; i < 3; ++i) u[i] = h * omega[i];
  problem->so3_exp(problem->context, u, E);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      y_next[3 * i + j] = scale * (E[3 * i + 0] * R[0 + j] + E[3 * i + 1] * R[3 + j] + E[3 * i + 2] * R[6 + j]);
  for (int i = 0; i < ROLLBENCH_Z_SIZE; ++i) y_next[9 + i] = z[i] + h * dz[i];
  return 0;
}
#elif !defined(RB_VARIANT_NO_STEP)
int rollbench_stepper_step(const struct rollbench_problem* problem, double t, double h,
                           const double y[ROLLBENCH_FLAT_SIZE], double y_next[ROLLBENCH_FLAT_SIZE], char* message,
                           size_t message_size) {
  double k[ROLLBENCH_FLAT_SIZE], mid[ROLLBENCH_FLAT_SIZE];
  (void)t; /* the variants that fail look at it */
#ifdef RB_VARIANT_FAILS
  if (t >= 0.5) {
    snprintf(message, message_size, "the linear solve did not converge (residual %.1e)", 1e-3);
    return 7;
  }
#elif defined(RB_VARIANT_BAD_UTF8)
  if (t >= 0.5) {
    snprintf(message, message_size, "bad bytes \xff\xfe in the reason");
    return 5;
  }
#else
  (void)message;
  (void)message_size;
#endif
#ifdef RB_VARIANT_CRASH
  if (t >= 0.5) {
    volatile int* volatile nowhere = NULL;
    *nowhere = 1;
  }
#endif
#ifdef RB_VARIANT_ABORT
  if (t >= 0.5) abort();
#endif
#ifdef RB_VARIANT_EXIT
  if (t >= 0.5) exit(3);
#endif
#ifdef RB_VARIANT_FORKS
  {
    static int forked = 0;
    if (!forked) {
      forked = 1;
      const pid_t grandchild = fork();
      if (grandchild > 0) { /* the child names it before going on */
        const char* file = getenv("RB_TEST_GRANDCHILD_PID_FILE");
        FILE* out = file != NULL ? fopen(file, "w") : NULL;
        if (out != NULL) {
          fprintf(out, "%d\n", (int)grandchild);
          fclose(out);
        }
      } else if (grandchild == 0) {
        sleep(60);
        _exit(0);
      }
    }
  }
#endif
#ifdef RB_VARIANT_FLOOD
  if (t >= 0.5) {
    static char block[1 << 20];
    memset(block, 'x', sizeof block);
    for (int fd = 3; fd < 64; ++fd)
      for (int i = 0; i < 400; ++i)
        if (write(fd, block, sizeof block) < 0) break;
  }
#endif
#ifdef RB_VARIANT_HANG
  if (t >= 0.5) {
    volatile int spin = 1;
    while (spin) {
    }
  }
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
