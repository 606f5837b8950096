// The native-formula cache's folder, secret and sealed entries
// (native_cache.hpp). Every check is made on an opened descriptor (fstat),
// never on a path that could change between the check and the use.
#include "problems/native_cache.hpp"

#include <fcntl.h>
#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "problems/input_error.hpp"
#include "problems/input_file.hpp"
#include "problems/safe_path.hpp"

namespace rb {
namespace fs = std::filesystem;

UniqueFd& UniqueFd::operator=(UniqueFd&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = other.release();
  }
  return *this;
}

UniqueFd::~UniqueFd() {
  if (fd_ >= 0) ::close(fd_);
}

int UniqueFd::release() {
  const int fd = fd_;
  fd_ = -1;
  return fd;
}

namespace {

constexpr char kSecretName[] = "hmac-secret";
constexpr std::size_t kSecretSize = 32;
constexpr char kMagic[9] = "RBNATIV2";
// what the MAC is of, so that the secret authenticates nothing else
constexpr std::string_view kMacDomain = "rollbench native cache entry 2";
std::string in_quotes(const std::string& s) { return "'" + s + "'"; }

std::string octal_mode(mode_t mode) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "%04o", static_cast<unsigned>(mode & 07777));
  return buf;
}

// What a file must be: an entry or folder this user's and writable by no one
// else, a secret also unreadable by others, the compiler's output (in a
// private 0700 folder, whatever the umask made it) only this user's.
enum class Trust { shared_read, secret, own_output };

// Why what (a file or folder described for the message) may not be
// trusted; empty when it may.
std::string distrust(const struct stat& st, const std::string& what, Trust trust) {
  if (st.st_uid != geteuid())
    return what + " is owned by uid " + std::to_string(st.st_uid) + ", not by this user (uid " +
           std::to_string(geteuid()) + ")";
  if (trust == Trust::own_output) return {};
  if (st.st_mode & (S_IWGRP | S_IWOTH))
    return what + " is writable by group or others (mode " + octal_mode(st.st_mode) + ")";
  if (trust == Trust::secret && (st.st_mode & (S_IRWXG | S_IRWXO)))
    return what + " has mode " + octal_mode(st.st_mode) + "; a secret must be 0600";
  return {};
}

bool random_bytes(unsigned char* out, std::size_t n) {
  std::size_t have = 0;
  while (have < n) {
    const ssize_t got = getrandom(out + have, n - have, 0);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) break;
    have += static_cast<std::size_t>(got);
  }
  if (have == n) return true;
  // no getrandom (an old kernel): the same pool through /dev/urandom
  const UniqueFd fd(::open("/dev/urandom", O_RDONLY | O_CLOEXEC));
  while (fd && have < n) {
    const ssize_t got = ::read(fd.get(), out + have, n - have);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) return false;
    have += static_cast<std::size_t>(got);
  }
  return have == n;
}

std::string random_hex(std::size_t bytes) {
  unsigned char raw[16];
  if (bytes > sizeof raw || !random_bytes(raw, bytes)) return {};
  std::string s;
  for (std::size_t i = 0; i < bytes; ++i) {
    char two[3];
    std::snprintf(two, sizeof two, "%02x", raw[i]);
    s += two;
  }
  return s;
}

EntryRead read_checked(const CacheFolder& folder, const std::string& name, std::string& bytes, std::string& why,
                       const std::string& what, Trust trust) {
  bytes.clear();
  // O_NONBLOCK: a FIFO in its place must not hang the open (fstat refuses it)
  const UniqueFd fd(::openat(folder.fd.get(), name.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK));
  if (!fd) {
    if (errno == ENOENT) return EntryRead::missing;
    why = what +
          (errno == ELOOP ? " is a symbolic link" : std::string(" cannot be opened (") + std::strerror(errno) + ")");
    return EntryRead::refused;
  }
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0 || !S_ISREG(st.st_mode)) {
    why = what + " is not a regular file";
    return EntryRead::refused;
  }
  if (why = distrust(st, what, trust); !why.empty()) return EntryRead::refused;
  // its size checked before it is read, at most the limit read (problems/input_file.hpp)
  try {
    bytes = read_open_input(fd.get(), folder.path + "/" + name, kNativeCacheInput, "");
  } catch (const InputError& e) {
    why = e.message();
    return EntryRead::refused;
  }
  return EntryRead::ok;
}

