#pragma once
// rollbench's --tableau FILE (repeatable): each file's integrators join the
// registry before the command runs, so that list, run and trajectory see
// them like any other (docs/formats.md, "Butcher tableau").
#include <functional>
#include <string>
#include <vector>

namespace rb {

// Registers the integrators of every file, in order; returns their names.
// Throws InputError naming the file (and the key) for the first bad one.
// note gets a line for each file whose method is a shipped one.
std::vector<std::string> add_tableau_files(const std::vector<std::string>& paths,
                                           const std::function<void(const std::string&)>& note = {});

// The sweep's methods with the tableaux' ones added: a preset that lists
// its methods would leave them out; an empty list (everything registered)
// and one the user gave (--integrators) stay as they are.
std::vector<std::string> with_tableau_methods(std::vector<std::string> methods, bool user_chose,
                                              const std::vector<std::string>& tableau_methods);

}  // namespace rb
