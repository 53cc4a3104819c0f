// tables.md of `slamkit study`: seed 001's Tables 1-5, ours beside the paper's.
#include <string>

#include <fmt/format.h>

#include "slamkit/runners/landmark/study_outputs.hpp"

namespace slamkit {
namespace {

std::string SectionTable(const StudyResult& result, int i) {
  std::string md = fmt::format(
      "## Table {0}. Section {0}\n\n"
      "| Method | Total observations | paper | Observations per step | paper | "
      "Observations per landmark | paper | Runs with the section |\n"
      "|---|---:|---:|---:|---:|---:|---:|---:|\n",
      i + 1);
  for (const StudyMethodResult& m : result.methods) {
    const PaperSectionRow& p = Seed001FiguresOf(m.key).sections[static_cast<std::size_t>(i)];
    if (i < static_cast<int>(m.sections.size())) {
      const SectionMean& s = m.sections[static_cast<std::size_t>(i)];
      md += fmt::format("| {} | {:.1f} | {} | {:.1f} | {} | {:.1f} | {} | {} |\n", m.title,
                        s.observations, p.observations, s.observations_per_period,
                        p.observations_per_period, s.observations_per_landmark,
                        p.observations_per_landmark, s.runs);
    } else {
      md += fmt::format("| {} | – | {} | – | {} | – | {} | 0 |\n", m.title, p.observations,
                        p.observations_per_period, p.observations_per_landmark);
    }
  }
  return md + "\n";
}

std::string ErrorTable(const StudyResult& result, bool position) {
  std::string md =
      position ? "## Table 4. Position error (each run's RMS: mean and variance over runs)\n\n"
                 "| Method | Mean [m] | paper | Variance [m²] | paper |\n"
               : "## Table 5. Heading error (each run's RMS: mean and variance over runs)\n\n"
                 "| Method | Mean [rad] | paper | Variance [rad²] | paper |\n";
  md += "|---|---:|---:|---:|---:|\n";
  for (const StudyMethodResult& m : result.methods) {
    const Spread& ours = position ? m.position_rms_m : m.heading_rms_rad;
    const PaperMethodFigures& p = Seed001FiguresOf(m.key);
    const MeanVariance& paper = position ? p.position_m : p.heading_rad;
    md += fmt::format("| {} | {:.4f} | {:.4f} | {:.4g} | {:.4g} |\n", m.title, ours.mean,
                      paper.mean, ours.variance, paper.variance);
  }
  return md + "\n";
}

std::string ConsistencyTable(const StudyResult& result) {
  std::string md =
      "## Consistency and time\n\n"
      "| Method | ANEES | 95 % band | Steps in band | Median run's ANEES | Position RMSE [m] | "
      "Heading RMSE [rad] | Landmarks mapped | Wall time [s] |\n"
      "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const StudyMethodResult& m : result.methods) {
    const MonteCarloResult& mc = m.mc;
    md += fmt::format(
        "| {} | {:.4g} | [{:.3f}, {:.3f}] | {:.0f} % | {:.4g} | {:.4f} | {:.4f} | "
        "{:.1f} | {:.1f} |\n",
        m.title, mc.anees_mean, mc.band.lo, mc.band.hi, 100.0 * mc.anees_fraction_in_band,
        m.anees_run_median, mc.rmse.position_m, mc.rmse.heading_rad, mc.landmarks_mapped_mean,
        m.wall_time_s);
  }
  return md +
         "\nANEES: the pose NEES (3 DoF) averaged over the runs still running at each step, then "
         "over steps; the band is that of a mean over all the runs, so one diverging run can "
         "lift it out of the band: the median over runs of each run's mean NEES shows the typical "
         "run. The paper gives its band for 50 runs as [2.36, 3.72] and reports its NEES only as "
         "a figure.\n";
}

}  // namespace

std::string StudyTablesMarkdown(const StudyResult& result) {
  const StudyParams& p = result.params;
  std::string md = fmt::format(
      "# Seed 001 (SWSLAM), Tables 1-5: ours beside the paper's\n\n"
      "{} Monte Carlo runs per method on the same worlds and seeds (master seed {}); FastSLAM "
      "2.0 with {} particles. Ours are means over runs; the `paper` columns are the figures "
      "printed in seed 001 (its Table 4 labels position errors rad and rad², evidently "
      "metres).\n\n{}\n\n",
      p.runs, p.seed, p.particles, StudySectionsNote());
  for (int i = 0; i < 3; ++i) md += SectionTable(result, i);
  md += ErrorTable(result, true);
  md += ErrorTable(result, false);
  return md + ConsistencyTable(result);
}

}  // namespace slamkit
