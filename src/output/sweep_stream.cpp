#include "abu/output/sweep_stream.hpp"

#include <fmt/format.h>

#include <fstream>
#include <stdexcept>

namespace abu {

namespace {
void copy_into(std::FILE* from, std::ofstream& to) {
  std::rewind(from);
  char buffer[1 << 16];
  for (std::size_t got; (got = std::fread(buffer, 1, sizeof buffer, from)) > 0;) to.write(buffer, long(got));
  if (std::ferror(from)) throw std::runtime_error("sweep: reading back a temporary file of its rows failed");
}

void spill(std::FILE* to, const std::string& rows, const std::string& name, double value) {
  if (std::fwrite(rows.data(), 1, rows.size(), to) != rows.size())
    throw std::runtime_error(fmt::format("sweep: writing the rows of {}={} to a temporary file failed", name, value));
}
}  // namespace

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
  spill(rows_.get(), sweep_value_rows(step, name_, value, a, n_max_), name_, value);
  comments_ += sweep_value_comments(name_, value, a);
  summary_rows_ += sweep_summary_row(step, name_, value, a);
  stable_.push_back(stable_at(a));
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
    copy_into(rows_.get(), file);
    if (!file.flush())
      throw std::runtime_error(fmt::format("sweep: writing {} failed", staged_csv.string()));
  }
  const std::filesystem::path staged_summary = out.stage(summary, sweep_summary_head(name_, unit_, header) + summary_rows_);
  return {staged_csv, staged_summary};
}

std::vector<CampbellSample> SweepStream::campbell() {
  sort_campbell_series(samples_);
  return samples_;
}

StabilityRanges SweepStream::ranges() const { return stability_ranges(values_, stable_); }

TwoBallSweepStream::TwoBallSweepStream(ParamRef param, std::size_t values, const Params& base)
    : param_(param), count_(values), base_(base), samples_(6) {
  for (int k = 0; k < 6; ++k) {
    spills_.emplace_back(std::tmpfile(), &std::fclose);
    if (!spills_.back()) throw std::runtime_error("sweep: cannot create a temporary file for its rows");
  }
}

void TwoBallSweepStream::add(double value, const Analysis& a) {
  const std::size_t step = values_.size();
  comments_ += sweep_value_comments(param_, value, a);
  Params p = base_;
  set(p, param_, value);
  const auto points = a.equilibria.points();
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Equilibrium& e = points[k];
    const Spectrum& sp = a.spectra[k];
    // The spill of its family and member (sweep_csv's order): balanced 1, 2, together 1, 2, ...
    const std::size_t which = 2 * std::size_t(e.family) + std::size_t(e.member - 1);
    if (which >= spills_.size()) throw std::logic_error("sweep: an equilibrium outside the three families' two members");
    spill(spills_[which].get(), sweep_row(step, param_, value, e, sp), to_string(param_), value);
    ++rows_;
    if (param_.quantity == Quantity::omega) samples_[which].push_back(campbell_sample(int(step), p, e, sp));
  }
  stable_.push_back(stable_at(a));
  values_.push_back(value);
}

std::filesystem::path TwoBallSweepStream::stage(OutputTransaction& out, const std::filesystem::path& csv,
                                                std::string_view header) {
  const std::filesystem::path staged = out.reserve_data(csv);
  std::ofstream file(staged, std::ios::binary | std::ios::trunc);
  file << sweep_head(param_, count_, header) << comments_ << sweep_columns(param_);
  for (const File& spill : spills_) copy_into(spill.get(), file);
  if (!file.flush()) throw std::runtime_error(fmt::format("sweep: writing {} failed", staged.string()));
  return staged;
}

std::vector<CampbellSample> TwoBallSweepStream::campbell() {
  std::vector<CampbellSample> all;
  for (auto& v : samples_) {
    all.insert(all.end(), std::make_move_iterator(v.begin()), std::make_move_iterator(v.end()));
    v.clear();
  }
  return all;
}

StabilityRanges TwoBallSweepStream::ranges() const { return stability_ranges(values_, stable_); }

}  // namespace abu
