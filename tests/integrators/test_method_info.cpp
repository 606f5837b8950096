// The Integrator base holds a method's facts once: what it was given at
// construction, with the two defaults filled in, and every accessor reads
// that one record.
#include <gtest/gtest.h>

#include "integrators/registry.hpp"

namespace rb {
namespace {

class FactsOnly final : public Integrator {
 public:
  explicit FactsOnly(MethodInfo info) : Integrator(std::move(info)) {}
  RunResult integrate(const Problem&, const RunOptions&) const override { return {}; }
};

TEST(MethodInfo, TheBaseFillsTheRotationOrderAndTheControllerWhenLeftOut) {
  const FactsOnly fixed({.name = "f", .family = "test", .declared_order = 3, .description = "d"});
  EXPECT_EQ(fixed.rotation_order(), 3);
  EXPECT_EQ(fixed.controller(), "constant");
  const FactsOnly adaptive({.name = "a", .family = "test", .declared_order = 5, .adaptive = true});
  EXPECT_EQ(adaptive.info().rotation_order, 5);
  EXPECT_EQ(adaptive.info().controller, "library");
  const FactsOnly given({.name = "g", .declared_order = 4, .rotation_order = 2, .adaptive = true, .controller = "pi"});
  EXPECT_EQ(given.rotation_order(), 2);
  EXPECT_EQ(given.controller(), "pi");
}

// name() and description() are the record's own strings, not copies made
// per call: one source for list, the runner and the report.
TEST(MethodInfo, EveryRegisteredIntegratorAnswersFromItsOneRecord) {
  for (const auto& m : registry()) {
    const MethodInfo& info = m->info();
    EXPECT_EQ(&m->name(), &info.name) << info.name;
    EXPECT_EQ(&m->description(), &info.description) << info.name;
    EXPECT_EQ(m->declared_order(), info.declared_order) << info.name;
    EXPECT_GE(info.rotation_order, 1) << info.name;
    EXPECT_LE(info.rotation_order, info.declared_order) << info.name;
    EXPECT_FALSE(info.controller.empty()) << info.name;
    EXPECT_EQ(info.adaptive, info.controller != "constant") << info.name;
  }
}

}  // namespace
}  // namespace rb
