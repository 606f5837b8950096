#include "bench/lib/json_input.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "problems/input_error.hpp"

namespace rb {

namespace {

// The byte offset of the first bracket nested deeper than kMaxJsonDepth, or
// npos: checked before parsing, so that no parser or destructor recurses on
// it (100 000 '[' would overflow the stack).
std::size_t too_deep_at(const std::string& text) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth) return i;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return std::string::npos;
}

}  // namespace

std::string read_regular_file(const std::string& path, const std::string& what, const std::string& key,
                              std::size_t max_bytes) {
  const std::string name = what + " '" + path + "'";
  // O_NONBLOCK: opening a FIFO with no writer must not hang; it is refused below
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw InputError("cannot read the " + name + " (" + std::strerror(errno) + ")", key);
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw InputError("the " + name + " is not a regular file", key);
  }
  if (static_cast<unsigned long long>(st.st_size) > max_bytes) {
    ::close(fd);
    throw InputError("the " + name + " is " + std::to_string(st.st_size) + " bytes, more than the limit of " +
                         std::to_string(max_bytes),
                     key);
  }
  std::string text;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    if (n < 0) {
      const int error = errno;
      ::close(fd);
      throw InputError("cannot read the " + name + " (" + std::strerror(error) + ")", key);
    }
    if (n == 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
    if (text.size() > max_bytes) {  // a file that grows while it is read
      ::close(fd);
      throw InputError("the " + name + " is more than the limit of " + std::to_string(max_bytes) + " bytes", key);
    }
  }
  ::close(fd);
  return text;
}

nlohmann::json parse_limited_json(const std::string& text, const std::string& what, const std::string& path,
                                  const std::string& key) {
  const std::string name = "the " + what + " '" + path + "'";
  if (const std::size_t at = too_deep_at(text); at != std::string::npos)
    throw InputError(name + " nests deeper than " + std::to_string(kMaxJsonDepth) + " levels (at byte " +
                         std::to_string(at + 1) + ")",
                     key);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(name + " is not JSON (syntax error at byte " + std::to_string(e.byte) + ")", key);
  } catch (const nlohmann::json::out_of_range&) {
    // 1e400: a number beyond double's range
    throw InputError(name + " holds a number out of range", key);
  } catch (const nlohmann::json::exception&) {
    throw InputError(name + " is not JSON", key);
  }
}

nlohmann::json read_json_file(const std::string& path, const std::string& what, const std::string& key) {
  return parse_limited_json(read_regular_file(path, what, key, kMaxJsonBytes), what, path, key);
}

}  // namespace rb
