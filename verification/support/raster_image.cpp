#include "verification/support/raster_image.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <stdexcept>

namespace pdmpm::test {
namespace {

std::uint32_t crc32(const std::uint8_t* data, std::size_t n, std::uint32_t crc = 0xFFFFFFFFu) {
  static const auto table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  for (std::size_t i = 0; i < n; ++i) crc = table[(crc ^ data[i]) & 0xFFu] ^ (crc >> 8);
  return crc;
}

void put32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<std::uint8_t>(v >> s));
}

void chunk(std::vector<std::uint8_t>& out, const char* type, const std::vector<std::uint8_t>& body) {
  put32(out, static_cast<std::uint32_t>(body.size()));
  const std::size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), body.begin(), body.end());
  put32(out, crc32(out.data() + start, out.size() - start) ^ 0xFFFFFFFFu);
}

// Bits into a deflate stream, least significant first.
class BitWriter {
 public:
  explicit BitWriter(std::vector<std::uint8_t>& out) : out_(out) {}
  void bits(std::uint32_t value, int count) {
    for (int k = 0; k < count; ++k) push((value >> k) & 1u);
  }
  // Huffman codes go most significant bit first.
  void code(std::uint32_t value, int count) {
    for (int k = count - 1; k >= 0; --k) push((value >> k) & 1u);
  }
  void flush() {
    if (n_) out_.push_back(acc_), acc_ = 0, n_ = 0;
  }

 private:
  void push(std::uint32_t bit) {
    acc_ = static_cast<std::uint8_t>(acc_ | (bit << n_));
    if (++n_ == 8) out_.push_back(acc_), acc_ = 0, n_ = 0;
  }
  std::vector<std::uint8_t>& out_;
  std::uint8_t acc_ = 0;
  int n_ = 0;
};

// Fixed literal/length code of RFC 1951 §3.2.6.
void literal_length(BitWriter& w, int symbol) {
  if (symbol < 144) w.code(static_cast<std::uint32_t>(0x30 + symbol), 8);
  else if (symbol < 256) w.code(static_cast<std::uint32_t>(0x190 + symbol - 144), 9);
  else if (symbol < 280) w.code(static_cast<std::uint32_t>(symbol - 256), 7);
  else w.code(static_cast<std::uint32_t>(0xC0 + symbol - 280), 8);
}

void match(BitWriter& w, int length, int distance) {
  static const int len_base[] = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                 31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
  static const int len_extra[] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
  static const int dist_base[] = {1,   2,   3,   4,   5,   7,    9,    13,   17,   25,   33,   49,   65,    97,    129,
                                  193, 257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
  static const int dist_extra[] = {0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};
  int l = 28;
  while (len_base[l] > length) --l;
  literal_length(w, 257 + l);
  w.bits(static_cast<std::uint32_t>(length - len_base[l]), len_extra[l]);
  int d = 29;
  while (dist_base[d] > distance) --d;
  w.code(static_cast<std::uint32_t>(d), 5);
  w.bits(static_cast<std::uint32_t>(distance - dist_base[d]), dist_extra[d]);
}

// One final fixed-Huffman block; greedy matches at the given distances (≤ 32768).
void deflate_fixed(const std::vector<std::uint8_t>& raw, std::initializer_list<std::size_t> distances,
                   std::vector<std::uint8_t>& out) {
  BitWriter w(out);
  w.bits(1, 1);  // BFINAL
  w.bits(1, 2);  // BTYPE = 01, fixed codes
  for (std::size_t i = 0; i < raw.size();) {
    std::size_t best = 0, best_d = 0;
    for (std::size_t d : distances) {
      if (d > i || d > 32768) continue;
      std::size_t n = 0;
      while (n < 258 && i + n < raw.size() && raw[i + n] == raw[i + n - d]) ++n;
      if (n > best) best = n, best_d = d;
    }
    if (best >= 3) {
      match(w, static_cast<int>(best), static_cast<int>(best_d));
      i += best;
    } else {
      literal_length(w, raw[i]);
      ++i;
    }
  }
  literal_length(w, 256);  // end of block
  w.flush();
}

std::uint8_t channel(double v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); }

}  // namespace

