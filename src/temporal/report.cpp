#include "temporal/report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace holoray {

namespace {
std::string db(double v) { return std::isnan(v) ? "-" : std::isinf(v) ? "inf" : fmt::format("{:.2f}", v); }
double pct(int64_t part, int64_t whole) { return whole > 0 ? 100.0 * part / whole : 0; }
}  // namespace

RunSummary summarise(const std::vector<FrameReport>& frames) {
  RunSummary s;
  double psnr_sum = 0;
  int psnr_n = 0;
  s.min_psnr = s.min_hold_psnr = INFINITY;
  double hold_sum = 0;
  int hold_n = 0, held = 0;
  int64_t px = 0, reprojected = 0, traced = 0, interpolated = 0;
  for (const FrameReport& f : frames) {
    ++s.frames;
    s.full_seconds += f.reference_seconds;
    s.accelerated_seconds += f.seconds;
    if (f.keyframe) {
      ++s.keyframes;
      // A keyframe traced with the shadow cache may differ from the full trace.
      if (f.difference && !std::isinf(f.difference->psnr_all())) {
        const double p = f.difference->psnr_all();
        s.min_psnr = std::min(s.min_psnr, p);
        psnr_sum += p;
        ++psnr_n;
      }
      continue;
    }
    px += f.pixels;
    reprojected += f.reprojected;
    traced += f.traced;
    interpolated += f.interpolated;
    s.rebuilt_frames += f.rebuilt;
    if (f.hold) {
      ++held;
      const double h = f.hold->psnr_all();
      s.min_hold_psnr = std::min(s.min_hold_psnr, h);
      if (!std::isinf(h)) hold_sum += h, ++hold_n;
      if (f.difference && f.difference->psnr_all() < h) ++s.below_hold_frames;
    }
    if (!f.difference) continue;
    const double p = f.difference->psnr_all();
    s.min_psnr = std::min(s.min_psnr, p);
    if (std::isinf(p)) {
      ++s.exact_frames;
    } else {
      psnr_sum += p;
      ++psnr_n;
    }
  }
  s.mean_psnr = psnr_n ? psnr_sum / psnr_n : INFINITY;
  s.mean_hold_psnr = hold_n ? hold_sum / hold_n : INFINITY;
  if (held == 0) s.mean_hold_psnr = s.min_hold_psnr = NAN;  // no reprojected frame: nothing was held
  s.reprojected_percent = pct(reprojected, px);
  s.traced_percent = pct(traced, px);
  s.interpolated_percent = pct(interpolated, px);
  return s;
}

std::string markdown_report(const std::string& title, const std::vector<std::string>& context,
                            const std::vector<FrameReport>& frames) {
  const RunSummary s = summarise(frames);
  std::string md = fmt::format("# {}\n\n", title);
  for (const std::string& line : context) md += fmt::format("{}\n", line);
  md += "\n## Time (the paper's Table 2)\n\n";
  md += "| frames | keyframes | full ray tracing s | accelerated s | saved s | saved % | mean PSNR dB | min PSNR dB | hold mean PSNR dB | hold min PSNR dB | frames below hold | rebuilt frames | exact frames | reprojected % | traced % | interpolated % |\n";
  md += "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  md += fmt::format("| {} | {} | {:.3f} | {:.3f} | {:.3f} | {:.1f} | {} | {} | {} | {} | {} | {} | {} | {:.2f} | {:.2f} | {:.2f} |\n",
                    s.frames, s.keyframes, s.full_seconds, s.accelerated_seconds, s.saved_seconds(), s.saved_percent(),
                    db(s.mean_psnr), db(s.min_psnr), db(s.mean_hold_psnr), db(s.min_hold_psnr), s.below_hold_frames,
                    s.rebuilt_frames, s.exact_frames, s.reprojected_percent, s.traced_percent, s.interpolated_percent);
  md += "\nPixel shares are of the reprojected (non-key) frames; PSNR = 10 log10(255^2 / MSE) over the 8-bit outputs, "
        "mean over frames that are not exact. \"Hold\" is the do-nothing baseline: each reprojected frame replaced by "
        "its nearest keyframe, scored against the same full trace.\n";
  md += "\n## Per frame (the paper's Table 1; its column \"RMSE\" holds the MSE)\n\n";
  md += "| frame | kind | MSE R | MSE G | MSE B | MSE | PSNR dB | hold PSNR dB | reprojected | missed | leaks | rejected | traced | interpolated | s | full s |\n";
  md += "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const FrameReport& f : frames) {
    const std::string mse = f.difference ? fmt::format("{:.4f} | {:.4f} | {:.4f} | {:.4f} | {}", f.difference->mse[0],
                                                       f.difference->mse[1], f.difference->mse[2], f.difference->mse_all,
                                                       db(f.difference->psnr_all()))
                                         : "- | - | - | - | -";
    md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.4f} | {:.4f} |\n", f.frame,
                      f.keyframe             ? std::string("key")
                      : f.copied_from >= 0 ? fmt::format("copy of key {}", f.copied_from)
                      : f.rebuilt            ? std::string("reprojected, rebuilt")
                                             : std::string("reprojected"),
                      mse,
                      f.hold ? db(f.hold->psnr_all()) : "-", f.reprojected, f.missed, f.leaks, f.rejected, f.traced,
                      f.interpolated, f.seconds, f.reference_seconds);
  }
  return md;
}

}  // namespace holoray
