#include "solver/core/state_archive.hpp"

#include <fmt/format.h>

#include <fstream>
#include <iterator>

namespace pdmpm::core {
namespace {

constexpr char kMagic[16] = {'p', 'd', 'm', 'p', 'm', ' ', 'c', 'h', 'e', 'c', 'k', 'p', 'o', 'i', 'n', 't'};
constexpr std::uint32_t kFileVersion = 1;

// FNV-1a, 64 bit: enough to tell a damaged or truncated file from a good one.
std::uint64_t fnv1a(const std::string& bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

template <class T>
void append(std::string& out, T value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

class Reader {
 public:
  Reader(const std::string& bytes, const std::filesystem::path& path) : bytes_(bytes), path_(path) {}
  template <class T>
  T value() {
    T v;
    std::memcpy(&v, take(sizeof(T)), sizeof(T));
    return v;
  }
  std::string text(std::size_t n) { return std::string(take(n), n); }

 private:
  const char* take(std::size_t n) {
    if (n > bytes_.size() - at_) throw StateMismatch(fmt::format("'{}' is truncated", path_.string()));
    const char* p = bytes_.data() + at_;
    at_ += n;
    return p;
  }
  const std::string& bytes_;
  const std::filesystem::path& path_;
  std::size_t at_ = 0;
};

}  // namespace

void StateArchive::sync(const std::string& name, std::string& text) {
  if (saving()) {
    put(name, text.data(), text.size());
  } else {
    text = take(name, 1, 0);
  }
}

void StateArchive::expect(const std::string& name, std::int64_t value) {
  std::int64_t stored = value;
  sync(name, stored);
  if (stored != value)
    throw StateMismatch(fmt::format("the checkpoint's body has {} = {}, this scene's has {}", name, stored, value));
}

std::vector<std::string> StateArchive::unread() const {
  std::vector<std::string> out;
  for (const auto& [name, bytes] : blocks_)
    if (!read_.count(name)) out.push_back(name);
  return out;
}

void StateArchive::put(const std::string& name, const void* data, std::size_t bytes) {
  if (!blocks_.emplace(name, std::string(static_cast<const char*>(data), bytes)).second)
    throw std::logic_error("state archive: block '" + name + "' saved twice");
}

const std::string& StateArchive::take(const std::string& name, std::size_t element, std::size_t count) {
  const auto it = blocks_.find(name);
  if (it == blocks_.end()) throw StateMismatch(fmt::format("the checkpoint has no '{}'", name));
  const std::size_t size = it->second.size();
  const bool fits = count > 0 ? size == element * count : size % element == 0;
  if (!fits)
    throw StateMismatch(
        fmt::format("the checkpoint's '{}' has {} bytes, this run expects {}", name, size,
                    count > 0 ? fmt::format("{}", element * count) : fmt::format("a multiple of {}", element)));
  read_.insert(name);
  return it->second;
}

void StateArchive::write(const std::filesystem::path& path) const {
  std::string out(kMagic, sizeof(kMagic));
  append(out, kFileVersion);
  append(out, static_cast<std::uint64_t>(blocks_.size()));
  for (const auto& [name, bytes] : blocks_) {
    append(out, static_cast<std::uint64_t>(name.size()));
    out += name;
    append(out, static_cast<std::uint64_t>(bytes.size()));
    out += bytes;
  }
  append(out, fnv1a(out));
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file.write(out.data(), static_cast<std::streamsize>(out.size()));
  file.close();
  if (!file) throw std::runtime_error(fmt::format("cannot write the checkpoint '{}'", path.string()));
}

StateArchive StateArchive::read(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw StateMismatch(fmt::format("cannot open '{}'", path.string()));
  const std::string bytes{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  if (bytes.size() < sizeof(kMagic) + sizeof(std::uint64_t) ||
      bytes.compare(0, sizeof(kMagic), kMagic, sizeof(kMagic)) != 0)
    throw StateMismatch(fmt::format("'{}' is not a pdmpm checkpoint", path.string()));
  const std::size_t body = bytes.size() - sizeof(std::uint64_t);
  std::uint64_t stored;
  std::memcpy(&stored, bytes.data() + body, sizeof(stored));
  if (fnv1a(bytes.substr(0, body)) != stored)
    throw StateMismatch(fmt::format("'{}' is damaged (checksum mismatch)", path.string()));
  const std::string content = bytes.substr(sizeof(kMagic), body - sizeof(kMagic));
  Reader in(content, path);
  if (const auto version = in.value<std::uint32_t>(); version != kFileVersion)
    throw StateMismatch(
        fmt::format("'{}' has checkpoint file version {}, this build reads {}", path.string(), version, kFileVersion));
  StateArchive a(Mode::restore);
  const auto n = in.value<std::uint64_t>();
  for (std::uint64_t k = 0; k < n; ++k) {
    std::string name = in.text(in.value<std::uint64_t>());
    std::string data = in.text(in.value<std::uint64_t>());
    a.blocks_.emplace(std::move(name), std::move(data));
  }
  return a;
}

}  // namespace pdmpm::core
