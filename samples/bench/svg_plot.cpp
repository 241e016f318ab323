#include "svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace sao::bench {
namespace {

const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#17becf", "#7f7f7f"};

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", v);
  return b;
}

std::string escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '<') o += "&lt;";
    else if (c == '>') o += "&gt;";
    else if (c == '&') o += "&amp;";
    else o += c;
  }
  return o;
}

}  // namespace

std::string renderSvg(const Chart& c, int W, int H) {
  const double left = 70, right = 180, top = 40, bottom = 50;
  double x0 = std::numeric_limits<double>::max(), x1 = -x0, y0 = x0, y1 = -x0;
  auto tx = [&](double v) { return c.logX ? std::log10(std::max(v, 1e-12)) : v; };
  auto ty = [&](double v) { return c.logY ? std::log10(std::max(v, 1e-12)) : v; };
  for (const auto& s : c.series)
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      x0 = std::min(x0, tx(s.x[i])), x1 = std::max(x1, tx(s.x[i]));
      y0 = std::min(y0, ty(s.y[i])), y1 = std::max(y1, ty(s.y[i]));
    }
  if (!(x1 > x0)) x1 = x0 + 1;
  if (!(y1 > y0)) y1 = y0 + 1;
  if (!c.logY) y0 = std::min(y0, 0.0);
  const double padY = 0.05 * (y1 - y0);
  y1 += padY;
  auto px = [&](double v) { return left + (tx(v) - x0) / (x1 - x0) * (W - left - right); };
  auto py = [&](double v) { return H - bottom - (ty(v) - y0) / (y1 - y0) * (H - top - bottom); };
  std::ostringstream o;
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
    << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<text x=\"" << W / 2 << "\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">" << escape(c.title) << "</text>\n";
  // Axes with 5 ticks each.
  o << "<line x1=\"" << left << "\" y1=\"" << H - bottom << "\" x2=\"" << W - right << "\" y2=\"" << H - bottom
    << "\" stroke=\"black\"/>\n<line x1=\"" << left << "\" y1=\"" << top << "\" x2=\"" << left << "\" y2=\"" << H - bottom
    << "\" stroke=\"black\"/>\n";
  for (int i = 0; i <= 4; ++i) {
    const double vx = x0 + (x1 - x0) * i / 4, vy = y0 + (y1 - y0) * i / 4;
    const double sx = left + (W - left - right) * i / 4.0, sy = H - bottom - (H - top - bottom) * i / 4.0;
    o << "<text x=\"" << sx << "\" y=\"" << H - bottom + 16 << "\" text-anchor=\"middle\">"
      << number(c.logX ? std::pow(10, vx) : vx) << "</text>\n";
    o << "<text x=\"" << left - 6 << "\" y=\"" << sy + 4 << "\" text-anchor=\"end\">"
      << number(c.logY ? std::pow(10, vy) : vy) << "</text>\n";
    o << "<line x1=\"" << left << "\" y1=\"" << sy << "\" x2=\"" << W - right << "\" y2=\"" << sy
      << "\" stroke=\"#ddd\"/>\n";
  }
  o << "<text x=\"" << (left + W - right) / 2 << "\" y=\"" << H - 12 << "\" text-anchor=\"middle\">" << escape(c.xLabel)
    << "</text>\n<text transform=\"translate(16," << (top + H - bottom) / 2 << ") rotate(-90)\" text-anchor=\"middle\">"
    << escape(c.yLabel) << "</text>\n";
  for (std::size_t k = 0; k < c.series.size(); ++k) {
    const auto& s = c.series[k];
    const std::string colour = s.colour.empty() ? kColours[k % 8] : s.colour;
    const std::string faint = s.opacity < 1 ? " opacity=\"" + number(s.opacity) + "\"" : "";
    if (s.lines && s.x.size() > 1) {
      o << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"2\"" << faint << " points=\"";
      for (std::size_t i = 0; i < s.x.size(); ++i) o << px(s.x[i]) << "," << py(s.y[i]) << " ";
      o << "\"/>\n";
    }
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      o << "<circle cx=\"" << px(s.x[i]) << "\" cy=\"" << py(s.y[i]) << "\" r=\"4\" fill=\"" << colour << "\"" << faint << "/>\n";
      if (i < s.pointLabels.size())
        o << "<text x=\"" << px(s.x[i]) + 6 << "\" y=\"" << py(s.y[i]) - 6 << "\" font-size=\"10\">"
          << escape(s.pointLabels[i]) << "</text>\n";
    }
    o << "<rect x=\"" << W - right + 12 << "\" y=\"" << top + 18 * k << "\" width=\"12\" height=\"12\" fill=\"" << colour
      << "\"/>\n<text x=\"" << W - right + 30 << "\" y=\"" << top + 18 * k + 10 << "\">" << escape(s.label) << "</text>\n";
  }
  o << "</svg>\n";
  return o.str();
}

}  // namespace sao::bench
