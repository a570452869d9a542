// An n-ball sweep written as its values come: each value's CSV rows go to a spill file and
// its analysis is dropped, so that a sweep holds a few kB a value (its comments, summary row,
// Campbell samples and stability flags) instead of every analysis (docs/robustness.md
// "Memory and disk"). The files are byte for byte sweep_csv's and sweep_summary_csv's.
//
//   abu::SweepStream stream("omega", "rad/s", values.size(), n_max, /*campbell=*/true);
//   for (i ...) stream.add(values[i], abu::analyze(p_i), p_i);
//   auto [csv, summary] = stream.stage(out, "out/sweep_omega.csv", "out/summary_omega.csv", header);
#pragma once

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "abu/analysis/dry_friction.hpp"
#include "abu/output/files.hpp"
#include "abu/output/report_views.hpp"

namespace abu {

class SweepStream {
 public:
  /// `values` the sweep's length (its CSV says it first), `n_max` the largest ball count (the
  /// CSV's columns), `campbell` whether to keep the Campbell samples (an omega sweep), `dry` the
  /// dry verdict's coefficients ("the same mu_i"; empty: no dry_* columns, report_dry_along.hpp).
  SweepStream(std::string name, std::string unit, std::size_t values, int n_max, bool campbell, std::string dry = {});
  /// The next value's analysis, written and dropped; `dry` its dry figures (with dry_* columns).
  void add(double value, const AnalysisN& a, const ParamsN& p, const DryFigures& dry = {});
  /// Stages the long CSV (head, every value's comments, columns, the spilled rows) and the
  /// summary; returns their staged paths.
  std::pair<std::filesystem::path, std::filesystem::path> stage(OutputTransaction& out,
                                                                const std::filesystem::path& csv,
                                                                const std::filesystem::path& summary,
                                                                std::string_view header);
  /// The Campbell samples, series contiguous (empty unless `campbell`).
  std::vector<CampbellSample> campbell();
  StabilityRanges ranges() const;
  const std::vector<double>& values() const { return values_; }

 private:
  std::string name_, unit_;
  std::size_t count_;
  int n_max_;
  bool campbell_;
  std::string dry_;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> rows_;  // the spill file (tmpfile, gone when closed)
  std::string comments_, summary_rows_;
  std::vector<double> values_;
  std::vector<StableAt> stable_;
  std::vector<CampbellSample> samples_;
};

/// The two-ball sweep the same way (sweep_csv's bytes): its rows, ordered by family and
/// member before value, go to one spill file per family and member; a value keeps its
/// comments, stability flags and, for omega, its Campbell samples.
class TwoBallSweepStream {
 public:
  TwoBallSweepStream(ParamRef param, std::size_t values, const Params& base, std::string dry = {});
  void add(double value, const Analysis& a, const DryFigures& dry = {});
  /// Stages the long CSV; returns its staged path.
  std::filesystem::path stage(OutputTransaction& out, const std::filesystem::path& csv, std::string_view header);
  std::vector<CampbellSample> campbell();
  StabilityRanges ranges() const;
  std::size_t rows() const { return rows_; }

 private:
  using File = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;
  ParamRef param_;
  std::size_t count_;
  Params base_;
  std::string dry_;
  std::vector<File> spills_;  // balanced 1, 2, together 1, 2, opposite 1, 2
  std::vector<std::vector<CampbellSample>> samples_;  // the same order
  std::string comments_;
  std::vector<double> values_;
  std::vector<StableAt> stable_;
  std::size_t rows_ = 0;
};

}  // namespace abu
