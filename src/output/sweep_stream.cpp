#include "abu/output/sweep_stream.hpp"

#include "abu/output/report_dry_along.hpp"

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

// `cells` at the end of every line of `rows` (the dry_* columns; nothing when `cells` is empty).
std::string with_cells(const std::string& rows, const std::string& cells) {
  if (cells.empty()) return rows;
  std::string out;
  out.reserve(rows.size() + 8 * cells.size());
  for (const char c : rows) {
    if (c == '\n') out += cells;
    out += c;
  }
  return out;
}
// A column line with the dry_* names, led by their comment (when the sweep has them).
std::string columns_with_dry(const std::string& columns, const std::string& dry) {
  if (dry.empty()) return columns;
  return dry_columns_doc(dry) + with_cells(columns, dry_columns());
}

void spill(std::FILE* to, const std::string& rows, const std::string& name, double value) {
  if (std::fwrite(rows.data(), 1, rows.size(), to) != rows.size())
    throw std::runtime_error(fmt::format("sweep: writing the rows of {}={} to a temporary file failed", name, value));
}
}  // namespace

SweepStream::SweepStream(std::string name, std::string unit, std::size_t values, int n_max, bool campbell,
                         std::string dry)
    : name_(std::move(name)),
      unit_(std::move(unit)),
      count_(values),
      n_max_(n_max),
      campbell_(campbell),
      dry_(std::move(dry)),
      rows_(std::tmpfile(), &std::fclose) {
  if (!rows_) throw std::runtime_error("sweep: cannot create a temporary file for its rows");
}

void SweepStream::add(double value, const AnalysisN& a, const ParamsN& p, const DryFigures& dry) {
  const std::size_t step = values_.size();
  const std::string cells = dry_.empty() ? std::string() : dry_cells(dry);
  spill(rows_.get(), with_cells(sweep_value_rows(step, name_, value, a, n_max_), cells), name_, value);
  comments_ += sweep_value_comments(name_, value, a);
  summary_rows_ += with_cells(sweep_summary_row(step, name_, value, a), cells);
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
    file << sweep_head(name_, unit_, count_, header) << comments_ << columns_with_dry(sweep_columns(name_, n_max_), dry_);
    copy_into(rows_.get(), file);
    if (!file.flush())
      throw std::runtime_error(fmt::format("sweep: writing {} failed", staged_csv.string()));
  }
  // The summary's head ends with its column line: the dry_* names go there.
  std::string head = sweep_summary_head(name_, unit_, header);
  if (!dry_.empty()) {
    const std::size_t last = head.rfind('\n', head.size() - 2) + 1;
    head = head.substr(0, last) + columns_with_dry(head.substr(last), dry_);
  }
  const std::filesystem::path staged_summary = out.stage(summary, head + summary_rows_);
  return {staged_csv, staged_summary};
}

std::vector<CampbellSample> SweepStream::campbell() {
  sort_campbell_series(samples_);
  return samples_;
}

StabilityRanges SweepStream::ranges() const { return stability_ranges(values_, stable_); }

TwoBallSweepStream::TwoBallSweepStream(ParamRef param, std::size_t values, const Params& base, std::string dry)
    : param_(param), count_(values), base_(base), dry_(std::move(dry)), samples_(6) {
  for (int k = 0; k < 6; ++k) {
    spills_.emplace_back(std::tmpfile(), &std::fclose);
    if (!spills_.back()) throw std::runtime_error("sweep: cannot create a temporary file for its rows");
  }
}

void TwoBallSweepStream::add(double value, const Analysis& a, const DryFigures& dry) {
  const std::size_t step = values_.size();
  const std::string cells = dry_.empty() ? std::string() : dry_cells(dry);
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
    spill(spills_[which].get(), with_cells(sweep_row(step, param_, value, e, sp), cells), to_string(param_), value);
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
  file << sweep_head(param_, count_, header) << comments_ << columns_with_dry(sweep_columns(param_), dry_);
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
