#include "integrators/steppers/plugin_stepper.hpp"

#include <dlfcn.h>
#include <sys/wait.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <vector>

#include "integrators/driver.hpp"
#include "problems/input_error.hpp"
#include "problems/so3.hpp"
#include "problems/state.hpp"
#include "problems/utf8.hpp"
#include "problems/whole_number.hpp"

namespace rb {

namespace {

using AbiVersionFn = unsigned (*)();
using InfoFn = const struct rollbench_stepper_info* (*)();
using StepFn = int (*)(const rollbench_problem*, double, double, const double*, double*, char*, size_t);

// the callbacks: evaluate through the Problem and count like a built-in step
void flat_rhs_callback(void* c, const double* y, double* dy) {
  auto& context = *static_cast<PluginCallContext*>(c);
  stage_flat_rhs(*context.problem, y, dy, *context.cost);
  ++context.cost->rhs_evals;
}

void lie_rhs_callback(void* c, const double* R, const double* z, double* omega, double* dz) {
  auto& context = *static_cast<PluginCallContext*>(c);
  stage_lie_rhs(*context.problem, Mat3(Eigen::Map<const RowMajorMat3>(R)), z, omega, dz, *context.cost);
  ++context.cost->rhs_evals;
}

void so3_exp_callback(void* c, const double* u, double* R) {
  auto& context = *static_cast<PluginCallContext*>(c);
  Eigen::Map<RowMajorMat3> rotation(R);
  rotation = so3_exp(Eigen::Map<const Vec3>(u));
  ++context.cost->exp_evals;
}

void so3_dexpinv_callback(void* c, const double* u, const double* w, double* out) {
  auto& context = *static_cast<PluginCallContext*>(c);
  Eigen::Map<Vec3> result(out);
  result = dexpinv(Eigen::Map<const Vec3>(u), Eigen::Map<const Vec3>(w));
  ++context.cost->dexpinv_evals;
}

// The library's three symbols, after its ABI version was checked.
struct OpenedLibrary {
  void* handle;
  InfoFn info;
  StepFn step;
};

// dlopen of absolute (path names it in the messages), its symbols and its
// ABI version; throws InputError under key "stepper". This runs the
// library's constructors: in a child process unless isolation is none.
OpenedLibrary open_library(const std::string& path, const std::string& absolute) {
  void* library = dlopen(absolute.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (library == nullptr) {
    const char* why = dlerror();
    throw InputError("'" + path + "' is not a shared library that can be loaded (" +
                         (why != nullptr ? std::string(why) : std::string("dlopen failed")) + ")",
                     "stepper");
  }
  try {
    auto symbol = [&](const char* name) {
      void* address = dlsym(library, name);
      if (address == nullptr)
        throw InputError("'" + path + "' does not export '" + name + "' (see integrators/plugin/rollbench_stepper.h)",
                         "stepper");
      return address;
    };
    const auto abi_version = reinterpret_cast<AbiVersionFn>(symbol("rollbench_stepper_abi_version"));
    const auto info = reinterpret_cast<InfoFn>(symbol("rollbench_stepper_info"));
    const auto step = reinterpret_cast<StepFn>(symbol("rollbench_stepper_step"));
    if (const unsigned version = abi_version(); version != ROLLBENCH_STEPPER_ABI_VERSION)
      throw InputError("'" + path + "': rollbench_stepper_abi_version() is " + std::to_string(version) +
                           ", this rollbench takes " + std::to_string(ROLLBENCH_STEPPER_ABI_VERSION) +
                           " (rebuild it against integrators/plugin/rollbench_stepper.h)",
                       "stepper");
    return {library, info, step};
  } catch (...) {
    dlclose(library);  // nothing of it was registered
    throw;
  }
}

class PluginStepper final : public Integrator {
 public:
  // step: the library's step in this process (isolation none), or null
  // and library the file each child opens again (isolation process)
  PluginStepper(MethodInfo facts, StepFn step, std::string library, bool lie_view, PluginIsolation isolation)
      : Integrator(std::move(facts)),
        step_(step),
        library_(std::move(library)),
        lie_view_(lie_view),
        isolation_(isolation) {}

  RunResult integrate(const Problem& problem, const RunOptions& options) const override {
    if (isolation_.mode == PluginIsolation::Mode::none) return integrate_here(problem, options);
    return run_isolated([&] { return integrate_here(problem, options); }, "stepper '" + name() + "'",
                        isolation_.wall_limit_s, problem.y0(), options.warm_up);
  }
  bool forks() const override { return isolation_.mode != PluginIsolation::Mode::none; }

 private:
  RunResult integrate_here(const Problem& problem, const RunOptions& options) const {
    // in a child: the library is opened here, never in the parent
    const StepFn step_fn = step_ != nullptr ? step_ : open_library(library_, library_).step;
    PluginCallContext context{&problem, nullptr};
    const rollbench_problem callbacks = plugin_callbacks(context);
    char message[512];
    auto step = [&](const FlatState& y, FlatState& next, double t, double h, Cost& cost) {
      context.cost = &cost;
      message[0] = '\0';
      const int code = step_fn(&callbacks, t, h, y.data(), next.data(), message, sizeof message);
      if (code != 0) [[unlikely]] {
        message[sizeof message - 1] = '\0';
        char at[48];
        std::snprintf(at, sizeof at, " at t = %.9g", t);
        // the driver ends the run here, at the last valid state
        // the reason is the plug-in's bytes: made valid UTF-8 here, where it enters
        throw StepFailure(Status::error, "stepper '" + name() + "' returned error code " + std::to_string(code) + at +
                                             (message[0] != '\0' ? ": " + valid_utf8(message) : std::string()));
      }
      // a Lie-view method claims R on SO(3): hold it to that where the state
      // comes back (NaN passes on to the driver's "diverged")
      if (lie_view_) {
        const double defect = rotation_defect(rotation_of(next));
        if (defect > kOffGroupBound) [[unlikely]] {
          char why[160];
          std::snprintf(why, sizeof why,
                        " (Lie-group view) returned R off SO(3) in the step from t = %.9g: "
                        "||R^T R - I||_F = %.3g > %.0e",
                        t, defect, kOffGroupBound);
          throw StepFailure(Status::off_group, "stepper '" + name() + "'" + why);
        }
      }
    };
    return drive_fixed_step(problem, options, step);
  }

  StepFn step_;
  std::string library_;
  bool lie_view_;
  PluginIsolation isolation_;
};

bool is_name_character(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_' ||
         c == '+' || c == '-';
}

// The library's facts, checked and copied out of its storage; where names
// the file and the symbol, path the file for the description.
MethodInfo checked_facts(const struct rollbench_stepper_info* info, const std::string& where, const std::string& path) {
  auto refuse = [&](const std::string& why) { throw InputError(where + ": " + why, "stepper"); };
  if (info == nullptr) refuse("returned NULL");
  MethodInfo facts;
  if (info->name == nullptr || info->name[0] == '\0') refuse("the name is empty");
  facts.name = info->name;
  for (const char c : facts.name)
    if (!is_name_character(c)) refuse("the name '" + facts.name + "' may hold only letters, digits and . _ + -");
  if (info->family == nullptr || info->family[0] == '\0') refuse("the family of '" + facts.name + "' is empty");
  facts.family = valid_utf8(info->family);
  if (info->order < 1) refuse("the order of '" + facts.name + "' is " + std::to_string(info->order) + ", not >= 1");
  facts.declared_order = info->order;
  if (info->view != ROLLBENCH_VIEW_FLAT && info->view != ROLLBENCH_VIEW_LIE)
    refuse("the view of '" + facts.name + "' is " + std::to_string(info->view) +
           ", not ROLLBENCH_VIEW_FLAT (0) or ROLLBENCH_VIEW_LIE (1)");
  const char* view = info->view == ROLLBENCH_VIEW_LIE ? "Lie-group view" : "flat view";
  facts.description = valid_utf8(std::string(info->description != nullptr ? info->description : "") + " (plug-in, " +
                                 view + ", " + path + ")");
  return facts;
}

// The probe's answer: fields, each an 8-byte length and its bytes.
constexpr std::size_t kMaxProbeBytes = std::size_t{1} << 16;

std::string fields_bytes(const std::vector<std::string>& fields) {
  std::string bytes;
  for (const std::string& field : fields) {
    const std::uint64_t size = field.size();
    bytes.append(reinterpret_cast<const char*>(&size), sizeof size);
    bytes.append(field);
  }
  return bytes;
}

bool read_fields(const std::string& bytes, std::vector<std::string>& fields) {
  for (std::size_t at = 0; at < bytes.size();) {
    std::uint64_t size = 0;
    if (bytes.size() - at < sizeof size) return false;
    std::memcpy(&size, bytes.data() + at, sizeof size);
    at += sizeof size;
    if (bytes.size() - at < size) return false;
    fields.emplace_back(bytes, at, size);
    at += size;
  }
  return true;
}

// In the child: open the library, call rollbench_stepper_info() once and
// send its facts ("info", name, family, description, order, view), "null",
// or ("error", the InputError's message).
std::string probe_answer(const std::string& path, const std::string& absolute) {
  try {
    const OpenedLibrary library = open_library(path, absolute);
    const struct rollbench_stepper_info* info = library.info();
    if (info == nullptr) return fields_bytes({"null"});
    auto text = [](const char* s) { return s != nullptr ? std::string(s, ::strnlen(s, 4096)) : std::string(); };
    return fields_bytes({"info", text(info->name), text(info->family), text(info->description),
                         std::to_string(info->order), std::to_string(info->view)});
  } catch (const InputError& e) {
    return fields_bytes({"error", e.message()});
  }
}

}  // namespace

rollbench_problem plugin_callbacks(PluginCallContext& context) {
  return {&context, flat_rhs_callback, lie_rhs_callback, so3_exp_callback, so3_dexpinv_callback};
}

std::unique_ptr<Integrator> load_plugin_stepper(const std::string& path, const PluginIsolation& isolation) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(path, ec))
    throw InputError("'" + path + "' is a directory, not a stepper library (give the .so file in it)", "stepper");
  if (!fs::exists(path, ec)) throw InputError("'" + path + "': no such file", "stepper");
  if (!fs::is_regular_file(path, ec))
    throw InputError("'" + path + "' is not a regular file (a device, FIFO or socket), not a stepper library",
                     "stepper");
  // an absolute path: dlopen would search the library path for a bare name
  const std::string absolute = fs::absolute(path, ec).string();
  const std::string where = "'" + path + "': rollbench_stepper_info()";
  if (isolation.mode == PluginIsolation::Mode::none) {
    const OpenedLibrary library = open_library(path, absolute);
    try {
      const struct rollbench_stepper_info* info = library.info();  // once: a second call may differ
      MethodInfo facts = checked_facts(info, where, path);
      return std::make_unique<PluginStepper>(std::move(facts), library.step, std::string(),
                                             info->view == ROLLBENCH_VIEW_LIE, isolation);
    } catch (...) {
      dlclose(library.handle);  // nothing of it was registered
      throw;
    }
  }
  // isolation process: opened, checked and asked for its facts in a child
  const ChildOutcome outcome = run_in_child([&] { return probe_answer(path, absolute); }, "stepper '" + path + "'",
                                            isolation.wall_limit_s, kMaxProbeBytes);
  std::vector<std::string> fields;
  const bool exited_clean = !outcome.timed_out && !outcome.too_long && WIFEXITED(outcome.wait_status) &&
                            WEXITSTATUS(outcome.wait_status) == 0;
  if (!exited_clean || !read_fields(outcome.answer, fields) || fields.empty())
    throw InputError("'" + path + "': loading it (in a child process) " +
                         (exited_clean ? std::string("returned no whole answer")
                                       : child_failure_text(outcome, isolation.wall_limit_s, kMaxProbeBytes)),
                     "stepper");
  if (fields[0] == "error" && fields.size() == 2) throw InputError(valid_utf8(fields[1]), "stepper");
  if (fields[0] == "null" && fields.size() == 1) (void)checked_facts(nullptr, where, path);
  // the order and view as the child wrote them (std::to_string of ints),
  // read strictly: anything else is no whole answer, never atoi's guess
  constexpr long long kIntMin = std::numeric_limits<int>::min(), kIntMax = std::numeric_limits<int>::max();
  const auto order = fields.size() == 6 ? whole_number_in(fields[4], kIntMin, kIntMax) : std::nullopt;
  const auto view = fields.size() == 6 ? whole_number_in(fields[5], kIntMin, kIntMax) : std::nullopt;
  if (fields[0] != "info" || !order || !view)
    throw InputError("'" + path + "': loading it (in a child process) returned no whole answer", "stepper");
  struct rollbench_stepper_info info {};
  info.name = fields[1].c_str();
  info.family = fields[2].c_str();
  info.description = fields[3].c_str();
  info.order = static_cast<int>(*order);
  info.view = static_cast<int>(*view);
  MethodInfo facts = checked_facts(&info, where, path);
  return std::make_unique<PluginStepper>(std::move(facts), nullptr, absolute, info.view == ROLLBENCH_VIEW_LIE,
                                         isolation);
}

}  // namespace rb
