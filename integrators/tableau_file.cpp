#include "integrators/tableau_file.hpp"

#include <algorithm>
#include <boost/multiprecision/cpp_int.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>

#include "integrators/order_conditions.hpp"
#include "problems/input_error.hpp"
#include "problems/input_file.hpp"
#include "problems/json_limits.hpp"
#include "problems/safe_name.hpp"

namespace rb {

namespace {

using json = nlohmann::json;

const std::vector<std::string> kKnownKeys = {"name",  "order",     "c",      "A",       "b",
                                             "b_err", "err_order", "source", "butcher", "order_tolerance"};

std::string list_of(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// No array of a tableau file holds more: butcher's s + 1 rows of s + 1.
constexpr std::size_t kMaxArrayEntries = kMaxStages + 1;

// The document, with a key given twice refused (nlohmann keeps the last one
// silently) and a number beyond a double (1e400) named by its key. The
// limits come first: the nesting before parsing, an array's length as it is
// parsed (a 2000-stage tableau is refused at its 34th entry, before the
// 4 million coefficients are built).
json parse_json_text(std::string_view text) {
  if (const std::size_t at = json_too_deep_at(text); at != std::string_view::npos)
    throw InputError("nests deeper than " + std::to_string(kMaxJsonDepth) + " levels (at byte " +
                     std::to_string(at + 1) + ")");
  std::vector<std::set<std::string>> seen;  // the keys of each object being read
  std::vector<std::size_t> entries;         // of each container being read; counted for arrays
  std::vector<bool> in_array;
  std::string last_key, top_key;  // top_key: the key of the file's own object the value is under
  const auto count_entry = [&] {
    if (!in_array.empty() && in_array.back() && ++entries.back() > kMaxArrayEntries)
      throw InputError("holds an array of more than " + std::to_string(kMaxArrayEntries) +
                           " entries; a tableau has 1 to " + std::to_string(kMaxStages) + " stages",
                       top_key);
  };
  const auto open = [&](bool array) {
    count_entry();
    in_array.push_back(array);
    entries.push_back(0);
  };
  const auto close = [&] {
    in_array.pop_back();
    entries.pop_back();
  };
  const json::parser_callback_t track = [&](int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
        open(false);
        seen.emplace_back();
        break;
      case json::parse_event_t::object_end:
        close();
        seen.pop_back();
        break;
      case json::parse_event_t::array_start: open(true); break;
      case json::parse_event_t::array_end: close(); break;
      case json::parse_event_t::value: count_entry(); break;
      case json::parse_event_t::key:
        last_key = escaped_excerpt(parsed.get<std::string>());
        if (in_array.size() == 1) top_key = last_key;
        if (!seen.back().insert(parsed.get<std::string>()).second)
          throw InputError("the key appears more than once", last_key);
        break;
    }
    return true;
  };
  try {
    return json::parse(text, track);
  } catch (const json::parse_error& e) {
    throw InputError("not JSON: " + json_error_text(e.what()));
  } catch (const json::out_of_range& e) {
    throw InputError("not a finite number: " + json_error_text(e.what()), last_key);
  }
}

double number_at(const json& v, const std::string& key, const std::string& where) {
  if (!v.is_number()) throw InputError(where + " is a " + v.type_name() + ", not a number", key);
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw InputError(where + " is not finite", key);
  return x;
}

// Numerators and denominators up to 2^53: each is a double, so p / q in
// doubles is the correctly rounded value of the fraction.
constexpr std::int64_t kMaxFractionPart = std::int64_t{1} << 53;
// A JSON number is exact when it is a multiple of 2^-20 (0, 1, 0.5, 0.375):
// binary holds such decimals as written; 0.1 or 1/3 to 16 digits it does not.
constexpr double kExactUnit = 1.0 / (1 << 20);

// One coefficient as the file gives it: a number, or a fraction "p/q" (or an
// integer "p") held exactly beside its double.
struct Coefficient {
  double value = 0.0;
  std::optional<Fraction> exact;  // none for a number binary cannot hold as written
};

std::optional<std::int64_t> integer_part(const std::string& digits) {
  if (digits.empty() || digits.size() > 16 || !std::all_of(digits.begin(), digits.end(), ::isdigit)) return {};
  const std::int64_t n = std::stoll(digits);
  return n <= kMaxFractionPart ? std::optional(n) : std::nullopt;
}

Coefficient coefficient_at(const json& v, const std::string& key, const std::string& where) {
  if (v.is_string()) {
    const std::string text = v.get<std::string>();
    const std::size_t slash = text.find('/');
    const bool has_sign = !text.empty() && (text[0] == '-' || text[0] == '+');
    const bool negative = has_sign && text[0] == '-';
    const std::size_t from = has_sign ? 1 : 0;
    const auto p = integer_part(text.substr(from, slash == std::string::npos ? std::string::npos : slash - from));
    const auto q = slash == std::string::npos ? std::optional<std::int64_t>(1) : integer_part(text.substr(slash + 1));
    if (!p || !q || *q == 0)
      throw InputError(where + " is the string \"" + escaped_excerpt(text) +
                           "\", not a number or a fraction \"p/q\" (integers up to 2^53, q > 0)",
                       key);
    const Fraction f{negative ? -*p : *p, *q};
    return {static_cast<double>(f.numerator) / static_cast<double>(f.denominator), f};
  }
  Coefficient c{number_at(v, key, where), std::nullopt};
  const double units = c.value / kExactUnit;
  if (units == std::floor(units) && std::abs(units) <= static_cast<double>(kMaxFractionPart))
    c.exact = Fraction{static_cast<std::int64_t>(units), std::int64_t{1} << 20};
  return c;
}

// An array of exactly n coefficients; why says where n comes from.
std::vector<Coefficient> numbers_at(const json& v, const std::string& key, long n, const std::string& why) {
  if (!v.is_array())
    throw InputError("must be an array of " + std::to_string(n) + " numbers, not a " + v.type_name(), key);
  if (v.size() != static_cast<std::size_t>(n))
    throw InputError("has " + std::to_string(v.size()) + " entries, not " + std::to_string(n) + why, key);
  std::vector<Coefficient> out;
  for (std::size_t i = 0; i < v.size(); ++i) out.push_back(coefficient_at(v[i], key, "entry " + std::to_string(i)));
  return out;
}

// A square matrix: rows arrays of as many coefficients as there are rows,
// at most max_rows of them (checked before any is read).
std::vector<std::vector<Coefficient>> square_at(const json& v, const std::string& key, std::size_t max_rows) {
  if (!v.is_array() || v.empty()) throw InputError("must be an array of rows (arrays of numbers)", key);
  if (v.size() > max_rows)  // Tableau's own sentence, before a coefficient is read
    throw InputError("a tableau needs 1 to " + std::to_string(kMaxStages) + " stages, got " +
                         std::to_string(v.size() - (max_rows - kMaxStages)),
                     key);
  const long n = static_cast<long>(v.size());
  std::vector<std::vector<Coefficient>> rows;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!v[i].is_array())
      throw InputError("row " + std::to_string(i) + " is a " + v[i].type_name() + ", not an array of numbers", key);
    if (v[i].size() != v.size())
      throw InputError("row " + std::to_string(i) + " has " + std::to_string(v[i].size()) + " entries, not " +
                           std::to_string(n) + " (" + key + " must be square)",
                       key);
    rows.push_back(numbers_at(v[i], key + "[" + std::to_string(i) + "]", n, ""));
  }
  return rows;
}

