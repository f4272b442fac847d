#pragma once
/// \file
/// Loading a target scan through the intake: the file as it is when the pipeline takes it,
/// otherwise the mesh prepare_scan makes of it, with every element traced back to the file.

#include "core/anchors.h"
#include "intake/scan_intake.h"
#include "io/mesh_loader.h"

#include <filesystem>
#include <vector>

namespace xparam {

/// The anchors' positions on the file's soup (a vertex index or face + barycentrics outside the
/// file is left out: anchor validation names it later).
std::vector<IntakeLandmark> landmarks_on_file(const AnchorSet& anchors, const TriangleSoup& soup);

/// What the intake makes of a soup read from `path`: the loaded mesh (LoadedMesh::intake says what
/// changed; `file_order` maps every mesh face and vertex to the file, fill elements numbered after
/// the file's). With IntakeMode::Strict, or when validation finds the file usable (its two load
/// repairs included) and of genus 0, this is load_soup: the intake runs only on files the pipeline
/// would refuse (strict refuses degenerate faces by their count, saying the intake drops them).
/// \throw InputError naming the file: what prepare_scan refuses, or what is still wrong after it.
LoadedMesh load_scan_soup(const std::filesystem::path& path, TriangleSoup soup, const AnchorSet& anchors,
                          const IntakeSettings& settings);

/// Read `path` and load_scan_soup it. \throw InputError naming the file
LoadedMesh load_scan(const std::filesystem::path& path, const AnchorSet& anchors, const IntakeSettings& settings);

}  // namespace xparam
