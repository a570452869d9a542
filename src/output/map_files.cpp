// The files of a stability map (map_files.hpp).
#include "abu/output/map_files.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <streambuf>

#include "abu/core/temp_files.hpp"
#include "abu/output/files.hpp"
#include "abu/output/format.hpp"
#include "abu/output/gnuplot.hpp"
#include "abu/output/provenance.hpp"
#include "abu/output/report.hpp"

namespace abu {

namespace fs = std::filesystem;

std::string map_provenance(const MapJob& job, std::string_view scene_file) {
  const std::string block = job.any_balls || job.stick_set ? provenance_header(job.command_line, scene_file, job.params_n)
                                                           : provenance_header(job.command_line, scene_file, job.params);
  return block + job.provenance_notes;
}

namespace {

// plots/map.gp's qfloor: a stable state with |q| at or below it [m] counts as balanced
// (|q| = 0) and gets its own colour.
constexpr double kChartZeroQ = 1e-15;

// One pixel of the heat maps, as plots/map.gp reads grid_file: category, |q| of the best
// stable state where it is above kChartZeroQ (else NaN), balanced_stable_fraction (NaN
// where there is no balanced state or no sample), 255 where a state with |q| <= kChartZeroQ
// is stable (else 0; the white overlay's r = g = b = alpha).
struct ChartPixel {
  double category, vibration, fraction, zero;
};

// Takes the tiles' grid blocks (MapCellFacts records, in the summary's order) as they are
// assembled: writes the chart's pixels to `fd` (if >= 0), finds the range of |q| above
// kChartZeroQ, and records the speed ranges' verdicts (if `verdicts`). Streams: a fixed
// buffer, whatever the map's size.
class GridSink : public std::streambuf {
 public:
  GridSink(int fd, fs::path path, MapVerdicts* verdicts) : fd_(fd), path_(std::move(path)), verdicts_(verdicts) {}
  long records() const { return records_; }
  double qlo = std::numeric_limits<double>::infinity(), qhi = 0;
  bool low = false;
  void flush_pixels() {
    std::string_view left(pixels_.data(), pixels_.size());
    while (!left.empty()) {
      const ssize_t n = ::write(fd_, left.data(), left.size());
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0)
        throw std::runtime_error(
            fmt::format("{}: cannot write: {}", path_.string(), std::strerror(n < 0 ? errno : ENOSPC)));
      left.remove_prefix(std::size_t(n));
    }
    pixels_.clear();
  }

 protected:
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    for (std::streamsize k = 0; k < n;) {
      const std::size_t take = std::min(sizeof partial_ - filled_, std::size_t(n - k));
      std::memcpy(partial_ + filled_, s + k, take);
      filled_ += take;
      k += std::streamsize(take);
      if (filled_ == sizeof partial_) {
        MapCellFacts facts;
        std::memcpy(&facts, partial_, sizeof facts);
        record(facts);
        filled_ = 0;
      }
    }
    return n;
  }
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    const char ch = traits_type::to_char_type(c);
    xsputn(&ch, 1);
    return c;
  }

 private:
  void record(const MapCellFacts& f) {
    const double q = f.best_q_abs;
    const bool stable = !std::isnan(q);
    if (stable && q > kChartZeroQ) {
      qlo = std::min(qlo, q);
      qhi = std::max(qhi, q);
    } else if (stable) {
      low = true;
    }
    if (verdicts_)
      verdicts_->cells.push_back(std::uint8_t((f.category == 3 ? MapVerdicts::balanced_stable : 0) |
                                              (stable ? MapVerdicts::some_stable : 0)));
    ++records_;
    if (fd_ < 0) return;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const ChartPixel pixel{f.category, stable && q > kChartZeroQ ? q : nan,
                           f.category == 0 ? nan : f.balanced_stable_fraction, stable && q <= kChartZeroQ ? 255.0 : 0.0};
    const char* bytes = reinterpret_cast<const char*>(&pixel);
    pixels_.append(bytes, bytes + sizeof pixel);
    if (pixels_.size() >= (std::size_t(1) << 20)) flush_pixels();
  }
  int fd_;
  fs::path path_;
  MapVerdicts* verdicts_;
  char partial_[sizeof(MapCellFacts)] = {};
  std::size_t filled_ = 0;
  long records_ = 0;
  fmt::memory_buffer pixels_;
};