int integer_at(const json& v, const std::string& key, int lo, int hi) {
  const double x = number_at(v, key, key);
  if (x != std::floor(x) || x < lo || x > hi)
    throw InputError(
        "must be an integer from " + std::to_string(lo) + " to " + std::to_string(hi) + ", not " + v.dump(), key);
  return static_cast<int>(x);
}

// "an array", "a number": a value named by its type
std::string a_type_name(const json& v) {
  const std::string type = v.type_name();
  return (type[0] == 'a' || type[0] == 'o' ? "an " : "a ") + type;
}

bool registry_safe(const std::string& name) {
  return !name.empty() && name.size() <= 40 && std::all_of(name.begin(), name.end(), [](char ch) {
    return std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_' || ch == '.';
  });
}

// The doubles of coefficients, and their fractions when every one is exact.
struct Split {
  std::vector<double> values;
  std::optional<std::vector<Fraction>> exact;
};

Split split(const std::vector<Coefficient>& coefficients) {
  Split out;
  out.exact.emplace();
  for (const Coefficient& c : coefficients) {
    out.values.push_back(c.value);
    if (c.exact && out.exact) out.exact->push_back(*c.exact);
    else out.exact.reset();
  }
  return out;
}

// A, b, c as the file gives them: separately, or as the seminar's matrix.
struct Coefficients {
  std::vector<double> a, b, c;  // a: s x s row-major
  // the same as fractions, when the file gives every one exactly: the
  // order conditions are then checked exactly
  std::optional<std::vector<Fraction>> exact_a, exact_b, exact_c;
  bool butcher = false;
  double order_tolerance = kOrderConditionTolerance;
  int stages() const { return static_cast<int>(b.size()); }
  bool exact() const { return exact_a && exact_b && exact_c; }
  // the file's key a Tableau error about key ("a", "b", "c") belongs to
  std::string file_key(const std::string& key) const {
    if (butcher && (key == "a" || key == "b" || key == "c")) return "butcher";
    return key == "a" ? "A" : key;
  }
};

