#include "bench/lib/tableau_option.hpp"

#include <algorithm>

#include "integrators/user_tableaux.hpp"

namespace rb {

std::vector<std::string> add_tableau_files(const std::vector<std::string>& paths,
                                           const std::function<void(const std::string&)>& note) {
  std::vector<std::string> names;
  for (const std::string& path : paths) {
    std::string twin;
    const std::vector<std::string> added = register_tableau_file(path, &twin);
    if (!twin.empty() && note) note(twin);
    names.insert(names.end(), added.begin(), added.end());
  }
  return names;
}

std::vector<std::string> with_tableau_methods(std::vector<std::string> methods, bool user_chose,
                                              const std::vector<std::string>& tableau_methods) {
  if (user_chose || methods.empty()) return methods;
  for (const std::string& name : tableau_methods)
    if (std::find(methods.begin(), methods.end(), name) == methods.end()) methods.push_back(name);
  return methods;
}

}  // namespace rb
