#pragma once
/// \file
/// What the scan intake did over a batch: how many targets it repaired, how many lost loose parts
/// or had holes filled, and the totals, for the summary (JSON and the closing lines).

#include "batch/batch_driver.h"

#include <cstddef>
#include <vector>

namespace xparam {

/// The intake's figures over a batch's targets (run or kept), from their metrics rows and
/// diagnoses; failed targets count in none.
struct IntakeTotals {
  /// Targets the intake changed: its record is in the diagnosis (every repair, a re-oriented face
  /// too), or, for a row of an archive from before diagnoses held it, parts were dropped or holes filled.
  std::size_t repaired = 0;
  std::size_t with_parts_dropped = 0;  ///< targets that lost loose parts
  std::size_t with_holes_filled = 0;   ///< targets with holes filled
  std::size_t dropped_faces = 0;       ///< faces of the dropped parts, all targets
  double dropped_area = 0.0;           ///< their area (each target in its own units squared)
  std::size_t holes_filled = 0;        ///< holes filled, all targets
  double filled_area = 0.0;            ///< area of the fill patches (each target in its own units squared)
  std::size_t on_filled_vertices = 0;  ///< template vertices whose image is on filled-in surface, all
};

/// The intake's figures over `targets`.
IntakeTotals intake_totals(const std::vector<TargetOutcome>& targets);

}  // namespace xparam
