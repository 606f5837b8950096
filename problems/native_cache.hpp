#pragma once
// The native-formula cache's trust (formula_native.hpp; docs/native-cache.md):
// a folder of this user's alone, a per-folder secret, and entries
// authenticated with it, so that a library planted by anyone else is never
// loaded.
//
// - The folder is created 0700 and opened once per use without following a
//   symbolic link; it is refused when the opened folder (fstat, not the path)
//   is not owned by the effective uid or is writable by group or others.
//   Everything after goes through that descriptor (openat, renameat), and the
//   compiler is given /proc/<pid>/fd/<n>/<name> paths, so a folder renamed or
//   replaced after the check is never used.
// - New files get fresh random names, O_CREAT|O_EXCL|O_NOFOLLOW, mode 0600;
//   the compiler writes into a fresh 0700 subfolder.
// - The folder holds a 32-byte secret, `hmac-secret`, made once from
//   getrandom and kept 0600; one with another owner, mode or size is refused.
// - An entry is the shared object followed by a trailer: the entry key, its
//   length, HMAC-SHA256 under the secret (OpenSSL) of both lengths, the key
//   and the object, and a magic word. It is read from a descriptor checked
//   like the folder, verified in memory, and only those verified bytes are
//   loaded (formula_native.cpp, through a sealed memfd).
#include <array>
#include <optional>
#include <string>
#include <string_view>

namespace rb {

// A file descriptor, closed with its owner.
class UniqueFd {
 public:
  UniqueFd() = default;
  explicit UniqueFd(int fd) : fd_(fd) {}
  UniqueFd(UniqueFd&& other) noexcept : fd_(other.release()) {}
  UniqueFd& operator=(UniqueFd&& other) noexcept;
  UniqueFd(const UniqueFd&) = delete;
  UniqueFd& operator=(const UniqueFd&) = delete;
  ~UniqueFd();
  int get() const { return fd_; }
  int release();
  explicit operator bool() const { return fd_ >= 0; }

 private:
  int fd_ = -1;
};

// The cache folder, opened, checked, with its secret.
struct CacheFolder {
  UniqueFd fd;
  std::string path;    // as given, for messages
  std::string secret;  // 32 bytes
};

// Opens path as this user's cache folder, creating it (mode 0700; its
// parents as mkdir -p would, reached by the path rule of safe_path.hpp: a
// link of another user's on the way is refused) when missing, and reads or
// makes its secret; nullopt and why (one sentence naming the path) when it
// is refused or cannot be had.
std::optional<CacheFolder> open_cache_folder(const std::string& path, std::string& why);

// A new folder inside folder, prefix + random, mode 0700 and checked so
// (no one else can reach what is made in it, whatever the umask); its path
// is folder's path / its name, its secret empty.
std::optional<CacheFolder> make_private_subfolder(const CacheFolder& folder, const std::string& prefix);

// name inside the folder, as a path another process (the compiler) reaches
// through this process's descriptor, whatever happens to the folder's path.
std::string child_path(const CacheFolder& folder, const std::string& name);

// A new file in the folder: prefix + random + suffix, mode 0600, O_EXCL and
// O_NOFOLLOW; empty fd when it cannot be made.
struct PrivateFile {
  UniqueFd fd;
  std::string name;
};
PrivateFile create_private_file(const CacheFolder& folder, const std::string& prefix, const std::string& suffix);

bool write_all(int fd, std::string_view bytes);

// Reads the folder's file name into bytes, without following a link, checking
// the opened file: a regular file of this user's, not writable by group or
// others (refused, why set), or missing.
enum class EntryRead { ok, missing, refused };
EntryRead read_cache_file(const CacheFolder& folder, const std::string& name, std::string& bytes, std::string& why);

// Reads a file made in a private subfolder (the compiler's output): this
// user's, a regular file, not a link; its mode is the umask's.
bool read_own_output(const CacheFolder& folder, const std::string& name, std::string& bytes);

// The entry for object under key: object + trailer.
std::string seal_entry(std::string_view object, std::string_view key, std::string_view secret);
// The object of a sealed entry whose trailer holds this key and a valid
// HMAC under secret; nullopt for anything else (forged, stale, damaged).
std::optional<std::string_view> open_sealed_entry(std::string_view entry, std::string_view key,
                                                  std::string_view secret);

// HMAC-SHA256 (OpenSSL's); tested against RFC 4231's cases.
std::array<unsigned char, 32> hmac_sha256(std::string_view key, std::string_view message);

// The default cache folder: $XDG_CACHE_HOME/rollbench, else
// $HOME/.cache/rollbench, else a folder made with mkdtemp in the temporary
// folder for this process alone (once per process, removed at its exit;
// empty if it cannot be made), never a shared, predictable one.
std::string default_cache_folder(const char* xdg_cache_home, const char* home);

}  // namespace rb
