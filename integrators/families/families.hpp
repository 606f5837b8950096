#pragma once
// The suite's own families of methods. A family is a folder
// integrators/families/<family>/ holding its data, its stepper and a
// register_<family>(MethodList&) that adds its methods; families.cpp lists
// the families, one line each (docs/extending.md, "A new family").
#include <initializer_list>
#include <memory>
#include <vector>

#include "integrators/integrator.hpp"

namespace rb {

using MethodList = std::vector<std::unique_ptr<Integrator>>;

// A family's registration: appends its methods, in the order `rollbench list`
// shows them.
using RegisterFamily = void (*)(MethodList&);

// The methods of these families, family by family.
MethodList methods_of(std::initializer_list<RegisterFamily> families);

// The methods of every family in families.cpp: the registry's built-in ones.
MethodList builtin_methods();

}  // namespace rb
