#pragma once
// Whole numbers from text (an option, a shard "I/N", a plug-in's answer),
// read strictly: the whole text, decimal digits with an optional '-', and
// the range stated. sscanf and CLI11 read loosely ("0/1junk" as 0/1, an int
// that wraps, "0x10"); every integer the suite takes from text comes here.
#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace rb {

// text as a whole number in [lo, hi]; none for anything else (empty text,
// a sign '+', spaces, other characters, a number out of range).
std::optional<long long> whole_number_in(std::string_view text, long long lo, long long hi);

// The same, or InputError under key: "'TEXT' is not a whole number from LO
// to HI" (TEXT an escaped excerpt).
long long parse_whole_number(std::string_view text, long long lo, long long hi, const std::string& key);

// The largest shard count `run --shard I/N` takes.
inline constexpr int kMaxShards = 100000;

// "I/N" with 0 <= I < N <= kMaxShards, or InputError under key "shard":
// "'TEXT' is not I/N with 0 <= I < N <= 100000".
std::pair<int, int> parse_shard(std::string_view text);

}  // namespace rb
