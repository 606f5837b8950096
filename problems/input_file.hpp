#pragma once
// Every input file rollbench reads (a scene, a tableau, a report or shard, a
// peer file, a trajectory CSV, a cache entry) is read here: opened without
// blocking (a FIFO never hangs), accepted only as a regular file, its size
// checked against its kind's limit before a byte is read, and read up to
// that limit only (a file may grow while it is read). docs/bad-input.md
// lists the limits.
#include <cstddef>
#include <string>

namespace rb {

inline constexpr std::size_t kKiB = std::size_t{1} << 10;
inline constexpr std::size_t kMiB = std::size_t{1} << 20;
inline constexpr std::size_t kGiB = std::size_t{1} << 30;

// A kind of input: what messages call it and the largest file of it read.
struct InputKind {
  std::string name;  // "scene file", "report", ...
  std::size_t max_bytes;
};

// The kinds and their limits, each far above what rollbench writes or ships
// (docs/bad-input.md, "Input files").
inline const InputKind kSceneInput{"scene file", 1 * kMiB};
inline const InputKind kTableauInput{"tableau file", 1 * kMiB};
inline const InputKind kReportInput{"report", 1 * kGiB};  // also a shard given to merge or --into
inline const InputKind kPeerFileInput{"peer file", 64 * kMiB};
inline const InputKind kTrajectoryInput{"trajectory", 256 * kMiB};  // score's CSV, a peer's trajectories
inline const InputKind kNativeCacheInput{"native-formula cache entry", 256 * kMiB};
// a cached reference: this much, plus kReferenceBytesPerTime per output time of its grid
inline constexpr std::size_t kReferenceBaseBytes = 64 * kKiB;
inline constexpr std::size_t kReferenceBytesPerTime = 2 * kKiB;
InputKind reference_cache_input(std::size_t output_times);

// The text of the input at path. Opened O_RDONLY | O_NONBLOCK | O_NOCTTY |
// O_CLOEXEC (following symbolic links, as a path the user typed should),
// then as read_open_input. InputError under key: "cannot read the scene file
// 'PATH' (No such file or directory)", and read_open_input's.
std::string read_input_file(const std::string& path, const InputKind& kind, const std::string& key);

// The same checks and read on a descriptor the caller opened (a cache entry
// opened with openat and O_NOFOLLOW); path only names it. InputError under
// key: "'PATH' is a FIFO; inputs are read only from regular files", "'PATH'
// is 1.07 GB; a scene file is at most 1 MiB", "'PATH' grew past 1 MiB while
// it was read; a scene file is at most 1 MiB", "cannot read ... (EIO's text)".
// The descriptor stays open.
std::string read_open_input(int fd, const std::string& path, const InputKind& kind, const std::string& key);

// bytes in words: "812 bytes", "1.07 GB" (three digits, powers of 1000).
std::string size_in_words(unsigned long long bytes);
// a limit in words: "1 MiB", "64 KiB" when a whole number of them, else as size_in_words.
std::string limit_in_words(std::size_t bytes);

// A path as messages show it: control characters, quotes, backslashes and
// bytes outside ASCII as \xNN, never cut (a path is the user's, not a file's content).
std::string shown_path(const std::string& path);

}  // namespace rb
