// holoray/temporal: the run's measurements as Markdown, in the shape of the
// paper's Table 1 (per frame: MSE per channel, PSNR, pixels reprojected,
// missed, traced) and Table 2 (full against accelerated time, time saved).
#pragma once

#include <string>
#include <vector>

#include "temporal/sequence.hpp"

namespace holoray {

/// Totals over a run (Table 2).
struct RunSummary {
  int frames = 0, keyframes = 0;
  double full_seconds = 0;         ///< sum of reference_seconds
  double accelerated_seconds = 0;  ///< sum of seconds
  double saved_seconds() const { return full_seconds - accelerated_seconds; }
  double saved_percent() const { return full_seconds > 0 ? 100 * saved_seconds() / full_seconds : 0; }
  double mean_psnr = 0;  ///< over reprojected frames (and keyframes traced with the cache) with a finite PSNR
  double min_psnr = 0;   ///< over the same frames (inf when all are exact)
  int exact_frames = 0;  ///< reprojected frames identical to the reference
  double reprojected_percent = 0, traced_percent = 0, interpolated_percent = 0;  ///< of the reprojected frames' pixels
  /// Holding the nearest keyframe (the do-nothing baseline), over the same
  /// frames; NaN (printed "-") when no frame was reprojected.
  double mean_hold_psnr = 0, min_hold_psnr = 0;
  int below_hold_frames = 0;  ///< reprojected frames that scored below holding
  int rebuilt_frames = 0;     ///< frames whose holes were traced, not interpolated
};

RunSummary summarise(const std::vector<FrameReport>& frames);

/// The report: a heading, `context` lines (command, machine) as given, the
/// summary (Table 2) and the per-frame table (Table 1).
std::string markdown_report(const std::string& title, const std::vector<std::string>& context,
                            const std::vector<FrameReport>& frames);

}  // namespace holoray
