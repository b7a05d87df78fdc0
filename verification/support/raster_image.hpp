#pragma once
// Small RGB rasters written as PNG without any image library (a fixed-Huffman
// deflate block with run matches; CRC-32 and Adler-32 by hand), for the report's
// pictures: damage maps (the particles of a lattice drawn as square cells
// coloured by a value, with crack paths drawn over them) and schlieren panels.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace pdmpm::test {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
};

// Blue (0) → cyan → yellow → red (1), clamped: a jet-like scale for damage φ.
Rgb damage_colour(double v);

// Perceptually ordered scale for v in [0, 1], clamped (five anchors of
// matplotlib's viridis, linearly interpolated): for smooth fields such as |v|.
Rgb viridis(double v);

class Raster {
 public:
  Raster(int width, int height, Rgb background = {255, 255, 255});
  int width() const { return w_; }
  int height() const { return h_; }
  void set(int x, int y, Rgb c);  // (0, 0) is the lower-left corner; outside is ignored
  void fill(int x0, int y0, int x1, int y1, Rgb c);  // inclusive pixel rectangle
  void line(double x0, double y0, double x1, double y1, Rgb c, int thickness = 1);
  // Places `other` with its lower-left corner at (x, y).
  void paste(const Raster& other, int x, int y);
  void write_png(const std::string& path) const;

 private:
  int w_, h_;
  std::vector<Rgb> px_;
};

// Maps points of a plane onto a raster: `scale` pixels per metre, `min` at the
// lower-left corner plus a margin of `margin` pixels.
struct PlaneView {
  double min_x = 0.0, min_y = 0.0, scale = 1.0;
  int margin = 0;
  double px(double x) const { return margin + (x - min_x) * scale; }
  double py(double y) const { return margin + (y - min_y) * scale; }
};

// Particles (x, y) of spacing dx drawn as cells of dx coloured by damage_colour(value).
// The view covers their bounding box; `pixels_per_cell` sets the size.
Raster damage_map(const std::vector<std::array<double, 2>>& xy, const std::vector<double>& value, double dx,
                  int pixels_per_cell, PlaneView* view_out = nullptr, int margin = 4);

// One lattice layer of a 3D body: the particles whose reference coordinate along
// `normal` (0, 1, 2) lies within dx/2 of `layer`, drawn over the other two axes
// (in increasing order: x–y for normal z, x–z for normal y, y–z for normal x).
Raster layer_map(const std::vector<std::array<double, 3>>& x0, const std::vector<double>& value, double dx, int normal,
                 double layer, int pixels_per_cell);

// Points (x, y) drawn as squares of `size` pixels coloured by value, in the view's
// frame; points with a larger `depth` are drawn last (on top).
Raster scatter_map(const std::vector<std::array<double, 2>>& xy, const std::vector<double>& value,
                   const std::vector<double>& depth, const PlaneView& view, int width, int height, int size);

// Rasters in a grid of `columns`, left to right then top to bottom.
Raster grid(const std::vector<Raster>& cells, int columns, int gap = 8);

// Two rasters side by side with a gap, aligned at the bottom.
Raster side_by_side(const Raster& left, const Raster& right, int gap = 8);

}  // namespace pdmpm::test
