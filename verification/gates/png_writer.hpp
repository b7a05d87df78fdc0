#pragma once
// A minimal PNG writer (8-bit RGB, zlib "stored" blocks, no compression) for
// the gates' raster images, so they need no image library. PNG: ISO/IEC 15948
// (chunks with CRC-32), zlib stream: RFC 1950 (Adler-32), stored deflate
// blocks: RFC 1951 §3.2.4.
#include <array>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace pdmpm::test::png {

inline std::uint32_t crc32(const std::uint8_t* data, std::size_t n, std::uint32_t crc = 0) {
  static const auto table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  crc = ~crc;
  for (std::size_t i = 0; i < n; ++i) crc = table[(crc ^ data[i]) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

inline void put32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<std::uint8_t>(v >> s));
}

inline void chunk(std::ofstream& f, const char* type, const std::vector<std::uint8_t>& data) {
  std::vector<std::uint8_t> buf;
  put32(buf, static_cast<std::uint32_t>(data.size()));
  buf.insert(buf.end(), type, type + 4);
  buf.insert(buf.end(), data.begin(), data.end());
  put32(buf, crc32(buf.data() + 4, buf.size() - 4));
  f.write(reinterpret_cast<const char*>(buf.data()), static_cast<std::streamsize>(buf.size()));
}

// rgb: width × height × 3 bytes, rows top to bottom. Returns false if the file
// cannot be written.
inline bool write_rgb(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb) {
  std::ofstream f(path, std::ios::binary);
  if (!f) return false;
  static const std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  f.write(reinterpret_cast<const char*>(signature), 8);
  std::vector<std::uint8_t> header;
  put32(header, static_cast<std::uint32_t>(width));
  put32(header, static_cast<std::uint32_t>(height));
  header.insert(header.end(), {8, 2, 0, 0, 0});  // 8 bits, RGB, deflate, no filter method, no interlace
  chunk(f, "IHDR", header);

  // Scanlines with filter type 0, then one zlib stream of stored blocks.
  std::vector<std::uint8_t> raw;
  const auto row = static_cast<std::size_t>(width) * 3;
  for (int y = 0; y < height; ++y) {
    raw.push_back(0);
    raw.insert(raw.end(), rgb.begin() + static_cast<std::ptrdiff_t>(y * row), rgb.begin() + static_cast<std::ptrdiff_t>((y + 1) * row));
  }
  std::vector<std::uint8_t> z = {0x78, 0x01};
  for (std::size_t pos = 0; pos < raw.size() || pos == 0;) {
    const std::size_t len = std::min<std::size_t>(65535, raw.size() - pos);
    const bool last = pos + len == raw.size();
    z.push_back(last ? 1 : 0);
    z.push_back(static_cast<std::uint8_t>(len & 0xFF));
    z.push_back(static_cast<std::uint8_t>(len >> 8));
    z.push_back(static_cast<std::uint8_t>(~len & 0xFF));
    z.push_back(static_cast<std::uint8_t>((~len >> 8) & 0xFF));
    z.insert(z.end(), raw.begin() + static_cast<std::ptrdiff_t>(pos), raw.begin() + static_cast<std::ptrdiff_t>(pos + len));
    pos += len;
    if (last) break;
  }
  std::uint32_t a = 1, b = 0;
  for (auto c : raw) a = (a + c) % 65521u, b = (b + a) % 65521u;
  put32(z, (b << 16) | a);
  chunk(f, "IDAT", z);
  chunk(f, "IEND", {});
  return static_cast<bool>(f);
}

// Perceptually ordered colour for s in [0, 1] (five anchors of matplotlib's
// viridis, linearly interpolated).
inline std::array<std::uint8_t, 3> viridis(double s) {
  static const double anchors[5][3] = {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}};
  s = s < 0 ? 0 : s > 1 ? 1 : s;
  const double x = s * 4.0;
  const int k = x >= 4.0 ? 3 : static_cast<int>(x);
  const double f = x - k;
  std::array<std::uint8_t, 3> out{};
  for (int c = 0; c < 3; ++c) out[static_cast<std::size_t>(c)] = static_cast<std::uint8_t>(anchors[k][c] + f * (anchors[k + 1][c] - anchors[k][c]) + 0.5);
  return out;
}

}  // namespace pdmpm::test::png
