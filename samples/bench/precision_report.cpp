#include "precision_report.h"

#include <cmath>
#include <filesystem>
#include <fstream>

namespace sao::bench {

void writePrecision(const std::string& dir, const PrecisionByBackend& results) {
  const std::filesystem::path out(dir);
  std::ofstream csv(out / "precision.csv");
  csv << "backend,format,far_m,convention,clip,distance_bin_m,z_worst_m,z_p99_m,normal_worst_deg,normal_p99_deg,"
         "pixels,lost\n";
  std::ofstream txt(out / "precision.txt");
  for (const auto& [backend, rows] : results) {
    txt << "== " << backend << " prepass\n" << prepass::formatPrecisionTable(rows) << "\n";
    for (const auto& r : rows)
      csv << backend << "," << toString(r.format) << "," << (std::isinf(r.farPlane) ? std::string("inf") : std::to_string(r.farPlane))
          << "," << (r.reversed ? "reversed" : "standard") << ","
          << (r.clip == ClipDepth::ZeroToOne ? "0..1" : "-1..1") << "," << r.distanceBin << "," << r.zWorstM << ","
          << r.zP99M << "," << r.normalWorstDeg << "," << r.normalP99Deg << "," << r.pixels << "," << r.lost << "\n";
  }
}

}  // namespace sao::bench