// The chart's grid file: a registered temporary in the output directory, removed when done.
class GridFile {
 public:
  explicit GridFile(const fs::path& target) { path_ = create_temporary_next_to(target, "grid", fd_); }
  ~GridFile() {
    if (fd_ >= 0) ::close(fd_);
    ::unlink(path_.c_str());
    unregister_temporary(path_);
  }
  GridFile(const GridFile&) = delete;
  GridFile& operator=(const GridFile&) = delete;
  int fd() const { return fd_; }
  const fs::path& path() const { return path_; }
  void close() {
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0)
      throw std::runtime_error(fmt::format("{}: cannot write: {}", path_.string(), std::strerror(errno)));
  }

 private:
  fs::path path_;
  int fd_ = -1;
};

// The heat maps of a stick-set map (plots/stick_set_map.gp, from the summary).
void draw_stick_charts(OutputTransaction& out, const MapJob& job, const fs::path& dir, const fs::path& summary,
                       const std::string& title) {
  const std::string x = job.x.name(), y = job.y.name();
  const auto name = [&](const char* kind) { return out.reserve(dir / fmt::format("{}_{}_{}.png", kind, x, y)).string(); };
  run_gnuplot(plots_dir() / "stick_set_map.gp", {{"summary", summary.string()},
                                                  {"png_worst", name("stick_worst")},
                                                  {"png_area", name("stick_area")},
                                                  {"xname", x},
                                                  {"xunit", std::string(unit(job.x.param.quantity))},
                                                  {"yname", y},
                                                  {"yunit", std::string(unit(job.y.param.quantity))},
                                                  {"logx", job.x.logarithmic ? "1" : "0"},
                                                  {"logy", job.y.logarithmic ? "1" : "0"},
                                                  {"title", title}});
}

// The heat maps of a two-ball or n-ball map (plots/map.gp): from `grid` (its pixels and
// |q| range) when the map is a grid, else from the summary.
void draw_map_charts(OutputTransaction& out, const MapJob& job, const fs::path& dir, const fs::path& summary,
                     const fs::path& curves, const GridFile* grid, const GridSink& sink, const std::string& title) {
  const std::string x = job.x.name(), y = job.y.name();
  const auto name = [&](const char* kind, const char* ext) {
    return out.reserve(dir / fmt::format("{}_{}_{}.{}", kind, x, y, ext)).string();
  };
  const auto axis_unit = [](const Axis& a) { return a.ball_count ? std::string() : std::string(unit(a.param.quantity)); };
  std::vector<std::pair<std::string, std::string>> variables{{"summary", summary.string()},
                                                             {"curves", curves.string()},
                                                             {"png_stability", name("stability", "png")},
                                                             {"svg_stability", name("stability", "svg")},
                                                             {"png_vibration", name("vibration", "png")},
                                                             {"svg_vibration", name("vibration", "svg")},
                                                             {"xname", x},
                                                             {"xunit", axis_unit(job.x)},
                                                             {"yname", y},
                                                             {"yunit", axis_unit(job.y)},
                                                             {"logx", job.x.logarithmic ? "1" : "0"},
                                                             {"logy", job.y.logarithmic ? "1" : "0"},
                                                             {"title", title}};
  if (job.any_balls) {
    variables.emplace_back("nballs", "1");
    variables.emplace_back("png_fraction", name("fraction", "png"));
    variables.emplace_back("svg_fraction", name("fraction", "svg"));
  }
  if (grid) {
    // The geometry and the |q| range the script would otherwise read from the summary, with
    // 17 digits and a decimal point (gnuplot reads "1e-05" as 1 and trailing characters).
    const auto value = [](double v) {
      (void)format_number(v, "a chart's value");  // no NaN reaches gnuplot either
      return fmt::format("{:.16e}", v);
    };
    for (auto [key, v] : {std::pair{"grid_x0", job.x.value(0)}, {"grid_x1", job.x.value(job.x.count - 1)},
                          {"grid_y0", job.y.value(0)}, {"grid_y1", job.y.value(job.y.count - 1)}})
      variables.emplace_back(key, value(v));
    variables.emplace_back("grid_file", grid->path().string());
    variables.emplace_back("grid_nx", std::to_string(job.x.count));
    variables.emplace_back("grid_ny", std::to_string(job.y.count));
    variables.emplace_back("grid_qlo", value(sink.qhi > 0 ? sink.qlo : 1e300));  // the script's "none" value
    variables.emplace_back("grid_qhi", value(sink.qhi));
    variables.emplace_back("grid_low", sink.low ? "1" : "0");
  }
  run_gnuplot(plots_dir() / "map.gp", variables);
}

}  // namespace

