"""librollbench_problem.so (problems/abi/rollbench_problem.h) through ctypes:
a scene's flat right-hand side, its Jacobian, the start and the model's
checks, as NumPy arrays."""
import ctypes
import os

import numpy as np

ABI_VERSION = 1
STATE_SIZE = 14
DERIVED_SIZE = 10
# rb_problem_code: the report's statuses
CODE_NAMES = {0: "ok", 1: "diverged", 2: "lift-off", 3: "curvature", 4: "domain", -1: "error"}

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DEFAULT_LIBRARY = os.environ.get("RB_PROBLEM_LIB") or os.path.join(ROOT, "build", "release",
                                                                   "librollbench_problem.so")


class ProblemError(Exception):
    """A scene the library refused, or a library of another ABI version."""


def load_library(path=DEFAULT_LIBRARY):
    try:
        lib = ctypes.CDLL(path)
    except OSError as e:
        raise ProblemError(f"cannot load the problem library '{path}' ({e}); build it with "
                           "cmake --build --preset release --target rollbench_problem") from None
    p, d, i, u, s = ctypes.c_void_p, ctypes.c_double, ctypes.c_int, ctypes.c_uint, ctypes.c_char_p
    signatures = {
        "rb_problem_abi_version": (u, []),
        "rb_problem_open": (p, [s, d, ctypes.c_char_p, ctypes.c_size_t]),
        "rb_problem_close": (None, [p]),
        "rb_problem_name": (s, [p]),
        "rb_problem_state_size": (i, [p]),
        "rb_problem_component_name": (s, [i]),
        "rb_problem_initial_state": (i, [p, p]),
        "rb_problem_t_end": (d, [p]),
        "rb_problem_rhs": (i, [p, d, p, p]),
        "rb_problem_jacobian": (i, [p, d, p, p]),
        "rb_problem_check": (i, [p, p]),
        "rb_problem_derived": (i, [p, p, p]),
        "rb_problem_derived_name": (s, [i]),
        "rb_problem_message": (s, [p]),
        "rb_problem_rhs_evals": (ctypes.c_long, [p]),
        "rb_problem_jacobian_evals": (ctypes.c_long, [p]),
        "rb_problem_reset_counters": (None, [p]),
    }
    for name, (restype, argtypes) in signatures.items():
        f = getattr(lib, name)
        f.restype, f.argtypes = restype, argtypes
    if lib.rb_problem_abi_version() != ABI_VERSION:
        raise ProblemError(f"'{path}' is built for ABI version {lib.rb_problem_abi_version()}, "
                           f"this peer for {ABI_VERSION}")
    return lib


class Problem:
    """One open scene. rhs(t, y) and jacobian(t, y) are what solve_ivp calls;
    each counts in the library and notes the first stage beyond the model."""

    def __init__(self, lib, scene, t_end=0.0):
        self.lib = lib
        error = ctypes.create_string_buffer(1024)
        # the path's bytes as typed (os.fsencode: a name that is not UTF-8 too); the library escapes it in messages
        handle = lib.rb_problem_open(os.fsencode(scene), float(t_end), error, len(error))
        if not handle:
            raise ProblemError(error.value.decode("utf-8", "backslashreplace"))
        self.handle = handle
        self.name = lib.rb_problem_name(handle).decode()
        self.t_end = lib.rb_problem_t_end(handle)
        self.components = [lib.rb_problem_component_name(k).decode() for k in range(STATE_SIZE)]
        self.derived_names = [lib.rb_problem_derived_name(k).decode() for k in range(DERIVED_SIZE)]
        self.y0 = np.empty(STATE_SIZE)
        lib.rb_problem_initial_state(handle, self.y0.ctypes.data)
        self._rhs, self._jac = lib.rb_problem_rhs, lib.rb_problem_jacobian
        self.stages_beyond = 0  # stages that returned a model limit since reset()

    def close(self):
        if self.handle:
            self.lib.rb_problem_close(self.handle)
            self.handle = None

    def __enter__(self):
        return self

    def __exit__(self, *_):
        self.close()

    def rhs(self, t, y):
        y = np.ascontiguousarray(y, dtype=float)
        dy = np.empty(STATE_SIZE)
        if self._rhs(self.handle, t, y.ctypes.data, dy.ctypes.data) != 0:
            self.stages_beyond += 1
        return dy

    def jacobian(self, t, y):
        y = np.ascontiguousarray(y, dtype=float)
        J = np.empty((STATE_SIZE, STATE_SIZE))
        self._jac(self.handle, t, y.ctypes.data, J.ctypes.data)
        return J

    def rhs_code(self, y):
        """(code, message) of one evaluation at y."""
        y = np.ascontiguousarray(y, dtype=float)
        dy = np.empty(STATE_SIZE)
        code = self._rhs(self.handle, 0.0, y.ctypes.data, dy.ctypes.data)
        return code, self.lib.rb_problem_message(self.handle).decode()

    def check(self, y):
        """(status name, reason) of every check of the model at the state y."""
        y = np.ascontiguousarray(y, dtype=float)
        code = self.lib.rb_problem_check(self.handle, y.ctypes.data)
        return CODE_NAMES.get(code, "error"), self.lib.rb_problem_message(self.handle).decode()

    def derived(self, y):
        y = np.ascontiguousarray(y, dtype=float)
        out = np.empty(DERIVED_SIZE)
        self.lib.rb_problem_derived(self.handle, y.ctypes.data, out.ctypes.data)
        return out

    def counts(self):
        return self.lib.rb_problem_rhs_evals(self.handle), self.lib.rb_problem_jacobian_evals(self.handle)

    def reset(self):
        self.lib.rb_problem_reset_counters(self.handle)
        self.stages_beyond = 0
