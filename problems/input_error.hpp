#pragma once
// Bad input (a formula, a scene, a command-line option) as an error with a
// place: the key it belongs to and, for formulas, the 1-based column.
#include <stdexcept>
#include <string>

namespace rb {

class InputError : public std::runtime_error {
 public:
  // message: what is wrong, in a full sentence without the place.
  // key: the scene key or option (may be empty); column: 1-based, 0 = none.
  InputError(std::string message, std::string key = {}, int column = 0)
      : std::runtime_error(format(message, key, column)),
        message_(std::move(message)),
        key_(std::move(key)),
        column_(column) {}

  const std::string& message() const { return message_; }
  const std::string& key() const { return key_; }
  int column() const { return column_; }

  // The same error placed under an outer key, e.g. a formula error placed
  // under the scene key "landscape".
  InputError under(const std::string& outer_key) const {
    return InputError(message_, key_.empty() ? outer_key : outer_key + "." + key_, column_);
  }

 private:
  static std::string format(const std::string& message, const std::string& key, int column) {
    std::string where;
    if (!key.empty()) where.append("'").append(key).append("'");
    if (column > 0) {
      if (!where.empty()) where.append(" ");
      where.append("column ").append(std::to_string(column));
    }
    return where.empty() ? message : where.append(": ").append(message);
  }

  std::string message_;
  std::string key_;
  int column_;
};

}  // namespace rb