MapFilesReport write_map_files(const MapJob& job, const MapRunReport& run, const MapFilesOptions& options) {
  MapFilesReport report;
  const TileStore& store = *run.store;
  const fs::path& dir = options.directory;
  const std::string x = job.x.name(), y = job.y.name();
  OutputTransaction out;
  // The long CSV (a row per equilibrium per cell: ~800 bytes a cell) only on request.
  const auto map_path = job.long_rows ? out.reserve_data(dir / map_file_name(job)) : fs::path();
  const auto summary_path = out.reserve_data(dir / summary_file_name(job));
  const bool image = options.chart && !job.stick_set && job.x.count > 1 && job.y.count > 1;
  std::optional<GridFile> grid;
  if (image) grid.emplace(dir / fmt::format("grid_{}_{}.bin", x, y));
  const bool ranges = !job.any_balls && !job.stick_set && (x == "omega" || y == "omega");
  if (ranges) {
    for (int i = 0; i < job.x.count; ++i) report.verdicts.x.push_back(job.x.value(i));
    for (int i = 0; i < job.y.count; ++i) report.verdicts.y.push_back(job.y.value(i));
    report.verdicts.cells.reserve(std::size_t(job.x.count) * std::size_t(job.y.count));
  }
  GridSink sink(grid ? grid->fd() : -1, grid ? grid->path() : fs::path(), ranges ? &report.verdicts : nullptr);
  {
    std::ofstream summary_csv(summary_path, std::ios::binary);
    std::ofstream map_csv;
    std::ostream no_rows(nullptr);  // discards what is written to it
    if (job.long_rows) map_csv.open(map_path, std::ios::binary);
    std::ostream& rows = job.long_rows ? static_cast<std::ostream&>(map_csv) : no_rows;
    std::ostream facts(&sink);
    try {
      assemble(job, store, rows, summary_csv, job.stick_set ? nullptr : &facts);
      if (grid) {
        sink.flush_pixels();
        grid->close();
      }
    } catch (const std::exception& e) {
      throw std::runtime_error(fmt::format("{}; the tiles are kept in {}, rerun the same command with --resume",
                                           e.what(), escaped(store.directory().string())));
    }
    summary_csv.close();
    if (job.long_rows) map_csv.close();
    if ((job.long_rows && !map_csv) || !summary_csv)
      throw std::runtime_error(fmt::format("{}: cannot write the map: {}; the tiles are kept in {}, rerun the same "
                                           "command with --resume",
                                           escaped(dir.string()), errno ? std::strerror(errno) : "write error",
                                           escaped(store.directory().string())));
    const long cells = long(job.x.count) * long(job.y.count);
    if (!job.stick_set && sink.records() != cells)
      throw std::runtime_error(fmt::format("{}: the tiles hold {} cells' grid records of {}; rerun with --fresh",
                                           escaped(store.directory().string()), sink.records(), cells));
  }
  fs::path curves;
  if (run.boundaries)
    curves = out.stage(dir / fmt::format("boundary_{}_{}.csv", x, y), boundary_csv(*run.boundaries, job.provenance));
  else if (run.boundaries_n)
    curves = out.stage(dir / fmt::format("boundary_{}_{}.csv", x, y), boundary_csv(*run.boundaries_n, job.provenance));
  if (options.chart && job.stick_set)
    draw_stick_charts(out, job, dir, summary_path, options.title);
  else if (options.chart)
    draw_map_charts(out, job, dir, summary_path, curves, grid ? &*grid : nullptr, sink, options.title);
  if (options.stop && options.stop->load()) return report;  // `out` removes its temporaries
  // An earlier map of the same axes in this directory: what this run does not write again
  // would stand beside its summary as if it belonged to it.
  for (const char* kind : {"map", "boundary"}) out.retire(dir / fmt::format("{}_{}_{}.csv", kind, x, y));
  for (const char* kind : {"stability", "vibration"})
    for (const char* ext : {"png", "svg"}) out.retire(dir / fmt::format("{}_{}_{}.{}", kind, x, y, ext));
  for (const char* kind : {"stick_worst", "stick_area"}) out.retire(dir / fmt::format("{}_{}_{}.png", kind, x, y));
  out.commit();
  store.remove();
  report.written = true;
  return report;
}

}  // namespace abu
