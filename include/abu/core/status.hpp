// How a computation ended, as every result reports it (converged, not converged, numerical
// issue, with the reason), the way Ceres' Solver::Summary and Spectra's CompInfo do. The
// result's numbers are kept in every case: a not-converged equilibrium is still the best point
// Newton found, its residual printed.
//
//   abu::Spectrum sp = abu::compute_spectrum(lin);
//   if (!sp.status.ok()) fmt::print("{}: {}\n", to_string(sp.status.outcome), sp.status.reason);
//
// A reason outlives the function that formatted it: a string literal is kept by pointer (no
// allocation, so that results copied in hot loops — maps, the n-ball samples — allocate
// nothing, tests/alloc), any other text is owned (formatted once, shared by the copies).
#pragma once

#include <cstddef>
#include <iosfwd>
#include <memory>
#include <string>
#include <string_view>

namespace abu {

/// converged: the result meets its tolerance. not_converged: the iteration ended (out of
/// iterations, stalled above the tolerance) without meeting it. numerical_issue: it could
/// not be carried out (a non-finite value, a singular system, a library routine's error).
enum class Outcome { converged, not_converged, numerical_issue };
std::string_view to_string(Outcome o);  ///< "converged", "not converged", "numerical issue"

/// Why a computation did not converge: static text or an owned message. Reads as a
/// std::string_view (fmt prints it as one).
class Reason {
 public:
  Reason() = default;
  /// Static text: a string literal, kept by pointer.
  template <std::size_t N>
  Reason(const char (&literal)[N]) noexcept : text_(literal, N - 1) {}  // NOLINT: implicit by design
  /// Formatted text: owned, shared by the copies.
  Reason(std::string text)  // NOLINT: implicit by design
      : owned_(std::make_shared<const std::string>(std::move(text))), text_(*owned_) {}
  /// Any other text: copied.
  explicit Reason(std::string_view text) : Reason(std::string(text)) {}

  std::string_view view() const noexcept { return text_; }
  operator std::string_view() const noexcept { return text_; }  // NOLINT: implicit by design
  bool empty() const noexcept { return text_.empty(); }
  friend bool operator==(const Reason& a, std::string_view b) noexcept { return a.text_ == b; }

 private:
  std::shared_ptr<const std::string> owned_;
  std::string_view text_;
};
std::ostream& operator<<(std::ostream& out, const Reason& reason);

struct Status {
  Outcome outcome = Outcome::converged;
  Reason reason;  ///< why not converged; empty when converged

  bool ok() const { return outcome == Outcome::converged; }
  /// Keeps the first failure: a numerical issue outranks not converged, which outranks
  /// converged; among equals the earlier reason stays.
  void merge(Outcome o, Reason why) {
    if (int(o) > int(outcome)) outcome = o, reason = std::move(why);
  }
  void merge(const Status& other) { merge(other.outcome, other.reason); }
};

}  // namespace abu
