// Whole numbers read strictly (whole_number.hpp): std::from_chars over the
// whole text, then the range.
#include "problems/whole_number.hpp"

#include <charconv>

#include "problems/input_error.hpp"
#include "problems/safe_name.hpp"

namespace rb {

std::optional<long long> whole_number_in(std::string_view text, long long lo, long long hi) {
  long long value = 0;
  const char* end = text.data() + text.size();
  // from_chars takes no '+', no spaces and no base prefix; a value beyond
  // long long is result_out_of_range, never a wrapped one
  const auto [at, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || at != end || value < lo || value > hi) return std::nullopt;
  return value;
}

long long parse_whole_number(std::string_view text, long long lo, long long hi, const std::string& key) {
  if (const auto value = whole_number_in(text, lo, hi)) return *value;
  throw InputError("'" + escaped_excerpt(std::string(text)) + "' is not a whole number from " + std::to_string(lo) +
                       " to " + std::to_string(hi),
                   key);
}

std::pair<int, int> parse_shard(std::string_view text) {
  const std::size_t slash = text.find('/');
  if (slash != std::string_view::npos) {
    const auto count = whole_number_in(text.substr(slash + 1), 1, kMaxShards);
    const auto index = count ? whole_number_in(text.substr(0, slash), 0, *count - 1) : std::nullopt;
    if (index) return {static_cast<int>(*index), static_cast<int>(*count)};
  }
  throw InputError(
      "'" + escaped_excerpt(std::string(text)) + "' is not I/N with 0 <= I < N <= " + std::to_string(kMaxShards),
      "shard");
}

}  // namespace rb
