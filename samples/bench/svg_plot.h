// Minimal SVG charts for the bench report: lines or points over linear or log axes.
#pragma once
#include <string>
#include <vector>

namespace sao::bench {

struct Series {
  std::string label;
  std::vector<double> x, y;
  bool lines = true;  // false: points only (a scatter)
  std::vector<std::string> pointLabels;  // optional, one per point
  std::string colour;    // empty: the palette's next colour
  double opacity = 1;    // below 1: faint points and line (a background of many points)
};

struct Chart {
  std::string title, xLabel, yLabel;
  bool logX = false, logY = false;
  std::vector<Series> series;
};

std::string renderSvg(const Chart& chart, int width = 720, int height = 440);

}  // namespace sao::bench
