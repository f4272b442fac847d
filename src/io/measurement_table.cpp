#include "io/measurement_table.h"

#include "core/errors.h"
#include "io/archive_reader.h"
#include "io/text_file.h"

#include <cmath>
#include <cstdio>
#include <vector>

namespace xparam {
namespace {

// A CSV cell: quoted when it holds a comma, a quote or a line break (RFC 4180).
std::string cell(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string number(double value) {
  if (!std::isfinite(value)) return "";
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

template <typename Values>
std::string row(const std::string& name, const std::string& status, const Values& values, std::size_t count) {
  std::string line = cell(name) + "," + status;
  for (std::size_t i = 0; i < count; ++i)
    line += "," + (i < static_cast<std::size_t>(values.size()) ? number(values[static_cast<Eigen::Index>(i)]) : "");
  return line + "\n";
}

}  // namespace

std::string measurement_csv(const ArchiveReader& reader) {
  const TemplateRecord t = reader.read_template();
  const std::size_t m = t.measurement_names.size();
  if (m == 0)
    throw ArchiveError(reader.path().string() +
                       ": the archive holds no measurements; run the batch with --measurements FILE to take them");
  std::string csv = "name,status";
  for (std::size_t i = 0; i < m; ++i) csv += "," + cell(t.measurement_names[i] + " (" + t.measurement_units[i] + ")");
  csv += "\n" + row(t.mesh_file, "template", t.measurement_values, m);
  for (const ArchiveTargetSummary& target : reader.targets()) {
    const Eigen::Map<const Eigen::VectorXd> values(target.measurements.data(),
                                                   static_cast<Eigen::Index>(target.measurements.size()));
    csv += row(target.name, !target.ok ? "failed" : target.suspect ? "suspect" : "ok", values, m);
  }
  return csv;
}

void export_measurements(const std::filesystem::path& archive, const std::filesystem::path& out) {
  write_text_atomically(out, measurement_csv(ArchiveReader(archive)));
}

}  // namespace xparam
