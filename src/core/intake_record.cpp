#include "core/intake_record.h"

#include <cstdio>

namespace xparam {
namespace {

std::string plural(int n, const char* one, const char* many) { return std::to_string(n) + " " + (n == 1 ? one : many); }

// "0.31%": shares are small and their size is the point of the message.
std::string percent(double share) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2g%%", 100.0 * share);
  return text;
}

std::string length(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

}  // namespace

int IntakeRecord::dropped_faces() const {
  int faces = 0;
  for (const DroppedPart& part : dropped_parts) faces += part.faces;
  return faces;
}

double IntakeRecord::dropped_area() const {
  double area = 0.0;
  for (const DroppedPart& part : dropped_parts) area += part.area;
  return area;
}

double IntakeRecord::filled_area() const {
  double area = 0.0;
  for (const FilledHole& hole : holes) area += hole.area;
  for (const CutHandle& handle : handles) area += handle.area;
  return area;
}

std::vector<std::string> IntakeRecord::describe() const {
  std::vector<std::string> lines;
  if (merged_vertices > 0) lines.push_back(plural(merged_vertices, "vertex", "vertices") + " welded onto an equal one");
  if (unused_vertices > 0) lines.push_back(plural(unused_vertices, "unused vertex", "unused vertices") + " left out");
  if (degenerate_faces > 0) lines.push_back(plural(degenerate_faces, "degenerate face", "degenerate faces") + " removed");
  if (duplicate_faces > 0) lines.push_back(plural(duplicate_faces, "duplicated face", "duplicated faces") + " removed");
  if (split_vertices > 0)
    lines.push_back(plural(split_vertices, "vertex copy", "vertex copies") + " made to cut non-manifold edges or vertices open");
  if (reversed_faces > 0) lines.push_back(plural(reversed_faces, "face", "faces") + " turned to agree with their neighbours");
  if (!dropped_parts.empty())
    lines.push_back(plural(parts, "part", "parts") + ": " + std::to_string(dropped_parts.size()) + " dropped (" +
                    plural(dropped_faces(), "face", "faces") + ", " + percent(dropped_area() / total_area) +
                    " of the area)");
  for (const FilledHole& hole : holes)
    lines.push_back("hole of perimeter " + length(hole.perimeter) +
                    (hole.nearest_anchor.empty() ? std::string() : " near \"" + hole.nearest_anchor + "\"") +
                    " filled (" + plural(hole.faces, "face", "faces") + ", area " + length(hole.area) +
                    (hole.faired ? "" : ", not faired") + ")");
  for (const CutHandle& handle : handles)
    lines.push_back("handle cut along a loop of length " + length(handle.length) +
                    (handle.nearest_anchor.empty() ? std::string() : " near \"" + handle.nearest_anchor + "\"") +
                    " and capped (" + plural(handle.faces, "face", "faces") + ", area " + length(handle.area) +
                    (handle.faired ? "" : ", not faired") + ")");
  return lines;
}

}  // namespace xparam
