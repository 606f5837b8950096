// rb_problem: the problem library's C ABI (problems/abi/rollbench_problem.h)
// as one Octave function, so that Octave's solvers call the very
// right-hand side the suite's methods call. Built by analysis/peers/
// octave_peer.py with mkoctfile; the library is opened with dlopen at
// "load", so the oct-file is not tied to one build.
//
//   rb_problem("load", LIBRARY)              -> ABI version
//   [id, name, t_end, y0] = rb_problem("open", SCENE, T_END)
//   dy = rb_problem("rhs", id, t, y)         (counts; a state beyond the model counts as "beyond")
//   J = rb_problem("jacobian", id, t, y)
//   [code, message] = rb_problem("check", id, y)
//   [rhs_evals, jacobian_evals, beyond] = rb_problem("counts", id)
//   rb_problem("reset", id), rb_problem("close", id)
#include <dlfcn.h>
#include <octave/oct.h>

#include <map>
#include <string>

#include "rollbench_problem.h"

namespace {

struct Api {
  void* library = nullptr;
  decltype(&rb_problem_abi_version) abi_version = nullptr;
  decltype(&rb_problem_open) open = nullptr;
  decltype(&rb_problem_close) close = nullptr;
  decltype(&rb_problem_name) name = nullptr;
  decltype(&rb_problem_initial_state) initial_state = nullptr;
  decltype(&rb_problem_t_end) t_end = nullptr;
  decltype(&rb_problem_rhs) rhs = nullptr;
  decltype(&rb_problem_jacobian) jacobian = nullptr;
  decltype(&rb_problem_check) check = nullptr;
  decltype(&rb_problem_message) message = nullptr;
  decltype(&rb_problem_rhs_evals) rhs_evals = nullptr;
  decltype(&rb_problem_jacobian_evals) jacobian_evals = nullptr;
  decltype(&rb_problem_reset_counters) reset = nullptr;
};

struct Handle {
  rb_problem* problem = nullptr;
  long beyond = 0;  // rhs calls at a state beyond the model since the last reset
};

Api api;
std::map<int, Handle> handles;
int next_id = 1;

template <class F>
void bind(F& f, const char* symbol) {
  f = reinterpret_cast<F>(::dlsym(api.library, symbol));
  if (!f) error("rb_problem: the library has no symbol %s", symbol);
}

void load(const std::string& path) {
  if (api.library) return;
  api.library = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!api.library) error("rb_problem: cannot load '%s' (%s)", path.c_str(), ::dlerror());
  bind(api.abi_version, "rb_problem_abi_version");
  bind(api.open, "rb_problem_open");
  bind(api.close, "rb_problem_close");
  bind(api.name, "rb_problem_name");
  bind(api.initial_state, "rb_problem_initial_state");
  bind(api.t_end, "rb_problem_t_end");
  bind(api.rhs, "rb_problem_rhs");
  bind(api.jacobian, "rb_problem_jacobian");
  bind(api.check, "rb_problem_check");
  bind(api.message, "rb_problem_message");
  bind(api.rhs_evals, "rb_problem_rhs_evals");
  bind(api.jacobian_evals, "rb_problem_jacobian_evals");
  bind(api.reset, "rb_problem_reset_counters");
  if (api.abi_version() != ROLLBENCH_PROBLEM_ABI_VERSION)
    error("rb_problem: '%s' is built for ABI version %u, this oct-file for %u", path.c_str(), api.abi_version(),
          ROLLBENCH_PROBLEM_ABI_VERSION);
}

Handle& handle_of(const octave_value& id) {
  if (!api.library) error("rb_problem: call rb_problem(\"load\", LIBRARY) first");
  const auto found = handles.find(id.int_value());
  if (found == handles.end()) error("rb_problem: no open problem %d", id.int_value());
  return found->second;
}

// y as 14 doubles, from a column or row vector
ColumnVector state_of(const octave_value& y) {
  const ColumnVector v = y.column_vector_value();
  if (v.numel() != ROLLBENCH_PROBLEM_STATE_SIZE)
    error("rb_problem: a state has %d entries, not %ld", ROLLBENCH_PROBLEM_STATE_SIZE, static_cast<long>(v.numel()));
  return v;
}

}  // namespace

DEFUN_DLD(rb_problem, args, , "rb_problem(COMMAND, ...): the rollbench problem library (see rb_problem.cc)") {
  if (args.length() < 1) print_usage();
  const std::string command = args(0).string_value();
  const auto need = [&](int n) {
    if (args.length() != n) error("rb_problem: \"%s\" takes %d arguments", command.c_str(), n - 1);
  };
  if (command == "load") {
    need(2);
    load(args(1).string_value());
    return ovl(static_cast<double>(api.abi_version()));
  }
  if (command == "open") {
    need(3);
    if (!api.library) error("rb_problem: call rb_problem(\"load\", LIBRARY) first");
    char message[1024] = "";
    rb_problem* p = api.open(args(1).string_value().c_str(), args(2).double_value(), message, sizeof message);
    if (!p) error("%s", message);
    const int id = next_id++;
    handles[id] = Handle{p, 0};
    ColumnVector y0(ROLLBENCH_PROBLEM_STATE_SIZE);
    api.initial_state(p, y0.fortran_vec());
    return ovl(static_cast<double>(id), std::string(api.name(p)), api.t_end(p), y0);
  }
  if (command == "rhs") {
    need(4);
    Handle& h = handle_of(args(1));
    const ColumnVector y = state_of(args(3));
    ColumnVector dy(ROLLBENCH_PROBLEM_STATE_SIZE);
    if (api.rhs(h.problem, args(2).double_value(), y.data(), dy.fortran_vec()) != ROLLBENCH_PROBLEM_OK) ++h.beyond;
    return ovl(dy);
  }
  if (command == "jacobian") {
    need(4);
    Handle& h = handle_of(args(1));
    const ColumnVector y = state_of(args(3));
    double j[ROLLBENCH_PROBLEM_STATE_SIZE * ROLLBENCH_PROBLEM_STATE_SIZE];
    api.jacobian(h.problem, args(2).double_value(), y.data(), j);
    Matrix out(ROLLBENCH_PROBLEM_STATE_SIZE, ROLLBENCH_PROBLEM_STATE_SIZE);
    for (int r = 0; r < ROLLBENCH_PROBLEM_STATE_SIZE; ++r)
      for (int c = 0; c < ROLLBENCH_PROBLEM_STATE_SIZE; ++c) out(r, c) = j[r * ROLLBENCH_PROBLEM_STATE_SIZE + c];
    return ovl(out);
  }
  if (command == "check") {
    need(3);
    Handle& h = handle_of(args(1));
    const ColumnVector y = state_of(args(2));
    const int code = api.check(h.problem, y.data());
    return ovl(static_cast<double>(code), std::string(api.message(h.problem)));
  }
  if (command == "counts") {
    need(2);
    const Handle& h = handle_of(args(1));
    return ovl(static_cast<double>(api.rhs_evals(h.problem)), static_cast<double>(api.jacobian_evals(h.problem)),
               static_cast<double>(h.beyond));
  }
  if (command == "reset") {
    need(2);
    Handle& h = handle_of(args(1));
    api.reset(h.problem);
    h.beyond = 0;
    return ovl();
  }
  if (command == "close") {
    need(2);
    const Handle& h = handle_of(args(1));
    api.close(h.problem);
    handles.erase(args(1).int_value());
    return ovl();
  }
  error("rb_problem: unknown command \"%s\" (load, open, rhs, jacobian, check, counts, reset, close)", command.c_str());
}