// Makes the folder's secret and links it into place, unless another process
// was first (linkat never replaces): both then read the same one.
void make_secret(const CacheFolder& folder) {
  unsigned char secret[kSecretSize];
  if (!random_bytes(secret, sizeof secret)) return;
  PrivateFile file = create_private_file(folder, "hmac-secret.", ".tmp");
  if (!file.fd) return;
  const bool written = write_all(file.fd.get(), {reinterpret_cast<const char*>(secret), sizeof secret});
  file.fd = UniqueFd();
  if (written) ::linkat(folder.fd.get(), file.name.c_str(), folder.fd.get(), kSecretName, 0);
  ::unlinkat(folder.fd.get(), file.name.c_str(), 0);
}

bool read_secret(CacheFolder& folder, std::string& why) {
  const std::string what = "the cache secret " + in_quotes(folder.path + "/" + kSecretName);
  for (int attempt = 0; attempt < 2; ++attempt) {
    switch (read_checked(folder, kSecretName, folder.secret, why, what, Trust::secret)) {
      case EntryRead::refused: return false;
      case EntryRead::ok:
        if (folder.secret.size() == kSecretSize) return true;
        why = what + " holds " + std::to_string(folder.secret.size()) + " bytes, not " + std::to_string(kSecretSize);
        return false;
      case EntryRead::missing: make_secret(folder); break;
    }
  }
  why = what + " cannot be made";
  return false;
}

void put_u64(std::string& s, std::uint64_t v) { s.append(reinterpret_cast<const char*>(&v), sizeof v); }
std::uint64_t get_u64(std::string_view s, std::size_t at) {
  std::uint64_t v;
  std::memcpy(&v, s.data() + at, sizeof v);
  return v;
}

std::array<unsigned char, 32> entry_mac(std::string_view object, std::string_view key, std::string_view secret) {
  std::string message(kMacDomain);
  message += '\0';
  put_u64(message, object.size());
  put_u64(message, key.size());
  message.append(key);
  message.append(object);
  return hmac_sha256(secret, message);
}

// the mkdtemp folder of this process; a plain array, so that it outlives
// every static destructor and the exit handler can still read it
char private_folder[PATH_MAX] = {};

}  // namespace

