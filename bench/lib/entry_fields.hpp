#pragma once
// Reads the fields of one entry of a report (a run, a reference, an order, a
// tolerance fit), refusing what is missing or of the wrong type with an
// InputError that names the entry ("the report 'FILE': runs[i]") and the key.
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "bench/lib/sweep.hpp"
#include "problems/input_error.hpp"

namespace rb {

// where names the entry in errors: "the report 'FILE': runs[i]".
class EntryFields {
 public:
  EntryFields(const nlohmann::json& entry, std::string where) : entry_(entry), where_(std::move(where)) {
    if (!entry.is_object()) refuse("", "is not an object");
  }

  const nlohmann::json& at(const nlohmann::json& node, const std::string& key, const std::string& path) const {
    if (!node.is_object() || !node.contains(key)) refuse(path + key, "is missing");
    return node.at(key);
  }
  // the entry's own key, or node's (at path, "key." for nested ones)
  std::string text(const std::string& key) const { return text(entry_, key, ""); }
  std::string text(const nlohmann::json& node, const std::string& key, const std::string& path) const {
    const nlohmann::json& v = at(node, key, path);
    if (!v.is_string()) refuse(path + key, "is not a string");
    return v.get<std::string>();
  }
  bool flag(const std::string& key) const { return flag(entry_, key, ""); }
  bool flag(const nlohmann::json& node, const std::string& key, const std::string& path) const {
    const nlohmann::json& v = at(node, key, path);
    if (!v.is_boolean()) refuse(path + key, "is not true or false");
    return v.get<bool>();
  }
  long integer(const std::string& key) const { return integer(entry_, key, ""); }
  long integer(const nlohmann::json& node, const std::string& key, const std::string& path) const {
    const nlohmann::json& v = at(node, key, path);
    if (!v.is_number_integer()) refuse(path + key, "is not an integer");
    return v.get<long>();
  }
  const nlohmann::json& object(const nlohmann::json& node, const std::string& key, const std::string& path) const {
    const nlohmann::json& v = at(node, key, path);
    if (!v.is_object()) refuse(path + key, "is not an object");
    return v;
  }
  // a list of numbers or nulls (NaN)
  std::vector<double> numbers(const nlohmann::json& node, const std::string& key, const std::string& path) const {
    const nlohmann::json& v = at(node, key, path);
    if (!v.is_array()) refuse(path + key, "is not a list");
    std::vector<double> out;
    for (const nlohmann::json& x : v) out.push_back(entry(x, path + key));
    return out;
  }
  // a number or null (NaN)
  double number_or_null(const nlohmann::json& node, const std::string& key, const std::string& path = "") const {
    const nlohmann::json& v = at(node, key, path);
    if (v.is_null()) return kNaN;
    if (!v.is_number()) refuse(path + key, "is not a number or null");
    return v.get<double>();
  }
  RunErrors errors(const std::string& key) const {
    const nlohmann::json& e = at(entry_, key, "");
    if (!e.is_object()) refuse(key, "is not an object");
    const std::string path = key + ".";
    RunErrors out;
    for (std::size_t i = 0; i < kErrorComponentCount; ++i)
      out.component(i) = number_or_null(e, kErrorComponents[i].name, path);
    out.worst = number_or_null(e, "worst", path);
    const nlohmann::json& below = at(e, "below_floor", path);
    if (!below.is_array()) refuse(path + "below_floor", "is not a list");
    for (const nlohmann::json& name : below) {
      if (!name.is_string()) refuse(path + "below_floor", "holds something that is not a string");
      out.below_floor.push_back(name.get<std::string>());
    }
    return out;
  }
  // "final": contact, centre, omega and R (NaN where null)
  ReferencePoint end_point() const {
    const nlohmann::json& e = at(entry_, "final", "");
    if (!e.is_object()) refuse("final", "is not an object");
    ReferencePoint p;
    const auto vector = [&](const char* key, auto& out) {
      const nlohmann::json& v = at(e, key, "final.");
      const std::string path = std::string("final.") + key;
      if (!v.is_array() || v.size() != static_cast<std::size_t>(out.size()))
        refuse(path, "is not a list of " + std::to_string(out.size()) + " numbers");
      for (std::size_t i = 0; i < v.size(); ++i) out[static_cast<Eigen::Index>(i)] = entry(v[i], path);
    };
    vector("contact", p.alpha);
    vector("centre", p.centre);
    vector("omega", p.omega);
    const nlohmann::json& R = at(e, "R", "final.");
    if (!R.is_array() || R.size() != 3) refuse("final.R", "is not 3 rows of 3 numbers");
    for (std::size_t i = 0; i < 3; ++i) {
      if (!R[i].is_array() || R[i].size() != 3) refuse("final.R", "is not 3 rows of 3 numbers");
      for (std::size_t j = 0; j < 3; ++j)
        p.R(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = entry(R[i][j], "final.R");
    }
    return p;
  }
  double entry(const nlohmann::json& v, const std::string& path) const {
    if (v.is_null()) return kNaN;
    if (!v.is_number()) refuse(path, "holds something that is not a number or null");
    return v.get<double>();
  }
  [[noreturn]] void refuse(const std::string& key, const std::string& problem) const {
    throw InputError(where_ + (key.empty() ? "" : "." + key) + " " + problem, "reports");
  }

 private:
  const nlohmann::json& entry_;
  std::string where_;
};

}  // namespace rb
