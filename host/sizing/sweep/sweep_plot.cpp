#include "voxcd/host/sizing/sweep/sweep_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace voxcd {

namespace {

constexpr int kLeft = 50, kRight = 20, kTop = 20, kBottom = 40;

// Whole powers of ten around [lo, hi] (one decade when they are equal).
void decades(double lo, double hi, double& a, double& b) {
  a = std::pow(10.0, std::floor(std::log10(lo)));
  b = std::pow(10.0, std::ceil(std::log10(hi)));
  if (b <= a) b = a * 10;
}

void disc(Image& img, int cx, int cy, int r, uint8_t red, uint8_t green, uint8_t blue) {
  for (int y = -r; y <= r; ++y)
    for (int x = -r; x <= r; ++x)
      if (x * x + y * y <= r * r) img.set(cx + x, cy + y, red, green, blue);
}

}  // namespace

std::string SweepPlot::caption() const {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "x: cycles per frame (largest frame), log, %g to %g; y: contact error bound (world units), log, %g to "
                "%g; a grey line at every power of ten; red: the Pareto front",
                x_lo, x_hi, y_lo, y_hi);
  return buf;
}

SweepPlot sweep_plot(const SweepTable& t) {
  SweepPlot p;
  Image& img = p.image;
  double xmin = HUGE_VAL, xmax = 0, ymin = HUGE_VAL, ymax = 0;
  for (const SweepRow& r : t.rows) {
    if (!r.ok() || r.max_cycles == 0 || !(r.contact_bound > 0)) continue;
    xmin = std::min(xmin, double(r.max_cycles)), xmax = std::max(xmax, double(r.max_cycles));
    ymin = std::min(ymin, r.contact_bound), ymax = std::max(ymax, r.contact_bound);
  }
  if (xmax > 0) {
    decades(xmin, xmax, p.x_lo, p.x_hi);
    decades(ymin, ymax, p.y_lo, p.y_hi);
  }
  const int w = img.width - kLeft - kRight, h = img.height - kTop - kBottom;
  auto px = [&](double x) { return kLeft + int(std::lround(w * std::log10(x / p.x_lo) / std::log10(p.x_hi / p.x_lo))); };
  auto py = [&](double y) {
    return kTop + h - int(std::lround(h * std::log10(y / p.y_lo) / std::log10(p.y_hi / p.y_lo)));
  };
  for (double x = p.x_lo; x <= p.x_hi * 1.0001; x *= 10)
    for (int y = kTop; y <= kTop + h; ++y) img.set(px(x), y, 210, 210, 210);
  for (double y = p.y_lo; y <= p.y_hi * 1.0001; y *= 10)
    for (int x = kLeft; x <= kLeft + w; ++x) img.set(x, py(y), 210, 210, 210);
  for (int x = kLeft; x <= kLeft + w; ++x) img.set(x, kTop + h, 0, 0, 0);
  for (int y = kTop; y <= kTop + h; ++y) img.set(kLeft, y, 0, 0, 0);
  // The others first, so that the front's points lie on top.
  for (int front = 0; front < 2; ++front)
    for (const SweepRow& r : t.rows) {
      if (!r.ok() || r.max_cycles == 0 || !(r.contact_bound > 0) || int(r.pareto) != front) continue;
      if (front)
        disc(img, px(double(r.max_cycles)), py(r.contact_bound), 5, 220, 30, 30);
      else
        disc(img, px(double(r.max_cycles)), py(r.contact_bound), 3, 90, 110, 150);
    }
  return p;
}

}  // namespace voxcd