Coefficients read_coefficients(const json& doc) {
  std::vector<Coefficient> a, b, c;
  bool butcher = false;
  const bool separate = doc.contains("c") || doc.contains("A") || doc.contains("b");
  if (doc.contains("butcher")) {
    if (separate) throw InputError("give either butcher or c, A and b, not both", "butcher");
    // rows [c_i, a_i1 ... a_is], then [0, b_1 ... b_s]
    const std::vector<std::vector<Coefficient>> m = square_at(doc["butcher"], "butcher", kMaxStages + 1);
    const std::size_t s = m.size() - 1;
    if (s == 0) throw InputError("needs at least 2 rows: [c_1, a_11], then [0, b_1]", "butcher");
    if (m[s][0].value != 0.0)
      throw InputError("the last row holds [0, b_1 ... b_s]: its first entry must be 0", "butcher");
    for (std::size_t i = 0; i < s; ++i) {
      c.push_back(m[i][0]);
      a.insert(a.end(), m[i].begin() + 1, m[i].end());
    }
    b.assign(m[s].begin() + 1, m[s].end());
    butcher = true;
  } else {
    for (const char* key : {"c", "A", "b"})
      if (!doc.contains(key)) throw InputError("missing required key (or give butcher instead of c, A and b)", key);
    const std::vector<std::vector<Coefficient>> rows = square_at(doc["A"], "A", kMaxStages);
    const long s = static_cast<long>(rows.size());
    for (const auto& row : rows) a.insert(a.end(), row.begin(), row.end());
    const std::string why = " (A has " + std::to_string(s) + " rows)";
    c = numbers_at(doc["c"], "c", s, why);
    b = numbers_at(doc["b"], "b", s, why);
  }
  Coefficients k;
  Split sa = split(a), sb = split(b), sc = split(c);
  k.a = std::move(sa.values);
  k.b = std::move(sb.values);
  k.c = std::move(sc.values);
  k.exact_a = std::move(sa.exact);
  k.exact_b = std::move(sb.exact);
  k.exact_c = std::move(sc.exact);
  k.butcher = butcher;
  return k;
}