Rgb damage_colour(double v) {
  v = std::clamp(v, 0.0, 1.0);
  // Piecewise linear through dark blue, blue, cyan, yellow, red, dark red.
  const double stops[][4] = {{0.0, 0.0, 0.0, 0.5}, {0.125, 0.0, 0.0, 1.0}, {0.375, 0.0, 1.0, 1.0},
                             {0.625, 1.0, 1.0, 0.0}, {0.875, 1.0, 0.0, 0.0}, {1.0, 0.5, 0.0, 0.0}};
  for (int k = 1; k < 6; ++k)
    if (v <= stops[k][0]) {
      const double w = (v - stops[k - 1][0]) / (stops[k][0] - stops[k - 1][0]);
      return {channel(stops[k - 1][1] + w * (stops[k][1] - stops[k - 1][1])),
              channel(stops[k - 1][2] + w * (stops[k][2] - stops[k - 1][2])),
              channel(stops[k - 1][3] + w * (stops[k][3] - stops[k - 1][3]))};
    }
  return {128, 0, 0};
}

Rgb viridis(double v) {
  static const double anchors[5][3] = {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}};
  const double x = 4.0 * std::clamp(v, 0.0, 1.0);
  const int k = std::min(3, static_cast<int>(x));
  const double w = x - k;
  auto mix = [&](int c) { return channel((anchors[k][c] + w * (anchors[k + 1][c] - anchors[k][c])) / 255.0); };
  return {mix(0), mix(1), mix(2)};
}

Raster::Raster(int width, int height, Rgb background)
    : w_(width), h_(height), px_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), background) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("Raster: empty image");
}

void Raster::set(int x, int y, Rgb c) {
  if (x < 0 || y < 0 || x >= w_ || y >= h_) return;
  px_[static_cast<std::size_t>(h_ - 1 - y) * static_cast<std::size_t>(w_) + static_cast<std::size_t>(x)] = c;
}

void Raster::fill(int x0, int y0, int x1, int y1, Rgb c) {
  for (int y = std::max(0, y0); y <= std::min(h_ - 1, y1); ++y)
    for (int x = std::max(0, x0); x <= std::min(w_ - 1, x1); ++x) set(x, y, c);
}

void Raster::line(double x0, double y0, double x1, double y1, Rgb c, int thickness) {
  const double len = std::hypot(x1 - x0, y1 - y0);
  const int n = std::max(1, static_cast<int>(std::ceil(len * 2.0)));
  const int r = thickness / 2;
  for (int k = 0; k <= n; ++k) {
    const double w = static_cast<double>(k) / n;
    const int x = static_cast<int>(std::lround(x0 + w * (x1 - x0))), y = static_cast<int>(std::lround(y0 + w * (y1 - y0)));
    fill(x - r, y - r, x + r, y + r, c);
  }
}

void Raster::paste(const Raster& other, int x, int y) {
  for (int j = 0; j < other.h_; ++j)
    for (int i = 0; i < other.w_; ++i)
      set(x + i, y + j, other.px_[static_cast<std::size_t>(other.h_ - 1 - j) * static_cast<std::size_t>(other.w_) + static_cast<std::size_t>(i)]);
}

void Raster::write_png(const std::string& path) const {
  // Raw scanlines: filter byte 0, then RGB.
  std::vector<std::uint8_t> raw;
  raw.reserve(static_cast<std::size_t>(h_) * (1 + 3 * static_cast<std::size_t>(w_)));
  for (int y = 0; y < h_; ++y) {
    raw.push_back(0);
    for (int x = 0; x < w_; ++x) {
      const Rgb& c = px_[static_cast<std::size_t>(y) * static_cast<std::size_t>(w_) + static_cast<std::size_t>(x)];
      raw.insert(raw.end(), {c.r, c.g, c.b});
    }
  }
  // zlib stream: one deflate block with the fixed Huffman codes and matches at two
  // distances, the previous pixel (3) and the previous row: damage maps are mostly
  // runs of one colour, which this shrinks by one to two orders of magnitude.
  std::vector<std::uint8_t> z{0x78, 0x01};
  deflate_fixed(raw, {3, 1 + 3 * static_cast<std::size_t>(w_)}, z);
  std::uint32_t a = 1, b = 0;
  for (std::uint8_t v : raw) a = (a + v) % 65521u, b = (b + a) % 65521u;
  put32(z, (b << 16) | a);

  std::vector<std::uint8_t> png{0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  std::vector<std::uint8_t> ihdr;
  put32(ihdr, static_cast<std::uint32_t>(w_));
  put32(ihdr, static_cast<std::uint32_t>(h_));
  ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});  // 8-bit RGB, deflate, no filter choice, no interlace
  chunk(png, "IHDR", ihdr);
  chunk(png, "IDAT", z);
  chunk(png, "IEND", {});
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error("cannot write " + path);
  out.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
}