std::optional<CacheFolder> open_cache_folder(const std::string& path_in, std::string& why) {
  if (path_in.empty()) {
    why = "no cache folder: HOME and XDG_CACHE_HOME are unset and no private folder could be made";
    return std::nullopt;
  }
  std::string path = path_in;
  while (path.size() > 1 && path.back() == '/') path.pop_back();  // a trailing '/' would follow a link
  const std::string what = "the cache folder " + in_quotes(path);
  // its parents made as mkdir -p would, but reached by the path rule
  // (safe_path.hpp): a link of another user's on the way is not followed
  const fs::path as_path(path);
  const std::string leaf = as_path.filename().string();
  const std::string parent_path = as_path.has_parent_path() ? as_path.parent_path().string() : ".";
  const OpenedFolder parent = open_folder(parent_path, MissingFolders::make);
  if (!parent) {
    why = "cannot create " + what + " (" + parent.why() + ")";
    return std::nullopt;
  }
  if (::mkdirat(parent.fd.get(), leaf.c_str(), 0700) != 0 && errno != EEXIST) {
    why = "cannot create " + what + " (" + std::strerror(errno) + ")";
    return std::nullopt;
  }
  CacheFolder folder;
  folder.path = path;
  folder.fd = UniqueFd(::openat(parent.fd.get(), leaf.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
  if (!folder.fd) {
    why = what + (errno == ELOOP || errno == ENOTDIR ? " is a symbolic link or not a folder"
                                                     : std::string(" cannot be opened (") + std::strerror(errno) + ")");
    return std::nullopt;
  }
  struct stat st {};
  if (::fstat(folder.fd.get(), &st) != 0 || !S_ISDIR(st.st_mode)) {
    why = what + " is not a folder";
    return std::nullopt;
  }
  if (why = distrust(st, what, Trust::shared_read); !why.empty()) return std::nullopt;
  if (!read_secret(folder, why)) return std::nullopt;
  return folder;
}

std::optional<CacheFolder> make_private_subfolder(const CacheFolder& folder, const std::string& prefix) {
  for (int attempt = 0; attempt < 8; ++attempt) {
    const std::string random = random_hex(8);
    if (random.empty()) break;
    const std::string name = prefix + random;
    if (::mkdirat(folder.fd.get(), name.c_str(), 0700) != 0) {
      if (errno == EEXIST) continue;
      break;
    }
    CacheFolder sub;
    sub.path = folder.path + "/" + name;
    sub.fd = UniqueFd(::openat(folder.fd.get(), name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
    struct stat st {};
    if (sub.fd && ::fstat(sub.fd.get(), &st) == 0 && S_ISDIR(st.st_mode) && st.st_uid == geteuid() &&
        (st.st_mode & (S_IRWXG | S_IRWXO)) == 0)
      return sub;
    ::unlinkat(folder.fd.get(), name.c_str(), AT_REMOVEDIR);
    break;
  }
  return std::nullopt;
}

std::string child_path(const CacheFolder& folder, const std::string& name) {
  return "/proc/" + std::to_string(::getpid()) + "/fd/" + std::to_string(folder.fd.get()) + "/" + name;
}

PrivateFile create_private_file(const CacheFolder& folder, const std::string& prefix, const std::string& suffix) {
  for (int attempt = 0; attempt < 8; ++attempt) {
    const std::string random = random_hex(8);
    if (random.empty()) break;
    PrivateFile file{UniqueFd(), prefix + random + suffix};
    file.fd = UniqueFd(
        ::openat(folder.fd.get(), file.name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600));
    if (file.fd) return file;
    if (errno != EEXIST) break;
  }
  return {};
}

bool write_all(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t put = ::write(fd, bytes.data(), bytes.size());
    if (put < 0 && errno == EINTR) continue;
    if (put <= 0) return false;
    bytes.remove_prefix(static_cast<std::size_t>(put));
  }
  return true;
}

EntryRead read_cache_file(const CacheFolder& folder, const std::string& name, std::string& bytes, std::string& why) {
  return read_checked(folder, name, bytes, why, "the cache entry " + in_quotes(folder.path + "/" + name),
                      Trust::shared_read);
}

bool read_own_output(const CacheFolder& folder, const std::string& name, std::string& bytes) {
  std::string why;
  return read_checked(folder, name, bytes, why, name, Trust::own_output) == EntryRead::ok;
}

std::string seal_entry(std::string_view object, std::string_view key, std::string_view secret) {
  std::string entry(object);
  entry.append(key);
  put_u64(entry, key.size());
  const std::array<unsigned char, 32> mac = entry_mac(object, key, secret);
  entry.append(reinterpret_cast<const char*>(mac.data()), mac.size());
  return entry.append(kMagic, 8);
}

std::optional<std::string_view> open_sealed_entry(std::string_view entry, std::string_view key,
                                                  std::string_view secret) {
  constexpr std::size_t fixed = 8 + 32 + 8;  // key length, MAC, magic
  if (entry.size() < fixed + key.size() || entry.substr(entry.size() - 8) != std::string_view(kMagic, 8)) return {};
  if (get_u64(entry, entry.size() - fixed) != key.size()) return {};
  const std::size_t object_size = entry.size() - fixed - key.size();
  if (entry.substr(object_size, key.size()) != key) return {};
  const std::string_view object = entry.substr(0, object_size);
  const std::array<unsigned char, 32> mac = entry_mac(object, key, secret);
  if (CRYPTO_memcmp(mac.data(), entry.data() + entry.size() - 40, mac.size()) != 0) return {};
  return object;
}

std::array<unsigned char, 32> hmac_sha256(std::string_view key, std::string_view message) {
  static const unsigned char none = 0;  // OpenSSL wants a pointer even for an empty key or message
  std::array<unsigned char, 32> mac{};
  unsigned int length = 0;
  HMAC(EVP_sha256(), key.empty() ? static_cast<const void*>(&none) : key.data(), static_cast<int>(key.size()),
       message.empty() ? &none : reinterpret_cast<const unsigned char*>(message.data()), message.size(), mac.data(),
       &length);
  return mac;
}

std::string default_cache_folder(const char* xdg_cache_home, const char* home) {
  if (xdg_cache_home && *xdg_cache_home) return (fs::path(xdg_cache_home) / "rollbench").string();
  if (home && *home) return (fs::path(home) / ".cache" / "rollbench").string();
  // no home: a folder of this process alone, never a shared, guessable name
  static const bool made = [] {
    std::error_code error;
    fs::path temp = fs::temp_directory_path(error);
    if (error) temp = "/tmp";
    std::string name = (temp / "rollbench-cache-XXXXXX").string();
    if (name.size() >= sizeof private_folder || !::mkdtemp(name.data())) return false;
    std::memcpy(private_folder, name.c_str(), name.size() + 1);
    std::atexit([] {
      std::error_code ignored;
      fs::remove_all(private_folder, ignored);
    });
    return true;
  }();
  return made ? std::string(private_folder) : std::string();
}

}  // namespace rb