// For a file of exact coefficients: every row of A sums to its c exactly.
void check_rows_exactly(const Coefficients& k) {
  using boost::multiprecision::cpp_rational;
  const auto s = static_cast<std::size_t>(k.stages());
  for (std::size_t i = 0; i < s; ++i) {
    cpp_rational row = 0;
    for (std::size_t j = 0; j < s; ++j)
      row += cpp_rational((*k.exact_a)[i * s + j].numerator) / (*k.exact_a)[i * s + j].denominator;
    if (row != cpp_rational((*k.exact_c)[i].numerator) / (*k.exact_c)[i].denominator)
      throw InputError("c[" + std::to_string(i) + "] must equal the sum of row " + std::to_string(i) +
                           " of A exactly (the file gives every coefficient exactly)",
                       k.file_key("c"));
  }
}

// The exact check of weights w to order (the highest that holds when order
// is none); throws naming the first tree that fails, like Tableau does.
int exact_order_of(const Coefficients& k, const std::vector<Fraction>& w, const std::optional<int>& order,
                   const std::string& subject, const std::string& key) {
  const OrderConditionCheck check =
      check_order_conditions_exact(k.stages(), *k.exact_a, w, *k.exact_c, order.value_or(kMaxConditionOrder));
  if (order && check.failure)
    throw InputError(subject + " " + std::to_string(*order) +
                         " but satisfy the order conditions exactly only to order " +
                         std::to_string(check.satisfied_order) + " (" + describe(*check.failure) + ")",
                     key);
  if (check.satisfied_order == 0)
    throw InputError("the weights satisfy no order condition exactly (" + describe(*check.failure) + ")", key);
  return check.satisfied_order;
}

// The tableau, checked by Tableau itself; without a declared order, the
// highest whose conditions hold (order 1 is checked first: it must hold).
Tableau make_tableau(const std::string& name, const std::optional<int>& order, const Coefficients& k) {
  const auto plain = [&](int p) {
    TableauCoefficients t;
    t.name = name;
    t.order = p;
    t.a = k.a;
    t.b = k.b;
    t.c = k.c;
    t.order_tolerance = k.order_tolerance;
    return Tableau(std::move(t));
  };
  try {
    if (order) return plain(*order);
    return plain(plain(1).satisfied_order());
  } catch (const InputError& e) {
    if (order || e.key() != "order") throw InputError(e.message(), k.file_key(e.key()));
    // no order was declared: the weights fail order 1 itself
    const OrderConditionCheck check = check_order_conditions(k.stages(), k.a, k.b, k.c, 1, 1.0, k.order_tolerance);
    throw InputError("the weights satisfy no order condition (" + describe(*check.failure) + ")", k.file_key("b"));
  }
}

// b_err against its conditions; err_order, when not given, is the highest
// that holds (exactly, when b_err and the tableau are given exactly).
int check_embedded(const Coefficients& k, const std::vector<Coefficient>& given, const std::optional<int>& err_order) {
  const Split b_err = split(given);
  if (b_err.values == k.b) throw InputError("equals b: the error estimate b - b_err would be zero", "b_err");
  if (k.exact() && b_err.exact)
    return exact_order_of(k, *b_err.exact, err_order, "the embedded weights declare err_order", "b_err");
  const OrderConditionCheck check = check_order_conditions(
      k.stages(), k.a, b_err.values, k.c, err_order.value_or(kMaxConditionOrder), 1.0, k.order_tolerance);
  if (err_order && check.failure)
    throw InputError("the embedded weights declare err_order " + std::to_string(*err_order) +
                         " but satisfy the order conditions only to order " + std::to_string(check.satisfied_order) +
                         " (" + describe(*check.failure) + ")",
                     "b_err");
  if (check.satisfied_order == 0)
    throw InputError("the embedded weights satisfy no order condition (" + describe(*check.failure) + ")", "b_err");
  return check.satisfied_order;
}