Raster damage_map(const std::vector<std::array<double, 2>>& xy, const std::vector<double>& value, double dx,
                  int pixels_per_cell, PlaneView* view_out, int margin) {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const auto& p : xy) x0 = std::min(x0, p[0]), y0 = std::min(y0, p[1]), x1 = std::max(x1, p[0]), y1 = std::max(y1, p[1]);
  PlaneView v{x0 - 0.5 * dx, y0 - 0.5 * dx, pixels_per_cell / dx, margin};
  const int w = static_cast<int>(std::ceil((x1 - x0 + dx) * v.scale)) + 2 * margin;
  const int h = static_cast<int>(std::ceil((y1 - y0 + dx) * v.scale)) + 2 * margin;
  Raster img(w, h);
  for (std::size_t i = 0; i < xy.size(); ++i) {
    const int px = static_cast<int>(std::floor(v.px(xy[i][0] - 0.5 * dx) + 0.5));
    const int py = static_cast<int>(std::floor(v.py(xy[i][1] - 0.5 * dx) + 0.5));
    img.fill(px, py, px + pixels_per_cell - 1, py + pixels_per_cell - 1, damage_colour(value[i]));
  }
  if (view_out) *view_out = v;
  return img;
}

Raster layer_map(const std::vector<std::array<double, 3>>& x0, const std::vector<double>& value, double dx, int normal,
                 double layer, int pixels_per_cell) {
  const int a = normal == 0 ? 1 : 0, b = normal == 2 ? 1 : 2;
  std::vector<std::array<double, 2>> xy;
  std::vector<double> v;
  for (std::size_t i = 0; i < x0.size(); ++i)
    if (std::abs(x0[i][normal] - layer) < 0.5 * dx) xy.push_back({x0[i][a], x0[i][b]}), v.push_back(value[i]);
  if (xy.empty()) throw std::invalid_argument("layer_map: no particle in that layer");
  return damage_map(xy, v, dx, pixels_per_cell);
}

Raster scatter_map(const std::vector<std::array<double, 2>>& xy, const std::vector<double>& value,
                   const std::vector<double>& depth, const PlaneView& view, int width, int height, int size) {
  std::vector<std::size_t> order(xy.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return depth[a] < depth[b]; });
  Raster img(width, height);
  for (std::size_t i : order) {
    const int px = static_cast<int>(std::lround(view.px(xy[i][0]))) - size / 2;
    const int py = static_cast<int>(std::lround(view.py(xy[i][1]))) - size / 2;
    img.fill(px, py, px + size - 1, py + size - 1, damage_colour(value[i]));
  }
  return img;
}

Raster grid(const std::vector<Raster>& cells, int columns, int gap) {
  if (cells.empty()) throw std::invalid_argument("grid: no cells");
  int w = 0, h = 0;
  for (const auto& c : cells) w = std::max(w, c.width()), h = std::max(h, c.height());
  const int rows = static_cast<int>((cells.size() + static_cast<std::size_t>(columns) - 1) / static_cast<std::size_t>(columns));
  Raster out(columns * w + (columns - 1) * gap, rows * h + (rows - 1) * gap);
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const int col = static_cast<int>(k) % columns, row = static_cast<int>(k) / columns;
    out.paste(cells[k], col * (w + gap), (rows - 1 - row) * (h + gap));
  }
  return out;
}

Raster side_by_side(const Raster& left, const Raster& right, int gap) {
  Raster out(left.width() + gap + right.width(), std::max(left.height(), right.height()));
  out.paste(left, 0, 0);
  out.paste(right, left.width() + gap, 0);
  return out;
}

}  // namespace pdmpm::test
