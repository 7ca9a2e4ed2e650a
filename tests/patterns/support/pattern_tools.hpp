#pragma once
// Helpers for the pattern-export tests: scratch directories, running the real client
// programs, reading their images (PNG via cairo, PGM from pdftoppm), polygon geometry.
#include <cairo.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/shell_command.hpp"
#include "tightfit/common/planar.hpp"
#include "tightfit/common/types.hpp"

namespace tightfit::test {

/// A fresh, empty directory for one test; removed again when the test passed (kept
/// for inspection when it failed).
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() /
              ("tightfit_pattern_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  ~ScratchDir() {
    if (!::testing::Test::HasFailure()) {
      std::error_code ec;
      std::filesystem::remove_all(path_, ec);
    }
  }
  operator const std::filesystem::path&() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

inline ScratchDir scratch_dir(const std::string& name) { return ScratchDir(name); }

/// Fails the test when a client program the test relies on is not installed.
inline void require_program(const std::string& program) {
  ASSERT_TRUE(std::filesystem::exists(program))
      << program << " is not installed (run scripts/install-deps.sh)";
}

/// A grey image, 0 = black … 255 = white, row-major.
struct GrayImage {
  int width = 0;
  int height = 0;
  std::vector<unsigned char> pixels;
  unsigned char at(int x, int y) const {
    return pixels[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)];
  }
  double darkness(int x, int y) const { return (255.0 - at(x, y)) / 255.0; }
};

/// Reads a PNG with cairo, composited over white and converted to grey.
inline GrayImage read_png(const std::filesystem::path& path) {
  GrayImage image;
  cairo_surface_t* surface = cairo_image_surface_create_from_png(path.c_str());
  if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS) {
    cairo_surface_destroy(surface);
    ADD_FAILURE() << "cannot read PNG " << path;
    return image;
  }
  cairo_surface_flush(surface);
  image.width = cairo_image_surface_get_width(surface);
  image.height = cairo_image_surface_get_height(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  const cairo_format_t format = cairo_image_surface_get_format(surface);
  const unsigned char* data = cairo_image_surface_get_data(surface);
  image.pixels.resize(static_cast<size_t>(image.width) * static_cast<size_t>(image.height));
  for (int y = 0; y < image.height; ++y) {
    const auto* row = reinterpret_cast<const uint32_t*>(data + static_cast<ptrdiff_t>(y) * stride);
    for (int x = 0; x < image.width; ++x) {
      const uint32_t v = row[x];
      // Premultiplied ARGB: over white, channel + (255 − alpha).
      const double a = format == CAIRO_FORMAT_ARGB32 ? ((v >> 24) & 0xffu) : 255.0;
      const double r = ((v >> 16) & 0xffu) + 255.0 - a;
      const double g = ((v >> 8) & 0xffu) + 255.0 - a;
      const double b = (v & 0xffu) + 255.0 - a;
      image.pixels[static_cast<size_t>(y) * static_cast<size_t>(image.width) +
                   static_cast<size_t>(x)] =
          static_cast<unsigned char>(std::lround(0.299 * r + 0.587 * g + 0.114 * b));
    }
  }
  cairo_surface_destroy(surface);
  return image;
}

/// Reads a binary PGM (P5, maxval 255) as written by `pdftoppm -gray`.
inline GrayImage read_pgm(const std::filesystem::path& path) {
  GrayImage image;
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  int maxval = 0;
  in >> magic >> image.width >> image.height >> maxval;
  in.get();
  if (!in || magic != "P5" || maxval != 255) {
    ADD_FAILURE() << "cannot read PGM " << path;
    return {};
  }
  image.pixels.resize(static_cast<size_t>(image.width) * static_cast<size_t>(image.height));
  in.read(reinterpret_cast<char*>(image.pixels.data()),
          static_cast<std::streamsize>(image.pixels.size()));
  if (!in) ADD_FAILURE() << "short PGM " << path;
  return image;
}

/// Darkness-weighted centre (px) of the columns x0..x1 of row y.
inline double ink_centre_x(const GrayImage& image, int y, int x0, int x1) {
  double sum = 0.0;
  double weighted = 0.0;
  for (int x = std::max(0, x0); x <= std::min(image.width - 1, x1); ++x) {
    const double d = image.darkness(x, y);
    sum += d;
    weighted += d * (x + 0.5);
  }
  return sum > 0.0 ? weighted / sum : -1.0;
}

/// Darkness-weighted centre (px) of the rows y0..y1 of column x.
inline double ink_centre_y(const GrayImage& image, int x, int y0, int y1) {
  double sum = 0.0;
  double weighted = 0.0;
  for (int y = std::max(0, y0); y <= std::min(image.height - 1, y1); ++y) {
    const double d = image.darkness(x, y);
    sum += d;
    weighted += d * (y + 0.5);
  }
  return sum > 0.0 ? weighted / sum : -1.0;
}

/// Distance from `q` to the segment a–b.
inline double segment_distance(const Vec2& q, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((q - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (q - (a + d * t)).norm();
}

/// Perimeter of the closed polygon (points in order, the last not repeated).
inline double perimeter(const std::vector<Vec2>& polygon) {
  double length = 0.0;
  for (size_t i = 0; i < polygon.size(); ++i)
    length += (polygon[(i + 1) % polygon.size()] - polygon[i]).norm();
  return length;
}

/// Distance from `q` to the closed polyline `polygon`.
inline double polygon_distance(const Vec2& q, const std::vector<Vec2>& polygon) {
  double best = 1e300;
  for (size_t i = 0; i < polygon.size(); ++i) {
    best = std::min(best, segment_distance(q, polygon[i], polygon[(i + 1) % polygon.size()]));
  }
  return best;
}

/// Whether `q` lies inside the closed polygon (crossing number).
inline bool inside_polygon(const Vec2& q, const std::vector<Vec2>& polygon) {
  return tightfit::inside_polygon(
      polygon.size(), [&](size_t i) { return polygon[i]; }, q);
}

/// Whether two non-adjacent edges of the closed polygon cross or touch.
inline bool self_intersects(const std::vector<Vec2>& polygon) {
  const size_t n = polygon.size();
  auto cross = [](const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); };
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = i + 1; j < n; ++j) {
      if (j == i + 1 || (i == 0 && j == n - 1)) continue;
      const Vec2 p = polygon[i];
      const Vec2 r = polygon[(i + 1) % n] - p;
      const Vec2 q = polygon[j];
      const Vec2 s = polygon[(j + 1) % n] - q;
      const double denom = cross(r, s);
      if (std::abs(denom) < 1e-14) continue;
      const double t = cross(q - p, s) / denom;
      const double u = cross(q - p, r) / denom;
      if (t >= 0.0 && t <= 1.0 && u >= 0.0 && u <= 1.0) return true;
    }
  }
  return false;
}

}  // namespace tightfit::test