TableauFile read_tableau(const json& doc, const std::string& path) {
  if (!doc.is_object()) throw InputError(std::string("must be a JSON object, not ") + doc.type_name());
  for (const auto& item : doc.items())
    if (std::find(kKnownKeys.begin(), kKnownKeys.end(), item.key()) == kKnownKeys.end())
      throw InputError("unknown key (known: " + list_of(kKnownKeys) + ")", escaped_excerpt(item.key()));
  if (!doc.contains("name")) throw InputError("missing required key", "name");
  // the value is shown as a short excerpt, or by its type: never dumped whole
  const json& given_name = doc["name"];
  if (!given_name.is_string() || !registry_safe(given_name.get<std::string>()))
    throw InputError("must be a string of 1 to 40 letters, digits, '-', '_' or '.' (it names rk-<name>), not " +
                         (given_name.is_string() ? "\"" + escaped_excerpt(given_name.get<std::string>()) + "\""
                                                 : a_type_name(given_name)),
                     "name");
  const std::string name = doc["name"].get<std::string>();
  std::optional<int> order, err_order;
  if (doc.contains("order")) order = integer_at(doc["order"], "order", 1, kMaxConditionOrder);
  if (doc.contains("err_order")) err_order = integer_at(doc["err_order"], "err_order", 1, kMaxConditionOrder);
  Coefficients k = read_coefficients(doc);
  if (doc.contains("order_tolerance")) {
    k.order_tolerance = number_at(doc["order_tolerance"], "order_tolerance", "order_tolerance");
    if (!(k.order_tolerance > 0.0 && k.order_tolerance <= kMaxOrderTolerance))
      throw InputError("must be " + order_tolerance_rule() + ", not " + doc["order_tolerance"].dump(),
                       "order_tolerance");
  }
  // given exactly, the conditions are checked exactly first: a tolerance
  // cannot then pass a method that misses its order by a little
  std::optional<int> checked_order = order;
  if (k.exact()) {
    check_rows_exactly(k);
    checked_order = exact_order_of(k, *k.exact_b, order, "the weights declare order", k.file_key("b"));
  }
  TableauFile file{path, make_tableau(name, checked_order, k), order.has_value()};
  // the one tableau: b propagates, e = b - b_err estimates the error
  TableauCoefficients full;
  full.name = name;
  full.order = file.tableau.order();
  full.a = k.a;
  full.b = k.b;
  full.c = k.c;
  full.order_tolerance = k.order_tolerance;
  const bool has_b_err = doc.contains("b_err") && !doc["b_err"].is_null();
  if (has_b_err) {
    const std::vector<Coefficient> b_err =
        numbers_at(doc["b_err"], "b_err", k.stages(), " (b has " + std::to_string(k.stages()) + ")");
    full.embedded_order = check_embedded(k, b_err, err_order);
    for (std::size_t i = 0; i < b_err.size(); ++i) full.e.push_back(k.b[i] - b_err[i].value);
  } else if (err_order) {
    throw InputError("goes with b_err, which the file does not give", "err_order");
  }
  if (doc.contains("source")) {
    if (!doc["source"].is_string())
      throw InputError(std::string("must be a string, not ") + doc["source"].type_name(), "source");
    full.source = doc["source"].get<std::string>();
  }
  try {
    file.tableau = Tableau(std::move(full));
  } catch (const InputError& e) {
    throw InputError(e.message(), e.key() == "e" ? "b_err" : k.file_key(e.key()));
  }
  return file;
}

}  // namespace

TableauFile parse_tableau_file(std::string_view text, const std::string& path) {
  try {
    return read_tableau(parse_json_text(text), path);
  } catch (const InputError& e) {
    throw InputError("tableau file '" + shown_path(path) + "': " + e.what());
  }
}

TableauFile load_tableau_file(const std::string& path) {
  return parse_tableau_file(read_input_file(path, kTableauInput, "tableau"), path);
}

}  // namespace rb
