#include "abu/output/sweep_stream.hpp"

#include <fmt/format.h>

#include <fstream>
#include <stdexcept>

namespace abu {

SweepStream::SweepStream(std::string name, std::string unit, std::size_t values, int n_max, bool campbell)
    : name_(std::move(name)),
      unit_(std::move(unit)),
      count_(values),
      n_max_(n_max),
      campbell_(campbell),
      rows_(std::tmpfile(), &std::fclose) {
  if (!rows_) throw std::runtime_error("sweep: cannot create a temporary file for its rows");
}

void SweepStream::add(double value, const AnalysisN& a, const ParamsN& p) {
  const std::size_t step = values_.size();
  const std::string rows = sweep_value_rows(step, name_, value, a, n_max_);
  if (std::fwrite(rows.data(), 1, rows.size(), rows_.get()) != rows.size())
    throw std::runtime_error(fmt::format("sweep: writing the rows of {}={} to a temporary file failed", name_, value));
  comments_ += sweep_value_comments(name_, value, a);
  summary_rows_ += sweep_summary_row(step, name_, value, a);
  // Stability flags as stability_ranges takes them from a whole sweep (report_ranges.cpp).
  bool balanced = false, some = false;
  const auto points = a.equilibria.points();
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (a.spectra[k].stability != Stability::stable) continue;
    some = true;
    if (points[k].family == Family::balanced || points[k].on_balanced_set) balanced = true;
  }
  balanced_stable_.push_back(balanced);
  some_stable_.push_back(some);
  if (campbell_) append_campbell_samples(samples_, int(step), p, a);
  values_.push_back(value);
}

std::pair<std::filesystem::path, std::filesystem::path> SweepStream::stage(OutputTransaction& out,
                                                                           const std::filesystem::path& csv,
                                                                           const std::filesystem::path& summary,
                                                                           std::string_view header) {
  const std::filesystem::path staged_csv = out.reserve_data(csv);
  {
    std::ofstream file(staged_csv, std::ios::binary | std::ios::trunc);
    file << sweep_head(name_, unit_, count_, header) << comments_ << sweep_columns(name_, n_max_);
    std::rewind(rows_.get());
    char buffer[1 << 16];
    for (std::size_t got; (got = std::fread(buffer, 1, sizeof buffer, rows_.get())) > 0;) file.write(buffer, long(got));
    if (std::ferror(rows_.get()) || !file.flush())
      throw std::runtime_error(fmt::format("sweep: writing {} failed", staged_csv.string()));
  }
  const std::filesystem::path staged_summary = out.stage(summary, sweep_summary_head(name_, unit_, header) + summary_rows_);
  return {staged_csv, staged_summary};
}

std::vector<CampbellSample> SweepStream::campbell() {
  sort_campbell_series(samples_);
  return samples_;
}

StabilityRanges SweepStream::ranges() const {
  std::vector<bool> none(some_stable_.size());
  for (std::size_t i = 0; i < none.size(); ++i) none[i] = !some_stable_[i];
  return {grid_ranges(values_, balanced_stable_), grid_ranges(values_, none), grid_ranges(values_, some_stable_)};
}

}  // namespace abu
